// hotmesh sample tool: pictures of a meridional section of a 3D mesh of revolution, such as the
// periodic face of a sector (the paper's Figs. 15 and 17 show the stator well this way), or of
// a 3D mesh cut by a plane x, y or z = const (the duct3d sample).
//
// Run:   build/samples/tools/section_picture MESH.msh OUT.png [--patch per_lo] [--mm]
//            [--outline REFERENCE.msh] [--view NAME=ZMIN,ZMAX,RMIN,RMAX]... [--title TEXT]
//            [--plane x=V|y=V|z=V] [--curve FILE.csv] [--curve-label TEXT] [--quality-lo Q]
//            [--size WIDTH,HEIGHT] [--unit NAME]
// The faces of the patch (quads or triangles) are taken to (z, r) about the z axis and drawn,
// each filled by the scaled Jacobian of the 3D cell it bounds. OUT.png shows the whole section;
// each --view adds OUT-NAME.png, a close-up of the window given (in the units drawn). --mm draws
// a mesh in metres in millimetres; --unit names the mesh's unit on the axes (default m) without
// scaling. --outline draws the boundary of the same patch of another mesh (e.g. the undeformed
// one) in blue over it.
// With --plane, every cell is cut by the plane (V in the mesh's units) instead, and the cut, a
// convex polygon through the points where the cell's edges cross the plane, is drawn filled by
// the cell's scaled Jacobian, over the other two coordinates in order (x = V: y, z; y = V: x, z;
// z = V: x, y); the --view window is in those. --outline then draws where the plane cuts the
// --patch faces of the reference mesh. --curve draws a polyline, one point "a,b" a line in the
// coordinates drawn (lines starting with # skipped), in red: e.g. an exact wall to compare the
// mesh's with. --quality-lo sets the bottom of the colour scale (default 0).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/mesh/mesh_topology.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/core/input_error.hpp"
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

/// A cutting plane: coordinate `axis` (0 x, 1 y, 2 z) equal to `value`.
struct Plane {
  int axis = 1;
  double value = 0.0;
};

struct Options {
  std::filesystem::path mesh, out, outline, curve;
  std::string patch = "per_lo", title, curve_label;
  double scale = 1.0;
  std::string unit = "m";
  std::vector<View> views;
  std::optional<Plane> plane;
  double quality_lo = 0.0;
  int width = 1400, height = 900;
};

Plane parse_plane(const std::string& text) {
  Plane p;
  if (text.size() < 3 || text[1] != '=' || (text[0] != 'x' && text[0] != 'y' && text[0] != 'z')) {
    throw hotmesh::InputError("--plane expects x=V, y=V or z=V, got '" + text + "'");
  }
  p.axis = text[0] - 'x';
  char* end = nullptr;
  p.value = std::strtod(text.c_str() + 2, &end);
  if (end == text.c_str() + 2 || *end != '\0') throw hotmesh::InputError("--plane expects a number after '=', got '" + text + "'");
  return p;
}

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
    else if (a == "--unit") o.unit = value();
    else if (a == "--plane") o.plane = parse_plane(value());
    else if (a == "--curve") o.curve = value();
    else if (a == "--curve-label") o.curve_label = value();
    else if (a == "--quality-lo") o.quality_lo = std::stod(value());
    else if (a == "--size") {
      const std::string v = value();
      if (std::sscanf(v.c_str(), "%d,%d", &o.width, &o.height) != 2 || o.width < 100 || o.height < 100) {
        throw hotmesh::InputError("--size expects WIDTH,HEIGHT in pixels (at least 100), got '" + v + "'");
      }
    }
    else positional.push_back(a);
  }
  if (positional.size() != 2) {
    throw hotmesh::InputError("usage: section_picture MESH.msh OUT.png [--patch NAME] [--mm] [--outline REF.msh] "
                              "[--view NAME=ZMIN,ZMAX,RMIN,RMAX]... [--title TEXT] [--plane x=V|y=V|z=V] "
                              "[--curve FILE.csv] [--curve-label TEXT] [--quality-lo Q] [--size W,H] [--unit NAME]");
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

double coordinate(const hotmesh::geometry::Vec3& p, int axis) { return axis == 0 ? p.x : axis == 1 ? p.y : p.z; }

/// The two coordinates drawn for a cut by `plane`, scaled.
hotmesh::io::PlotPoint in_plane(const hotmesh::geometry::Vec3& p, const Plane& plane, double scale) {
  const int a = plane.axis == 0 ? 1 : 0, b = plane.axis == 2 ? 1 : 2;
  return {coordinate(p, a) * scale, coordinate(p, b) * scale};
}

/// Where segment p-q crosses the plane, if it does (an end on the plane counts).
std::optional<hotmesh::geometry::Vec3> crossing(const hotmesh::geometry::Vec3& p, const hotmesh::geometry::Vec3& q,
                                                const Plane& plane) {
  const double a = coordinate(p, plane.axis) - plane.value, b = coordinate(q, plane.axis) - plane.value;
  if ((a > 0 && b > 0) || (a < 0 && b < 0) || a == b) return std::nullopt;
  const double w = a / (a - b);
  return p + w * (q - p);
}

/// A cell cut by the plane: the polygon (in the coordinates drawn) and the cell's quality.
struct Cut {
  std::vector<hotmesh::io::PlotPoint> polygon;
  double quality;
};

/// Every cell crossing the plane, cut: the points where its edges (those of its faces) cross
/// the plane, ordered by angle about their mean (the cut of a convex cell is convex).
std::vector<Cut> plane_cuts(const Mesh& mesh, const Plane& plane, double scale) {
  std::vector<Cut> cuts;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const auto nodes = mesh.cells.nodes(c);
    const auto type = mesh.cells.type(c);
    double lo = 1e300, hi = -1e300;
    for (NodeId n : nodes) {
      const double v = coordinate(mesh.points[static_cast<std::size_t>(n)], plane.axis);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    if (lo > plane.value || hi < plane.value || lo == hi) continue;
    std::vector<std::pair<int, int>> edges;
    for (const auto& face : hotmesh::mesh::faces(type)) {
      for (int k = 0; k < face.count; ++k) {
        const int a = face.nodes[static_cast<std::size_t>(k)], b = face.nodes[static_cast<std::size_t>((k + 1) % face.count)];
        const std::pair<int, int> e{std::min(a, b), std::max(a, b)};
        if (std::find(edges.begin(), edges.end(), e) == edges.end()) edges.push_back(e);
      }
    }
    std::vector<hotmesh::io::PlotPoint> points;
    for (const auto& [i, j] : edges) {
      const auto x = crossing(mesh.points[static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)])],
                              mesh.points[static_cast<std::size_t>(nodes[static_cast<std::size_t>(j)])], plane);
      if (!x) continue;
      const auto p = in_plane(*x, plane, scale);
      const bool seen = std::any_of(points.begin(), points.end(), [&](const hotmesh::io::PlotPoint& q) {
        return std::abs(q.x - p.x) + std::abs(q.y - p.y) <= 1e-12 * (std::abs(p.x) + std::abs(p.y) + 1.0);
      });
      if (!seen) points.push_back(p);
    }
    if (points.size() < 3) continue;
    double cx = 0.0, cy = 0.0;
    for (const auto& p : points) {
      cx += p.x;
      cy += p.y;
    }
    cx /= static_cast<double>(points.size());
    cy /= static_cast<double>(points.size());
    std::sort(points.begin(), points.end(), [&](const hotmesh::io::PlotPoint& a, const hotmesh::io::PlotPoint& b) {
      return std::atan2(a.y - cy, a.x - cx) < std::atan2(b.y - cy, b.x - cx);
    });
    cuts.push_back({std::move(points), hotmesh::mesh::scaled_jacobian(type, hotmesh::mesh::gather(nodes, mesh.points))});
  }
  return cuts;
}

/// Where the plane cuts the faces of a patch, as segments in the coordinates drawn.
std::vector<std::array<hotmesh::io::PlotPoint, 2>> plane_outline(const Mesh& mesh, const hotmesh::mesh::Patch& patch,
                                                                 const Plane& plane, double scale) {
  std::vector<std::array<hotmesh::io::PlotPoint, 2>> segments;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    const auto n = patch.faces.nodes(f);
    std::vector<hotmesh::io::PlotPoint> points;
    for (std::size_t k = 0; k < n.size(); ++k) {
      const auto x = crossing(mesh.points[static_cast<std::size_t>(n[k])], mesh.points[static_cast<std::size_t>(n[(k + 1) % n.size()])], plane);
      if (x) points.push_back(in_plane(*x, plane, scale));
    }
    if (points.size() >= 2) segments.push_back({points.front(), points.back()});
  }
  return segments;
}

/// A polyline from a file of "a,b" lines (# comments and blank lines skipped).
std::vector<hotmesh::io::PlotPoint> read_curve(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw hotmesh::InputError("cannot read " + file.string());
  std::vector<hotmesh::io::PlotPoint> points;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    hotmesh::io::PlotPoint p;
    if (std::sscanf(line.c_str(), "%lf,%lf", &p.x, &p.y) != 2) throw hotmesh::InputError(file.string() + ": expected a,b in '" + line + "'");
    points.push_back(p);
  }
  if (points.size() < 2) throw hotmesh::InputError(file.string() + ": fewer than two points");
  return points;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    const Mesh mesh = hotmesh::io::read_gmsh(o.mesh);
    std::vector<double> quality;
    Mesh flat;
    std::vector<Cut> cuts;
    if (o.plane) {
      cuts = plane_cuts(mesh, *o.plane, o.scale);
      if (cuts.empty()) throw hotmesh::InputError(fmt::format("{}: no cell crosses the plane", o.mesh.string()));
    } else {
      flat = section(mesh, patch_of(mesh, o.patch, o.mesh), o.scale, quality);
    }
    std::vector<std::array<hotmesh::io::PlotPoint, 2>> reference;
    if (!o.outline.empty()) {
      const Mesh ref = hotmesh::io::read_gmsh(o.outline);
      const auto& patch = patch_of(ref, o.patch, o.outline);
      reference = o.plane ? plane_outline(ref, patch, *o.plane, o.scale) : outline(ref, patch, o.scale);
    }
    std::vector<hotmesh::io::PlotPoint> curve;
    if (!o.curve.empty()) curve = read_curve(o.curve);
    const char* names[] = {"x", "y", "z"};
    const std::string horizontal = o.plane ? names[o.plane->axis == 0 ? 1 : 0] : "z";
    const std::string vertical = o.plane ? names[o.plane->axis == 2 ? 1 : 2] : "r";
    const auto draw = [&](const std::filesystem::path& file, const std::optional<View>& view) {
      hotmesh::io::Figure figure({.width = o.width,
                                  .height = o.height,
                                  .title = o.title.empty() ? o.mesh.filename().string() : o.title,
                                  .x_label = horizontal + " (" + o.unit + ")",
                                  .y_label = vertical + " (" + o.unit + ")"});
      const hotmesh::io::Stroke edges{hotmesh::io::colors::black, view ? 0.7 : 0.3};
      if (o.plane) {
        const double span = 1.0 - o.quality_lo;
        for (const Cut& cut : cuts) {
          const auto fill = cut.quality <= 0.0 ? hotmesh::io::Color{0.45, 0.0, 0.0}
                                               : hotmesh::io::colormap((cut.quality - o.quality_lo) / span);
          figure.polygon(cut.polygon, fill, edges);
        }
        figure.color_bar("scaled Jacobian", o.quality_lo, 1.0);
      } else {
        hotmesh::io::draw_mesh(figure, flat, flat.points, {.edges = edges, .quality = quality, .quality_lo = o.quality_lo});
      }
      for (const auto& s : reference) figure.polyline(s, {hotmesh::io::colors::blue, 1.6});
      if (!reference.empty()) {
        const std::string what = o.plane ? o.patch + " of " : "outline of ";
        figure.legend(what + o.outline.filename().string(), {hotmesh::io::colors::blue, 1.6});
      }
      if (!curve.empty()) {
        const hotmesh::io::Stroke red{hotmesh::io::colors::red, 1.6};
        figure.polyline(curve, red);
        figure.legend(o.curve_label.empty() ? o.curve.filename().string() : o.curve_label, red);
      }
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
