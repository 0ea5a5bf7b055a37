#include "hotmesh/mesh/validate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

#include <fmt/format.h>

#include "hotmesh/mesh/mesh_topology.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

namespace hotmesh::mesh {
namespace {

constexpr std::size_t kExamples = 5;

std::string point_text(const Vec3& p) { return fmt::format("({:.9g}, {:.9g}, {:.9g})", p.x, p.y, p.z); }

std::string node_text(const Mesh& mesh, NodeId n) {
  return fmt::format("node {} at {}", mesh.node_id(n), point_text(mesh.points[static_cast<std::size_t>(n)]));
}

std::string cell_text(const Mesh& mesh, CellId c) {
  return fmt::format("cell {} ({})", mesh.cell_id(c), name(mesh.cells.type(static_cast<std::size_t>(c))));
}

std::string node_list(const Mesh& mesh, std::span<const NodeId> nodes) {
  std::string s;
  for (NodeId n : nodes) s += (s.empty() ? "" : ", ") + std::to_string(mesh.node_id(n));
  return s;
}

/// Collects instances of one kind of problem and throws them as one message.
class Problems {
 public:
  explicit Problems(std::string what) : what_(std::move(what)) {}
  void add(std::string example) {
    if (examples_.size() < kExamples) examples_.push_back(std::move(example));
    ++count_;
  }
  /// Counts one more instance; `example` is called only while examples are still wanted.
  template <class Example>
  void add_lazily(Example&& example) {
    if (examples_.size() < kExamples) examples_.push_back(example());
    ++count_;
  }
  std::size_t count() const { return count_; }
  /// The count stops here: the message says "N or more".
  void stop_counting() { stopped_ = true; }
  void raise_if_any(std::string_view advice = {}) const {
    if (count_ == 0) return;
    std::string text = fmt::format("{}{} {}:", count_, stopped_ ? " or more" : "", what_);
    for (const auto& e : examples_) text += "\n  " + e;
    if (count_ > examples_.size()) text += fmt::format("\n  ... and {} more", count_ - examples_.size());
    if (!advice.empty()) text += fmt::format("\n{}", advice);
    throw InputError(text);
  }

 private:
  std::string what_;
  std::vector<std::string> examples_;
  std::size_t count_ = 0;
  bool stopped_ = false;
};

bool node_in_range(const Mesh& mesh, NodeId n) {
  return n >= 0 && static_cast<std::size_t>(n) < mesh.node_count();
}

void check_structure(const Mesh& mesh) {
  if (mesh.dimension != 2 && mesh.dimension != 3) {
    throw InputError(fmt::format("the mesh has dimension {}; hotmesh handles 2D and 3D meshes", mesh.dimension));
  }
  if (mesh.cells.empty()) throw InputError(fmt::format("the mesh has no {}D cells", mesh.dimension));

  Problems wrong_dimension(fmt::format("cells are not {}D cells", mesh.dimension));
  Problems missing(fmt::format("cells refer to nodes that do not exist (the mesh has {} nodes)", mesh.node_count()));
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    const auto cell = static_cast<CellId>(c);
    if (dimension(mesh.cells.type(c)) != mesh.dimension) wrong_dimension.add(cell_text(mesh, cell));
    for (NodeId n : mesh.cells.nodes(c)) {
      if (!node_in_range(mesh, n)) missing.add(fmt::format("{} refers to node index {}", cell_text(mesh, cell), n));
    }
  }
  wrong_dimension.raise_if_any();
  missing.raise_if_any();

  Problems bad_faces("patch faces are not faces of the mesh's cells or refer to missing nodes");
  for (const Patch& patch : mesh.patches) {
    for (std::size_t f = 0; f < patch.faces.size(); ++f) {
      if (dimension(patch.faces.type(f)) != mesh.dimension - 1) {
        bad_faces.add(fmt::format("patch '{}' face {} is a {} in a {}D mesh", patch.name, f + 1,
                                  name(patch.faces.type(f)), mesh.dimension));
      }
      for (NodeId n : patch.faces.nodes(f)) {
        if (!node_in_range(mesh, n)) {
          bad_faces.add(fmt::format("patch '{}' face {} refers to missing node index {} (the mesh has {} nodes)",
                                    patch.name, f + 1, n, mesh.node_count()));
        }
      }
    }
  }
  bad_faces.raise_if_any();
}

/// The mesh's size (largest extent along an axis) and distance from the origin must lie
/// where double precision can compute its motion (kSmallestMeshSize, kLargestCoordinate,
/// kSmallestRelativeSize); outside, the duplicate-node and stiffness checks would report
/// nonsense ("closer than inf", "not positive definite").
void check_coordinate_range(const Mesh& mesh) {
  if (mesh.node_count() < 2) return;
  Vec3 lo = mesh.points.front();
  Vec3 hi = lo;
  for (const Vec3& p : mesh.points) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  double size = 0.0;
  double reach = 0.0;
  for (int a = 0; a < 3; ++a) {
    size = std::max(size, hi[a] - lo[a]);  // no square: finite for any finite coordinates
    reach = std::max({reach, std::abs(lo[a]), std::abs(hi[a])});
  }
  const std::string unit_hint = "the mesh's coordinates are taken in the case's length_unit: is the mesh in "
                                "another unit, or were its coordinates written wrongly?";
  if (reach > kLargestCoordinate) {
    throw InputError(fmt::format("the mesh reaches {:.3g} from the origin: hotmesh moves meshes whose coordinates "
                                 "stay within {:.0e} (double precision cannot hold the stiffness of larger ones); {}",
                                 reach, kLargestCoordinate, unit_hint));
  }
  if (size == 0.0) {
    throw InputError(fmt::format("all {} nodes of the mesh are at the same point {}", mesh.node_count(),
                                 point_text(mesh.points.front())));
  }
  if (size < kSmallestMeshSize) {
    throw InputError(fmt::format("the mesh is {:.3g} across: hotmesh moves meshes at least {:.0e} across (double "
                                 "precision cannot hold the stiffness of smaller ones); {}",
                                 size, kSmallestMeshSize, unit_hint));
  }
  if (size < kSmallestRelativeSize * reach) {
    throw InputError(fmt::format("the mesh is {:.3g} across but lies {:.3g} from the origin: its coordinates keep "
                                 "fewer than 6 digits of its size; move it nearer the origin",
                                 size, reach));
  }
}

void check_coordinates(const Mesh& mesh) {
  Problems non_finite("nodes have non-finite coordinates");
  for (std::size_t n = 0; n < mesh.node_count(); ++n) {
    if (!geometry::is_finite(mesh.points[n])) non_finite.add(node_text(mesh, static_cast<NodeId>(n)));
  }
  non_finite.raise_if_any();
  check_coordinate_range(mesh);
  if (mesh.dimension != 2) return;
  const double z0 = mesh.points.front().z;
  const double tolerance = 1e-9 * std::max(bounding_diagonal(mesh.points), 1e-300);
  Problems off_plane(fmt::format("nodes of this 2D mesh are off the plane z = {:.9g} of its first node", z0));
  for (std::size_t n = 0; n < mesh.node_count(); ++n) {
    if (std::abs(mesh.points[n].z - z0) > tolerance) off_plane.add(node_text(mesh, static_cast<NodeId>(n)));
  }
  off_plane.raise_if_any("2D meshes must lie in the x-y plane (one constant z).");
}

void check_patch_names(const Mesh& mesh) {
  Problems duplicates("patch names are used twice");
  for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
    for (std::size_t j = i + 1; j < mesh.patches.size(); ++j) {
      if (mesh.patches[i].name == mesh.patches[j].name) {
        duplicates.add(fmt::format("'{}' names groups {} and {}", mesh.patches[i].name,
                                   mesh.patches[i].tag, mesh.patches[j].tag));
      }
    }
  }
  duplicates.raise_if_any("Every patch needs its own name: the case file assigns roles by name.");
}

void check_unused_nodes(const Mesh& mesh) {
  std::vector<char> used(mesh.node_count(), 0);
  for (NodeId n : mesh.cells.all_nodes()) used[static_cast<std::size_t>(n)] = 1;
  Problems unused("nodes are not used by any cell");
  for (std::size_t n = 0; n < used.size(); ++n) {
    if (!used[n]) unused.add(node_text(mesh, static_cast<NodeId>(n)));
  }
  unused.raise_if_any("Remove them (in Gmsh: Mesh.SaveAll = 0, or Coherence Mesh) and load the mesh again.");
}

/// Duplicate pairs counted before the check stops: nodes crowded into a few grid cells (one
/// node far from the others makes the tolerance as large as the mesh) have pairs, and
/// comparisons, by the square of their number.
constexpr std::size_t kCountedDuplicatePairs = 100'000;

/// Duplicates are found with a hash grid of cell size q = 2 * tolerance: a node within the
/// tolerance of node p lies, along each axis, in p's grid cell or in the neighbour on the
/// side of p's nearer cell wall, so 2^d cells are searched per node.
void check_duplicate_nodes(const Mesh& mesh, double relative_tolerance) {
  const double diagonal = bounding_diagonal(mesh.points);
  if (mesh.node_count() < 2) return;
  const double tolerance = relative_tolerance * diagonal;  // > 0: check_coordinate_range
  const double q = 2.0 * tolerance;
  using Key = std::array<std::int64_t, 3>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      auto h = static_cast<std::uint64_t>(k[0]) * 0x9E3779B97F4A7C15ull;
      h ^= static_cast<std::uint64_t>(k[1]) + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
      h ^= static_cast<std::uint64_t>(k[2]) + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
      return static_cast<std::size_t>(h);
    }
  };
  std::unordered_map<Key, NodeId, KeyHash> first;  // first node of each grid cell
  std::vector<NodeId> next(mesh.node_count(), -1);  // further nodes of the same grid cell
  first.reserve(mesh.node_count());
  const Vec3 origin = mesh.points.front();
  auto key_of = [&](const Vec3& p, Key& key, std::array<int, 3>& side) {
    for (int a = 0; a < 3; ++a) {
      const double s = (p[a] - origin[a]) / q;
      const double f = std::floor(s);
      key[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(f);
      side[static_cast<std::size_t>(a)] = (s - f) < 0.5 ? -1 : 1;
    }
  };
  for (std::size_t n = 0; n < mesh.node_count(); ++n) {
    Key key{};
    std::array<int, 3> side{};
    key_of(mesh.points[n], key, side);
    auto [it, inserted] = first.try_emplace(key, static_cast<NodeId>(n));
    if (!inserted) {
      next[n] = it->second;
      it->second = static_cast<NodeId>(n);
    }
  }
  Problems duplicates(fmt::format("pairs of nodes are duplicates (closer than {:.3g})", tolerance));
  for (std::size_t n = 0; n < mesh.node_count(); ++n) {
    if (duplicates.count() >= kCountedDuplicatePairs) {
      duplicates.stop_counting();
      break;
    }
    Key key{};
    std::array<int, 3> side{};
    key_of(mesh.points[n], key, side);
    for (int corner = 0; corner < 8; ++corner) {
      Key k = key;
      for (std::size_t a = 0; a < 3; ++a) {
        if (corner & (1 << a)) k[a] += side[a];
      }
      const auto it = first.find(k);
      if (it == first.end()) continue;
      for (NodeId m = it->second; m >= 0; m = next[static_cast<std::size_t>(m)]) {
        if (static_cast<std::size_t>(m) <= n) continue;  // report each pair once
        if (distance(mesh.points[n], mesh.points[static_cast<std::size_t>(m)]) <= tolerance) {
          duplicates.add_lazily([&] {
            return fmt::format("{} and node {}", node_text(mesh, static_cast<NodeId>(n)), mesh.node_id(m));
          });
        }
      }
    }
  }
  duplicates.raise_if_any("Merge them (in Gmsh: Coherence Mesh) so neighbouring cells share their nodes.");
}

std::size_t orient_cells(Mesh& mesh) {
  const std::size_t n = mesh.cells.size();
  std::vector<Orientation> orientations(n);
#pragma omp parallel for schedule(static) if (static_cast<std::ptrdiff_t>(n) >= kParallelCells)
  for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(n); ++c) {
    const auto i = static_cast<std::size_t>(c);
    orientations[i] = orientation(mesh.cells.type(i), gather(mesh.cells.nodes(i), mesh.points));
  }
  Problems folded("cells are folded or degenerate (a corner Jacobian <= 0)");
  std::size_t reoriented = 0;
  for (std::size_t c = 0; c < n; ++c) {
    if (orientations[c] == Orientation::folded) {
      const double q = scaled_jacobian(mesh.cells.type(c), gather(mesh.cells.nodes(c), mesh.points));
      folded.add(fmt::format("{} with nodes {} has scaled Jacobian {:.3g}", cell_text(mesh, static_cast<CellId>(c)),
                             node_list(mesh, mesh.cells.nodes(c)), q));
    }
  }
  folded.raise_if_any();
  for (std::size_t c = 0; c < n; ++c) {
    if (orientations[c] != Orientation::reversed) continue;
    const auto nodes = mesh.cells.nodes(c);
    std::array<NodeId, kMaxElementNodes> old{};
    std::copy(nodes.begin(), nodes.end(), old.begin());
    const auto permutation = reversal(mesh.cells.type(c));
    for (std::size_t i = 0; i < nodes.size(); ++i) nodes[i] = old[permutation[i]];
    ++reoriented;
  }
  return reoriented;
}

std::string face_text(const Mesh& mesh, CellFace f) {
  const FaceNodes fn = face_nodes(mesh.cells, f);
  return fmt::format("face (nodes {}) of {}", node_list(mesh, fn.view()), cell_text(mesh, f.cell));
}

void check_patches_cover_boundary(const Mesh& mesh, const FaceIndex& index, const FaceTopology& topology,
                                  ValidationReport& report) {
  std::vector<std::uint8_t> covered(mesh.cell_count(), 0);  // bit f: face f is in a patch
  Problems stray("patch faces are not faces of any cell");
  for (const Patch& patch : mesh.patches) {
    if (patch.faces.empty()) report.notes.push_back(fmt::format("patch '{}' has no faces", patch.name));
    for (std::size_t f = 0; f < patch.faces.size(); ++f) {
      const auto matches = index.find(patch.faces.nodes(f));
      if (matches.empty()) {
        stray.add(fmt::format("patch '{}' face {} (nodes {})", patch.name, f + 1, node_list(mesh, patch.faces.nodes(f))));
      } else if (matches.size() == 1) {
        covered[static_cast<std::size_t>(matches[0].cell)] |= static_cast<std::uint8_t>(1u << matches[0].local);
      } else {
        ++report.interior_patch_faces;
      }
    }
  }
  stray.raise_if_any();
  Problems uncovered("boundary faces are not in any patch");
  for (const CellFace& f : topology.boundary) {
    if (!(covered[static_cast<std::size_t>(f.cell)] & (1u << f.local))) uncovered.add(face_text(mesh, f));
  }
  uncovered.raise_if_any(
      "Every boundary face needs a patch (a named physical group) so that it gets a role in the case file.");
  if (report.interior_patch_faces > 0) {
    report.notes.push_back(fmt::format("{} patch faces lie between two cells (internal surfaces)",
                                       report.interior_patch_faces));
  }
}

}  // namespace

ValidationReport validate_mesh(Mesh& mesh, const ValidationOptions& options) {
  ValidationReport report;
  check_structure(mesh);
  check_coordinates(mesh);
  check_patch_names(mesh);
  check_unused_nodes(mesh);
  check_duplicate_nodes(mesh, options.duplicate_tolerance);
  report.reoriented_cells = orient_cells(mesh);

  const FaceIndex index(mesh.cells, mesh.node_count());
  const FaceTopology topology = face_topology(index);
  Problems non_manifold("faces are shared by more than two cells");
  for (const CellFace& f : topology.non_manifold) non_manifold.add(face_text(mesh, f));
  non_manifold.raise_if_any();
  Problems inconsistent("faces are shared by two cells lying on the same side of them (folded or overlapping cells)");
  for (const CellFace& f : topology.inconsistent) inconsistent.add(face_text(mesh, f));
  inconsistent.raise_if_any();

  report.boundary_faces = topology.boundary.size();
  check_patches_cover_boundary(mesh, index, topology, report);
  if (report.reoriented_cells > 0) {
    report.notes.push_back(fmt::format("{} of {} cells were numbered the other way round and have been reoriented",
                                       report.reoriented_cells, mesh.cell_count()));
  }
  mesh.derive_node_sets();
  return report;
}

}  // namespace hotmesh::mesh
