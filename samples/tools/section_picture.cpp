// hotmesh sample tool: pictures of a meridional section of a 3D mesh of revolution, such as the
// periodic face of a sector (the paper's Figs. 15 and 17 show the stator well this way).
//
// Run:   build/samples/tools/section_picture MESH.msh OUT.png [--patch per_lo] [--mm]
//            [--outline REFERENCE.msh] [--view NAME=ZMIN,ZMAX,RMIN,RMAX]... [--title TEXT]
// The faces of the patch (quads or triangles) are taken to (z, r) about the z axis and drawn,
// each filled by the scaled Jacobian of the 3D cell it bounds. OUT.png shows the whole section;
// each --view adds OUT-NAME.png, a close-up of the window given (in the units drawn). --mm draws
// a mesh in metres in millimetres. --outline draws the boundary of the same patch of another
// mesh (e.g. the undeformed one) in blue over it.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/mesh/mesh_topology.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/geometry/input_error.hpp"
#include "hotmesh/io/figure.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/io/mesh_picture.hpp"

namespace {

using hotmesh::mesh::Mesh;
using hotmesh::mesh::NodeId;

struct View {
  std::string name;
  double zmin, zmax, rmin, rmax;
};

struct Options {
  std::filesystem::path mesh, out, outline;
  std::string patch = "per_lo", title;
  double scale = 1.0;
  std::string unit = "m";
  std::vector<View> views;
};

View parse_view(const std::string& text) {
  const auto eq = text.find('=');
  View v{text.substr(0, eq), 0, 0, 0, 0};
  if (eq == std::string::npos || std::sscanf(text.c_str() + eq + 1, "%lf,%lf,%lf,%lf", &v.zmin, &v.zmax, &v.rmin, &v.rmax) != 4) {
    throw hotmesh::InputError("--view expects NAME=ZMIN,ZMAX,RMIN,RMAX, got '" + text + "'");
  }
  return v;
}

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&] {
      if (i + 1 >= argc) throw hotmesh::InputError(a + " needs a value");
      return std::string(argv[++i]);
    };
    if (a == "--patch") o.patch = value();
    else if (a == "--outline") o.outline = value();
    else if (a == "--view") o.views.push_back(parse_view(value()));
    else if (a == "--title") o.title = value();
    else if (a == "--mm") { o.scale = 1000.0; o.unit = "mm"; }
    else positional.push_back(a);
  }
  if (positional.size() != 2) {
    throw hotmesh::InputError("usage: section_picture MESH.msh OUT.png [--patch NAME] [--mm] [--outline REF.msh] "
                              "[--view NAME=ZMIN,ZMAX,RMIN,RMAX]... [--title TEXT]");
  }
  o.mesh = positional[0];
  o.out = positional[1];
  return o;
}

const hotmesh::mesh::Patch& patch_of(const Mesh& mesh, const std::string& name, const std::filesystem::path& file) {
  const auto* patch = mesh.find_patch(name);
  if (!patch) throw hotmesh::InputError(fmt::format("{}: no patch '{}'", file.string(), name));
  return *patch;
}

/// (z, r) about the z axis, scaled.
hotmesh::geometry::Vec3 section_point(const hotmesh::geometry::Vec3& p, double scale) {
  return {p.z * scale, std::hypot(p.x, p.y) * scale, 0.0};
}

/// The patch's faces as a 2D mesh in (z, r), with the scaled Jacobian of each face's cell.
Mesh section(const Mesh& mesh, const hotmesh::mesh::Patch& patch, double scale, std::vector<double>& quality) {
  Mesh flat;
  flat.dimension = 2;
  std::map<NodeId, NodeId> local;
  const hotmesh::mesh::FaceIndex index(mesh.cells, mesh.node_count());
  std::vector<NodeId> ids;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    ids.clear();
    for (NodeId n : patch.faces.nodes(f)) {
      auto [it, fresh] = local.try_emplace(n, static_cast<NodeId>(flat.points.size()));
      if (fresh) flat.points.push_back(section_point(mesh.points[static_cast<std::size_t>(n)], scale));
      ids.push_back(it->second);
    }
    flat.cells.add(patch.faces.type(f), ids);
    const auto cells = index.find(patch.faces.nodes(f));
    double q = 1.0;
    if (!cells.empty()) {
      const auto c = static_cast<std::size_t>(cells.front().cell);
      q = hotmesh::mesh::scaled_jacobian(mesh.cells.type(c), hotmesh::mesh::gather(mesh.cells.nodes(c), mesh.points));
    }
    quality.push_back(q);
  }
  return flat;
}

/// The boundary of a patch (edges of one face only), as segments in (z, r).
std::vector<std::array<hotmesh::io::PlotPoint, 2>> outline(const Mesh& mesh, const hotmesh::mesh::Patch& patch, double scale) {
  std::map<std::pair<NodeId, NodeId>, int> uses;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    const auto n = patch.faces.nodes(f);
    for (std::size_t k = 0; k < n.size(); ++k) ++uses[std::minmax(n[k], n[(k + 1) % n.size()])];
  }
  std::vector<std::array<hotmesh::io::PlotPoint, 2>> segments;
  for (const auto& [edge, count] : uses) {
    if (count != 1) continue;
    const auto a = section_point(mesh.points[static_cast<std::size_t>(edge.first)], scale);
    const auto b = section_point(mesh.points[static_cast<std::size_t>(edge.second)], scale);
    segments.push_back({{{a.x, a.y}, {b.x, b.y}}});
  }
  return segments;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    const Mesh mesh = hotmesh::io::read_gmsh(o.mesh);
    std::vector<double> quality;
    const Mesh flat = section(mesh, patch_of(mesh, o.patch, o.mesh), o.scale, quality);
    std::vector<std::array<hotmesh::io::PlotPoint, 2>> reference;
    if (!o.outline.empty()) {
      const Mesh ref = hotmesh::io::read_gmsh(o.outline);
      reference = outline(ref, patch_of(ref, o.patch, o.outline), o.scale);
    }
    const auto draw = [&](const std::filesystem::path& file, const std::optional<View>& view) {
      hotmesh::io::Figure figure({.width = 1400,
                                  .height = 900,
                                  .title = o.title.empty() ? o.mesh.filename().string() : o.title,
                                  .x_label = "z (" + o.unit + ")",
                                  .y_label = "r (" + o.unit + ")"});
      hotmesh::io::draw_mesh(figure, flat, flat.points, {.edges = {hotmesh::io::colors::black, view ? 0.7 : 0.3}, .quality = quality});
      for (const auto& s : reference) figure.polyline(s, {hotmesh::io::colors::blue, 1.6});
      if (!reference.empty()) figure.legend("outline of " + o.outline.filename().string(), {hotmesh::io::colors::blue, 1.6});
      if (view) figure.set_view(view->zmin, view->zmax, view->rmin, view->rmax);
      figure.save(file);
      std::printf("wrote %s\n", file.c_str());
    };
    draw(o.out, std::nullopt);
    for (const View& v : o.views) {
      draw(o.out.parent_path() / (o.out.stem().string() + "-" + v.name + o.out.extension().string()), v);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "section_picture: %s\n", e.what());
    return 2;
  }
}
