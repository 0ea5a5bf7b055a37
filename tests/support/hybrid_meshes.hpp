// hotmesh tests: hybrid meshes made by gmsh (a required test dependency) from
// tests/data/gmsh/hybrid_box.geo (tet4, pyramid5, wedge6 and hex8 cells; triangle and quad
// patches) and hybrid_plate.geo (tri3 and quad4 cells), and what to check of every reader's
// result: each cell type present, every cell positively oriented.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::test {

/// Meshes tests/data/gmsh/<name>.geo in `dimension` with gmsh into `dir`/<name>.msh, in
/// gmsh's `format` (msh41, msh22 for gmshToFoam, ...). Fails the test if gmsh fails.
inline std::filesystem::path hybrid_msh(const std::string& name, int dimension, const std::filesystem::path& dir,
                                        const std::string& format = "msh41") {
  const auto out = dir / (name + "-" + format + ".msh");
  const auto r = run_command("gmsh -" + std::to_string(dimension) + " -nt 1 " +
                             shell_quote(data_path("gmsh/" + name + ".geo").string()) + " -format " + format + " -o " +
                             shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 0) << "gmsh is a required test dependency (scripts/install-deps.sh):\n" << r.output;
  return out;
}

/// How many elements of each type a list holds.
inline std::map<mesh::ElementType, std::size_t> type_counts(const mesh::ElementList& elements) {
  std::map<mesh::ElementType, std::size_t> counts;
  for (const mesh::ElementType t : elements.types()) ++counts[t];
  return counts;
}

/// Every cell has all its corner Jacobians positive (the node order is right-handed).
inline void expect_positively_oriented(const mesh::Mesh& m) {
  std::size_t wrong = 0;
  for (std::size_t c = 0; c < m.cell_count(); ++c) {
    const auto o = mesh::orientation(m.cells.type(c), mesh::gather(m.cells.nodes(c), m.points));
    if (o != mesh::Orientation::positive && wrong++ < 5) {
      ADD_FAILURE() << "cell " << c << " (" << mesh::name(m.cells.type(c)) << ") is not positively oriented";
    }
  }
  EXPECT_EQ(wrong, 0u);
}

/// Each element as its type and node coordinates in element order, the list sorted: meshes
/// equal up to the numbering of nodes and the order of elements compare equal, and a cell
/// whose nodes come in another order does not.
using ElementShape = std::pair<mesh::ElementType, std::vector<std::array<double, 3>>>;
inline std::vector<ElementShape> element_shapes(const mesh::ElementList& elements,
                                                const std::vector<geometry::Vec3>& points) {
  std::vector<ElementShape> shapes;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    ElementShape s{elements.type(e), {}};
    for (const mesh::NodeId n : elements.nodes(e)) {
      const geometry::Vec3& p = points[static_cast<std::size_t>(n)];
      s.second.push_back({p.x, p.y, p.z});
    }
    shapes.push_back(std::move(s));
  }
  std::sort(shapes.begin(), shapes.end());
  return shapes;
}

/// The same with each element's nodes sorted too (for faces whose first node may differ).
inline std::vector<ElementShape> element_node_sets(const mesh::ElementList& elements,
                                                   const std::vector<geometry::Vec3>& points) {
  std::vector<ElementShape> shapes = element_shapes(elements, points);
  for (ElementShape& s : shapes) std::sort(s.second.begin(), s.second.end());
  std::sort(shapes.begin(), shapes.end());
  return shapes;
}

}  // namespace hotmesh::test
