// hotmesh sample tool: how far a duct3d mesh's floor is from the exact deflected floor.
//
// Run:   build/samples/duct3d/duct_wall_distance MESH [--load cold|hot1|hot2] [--undeformed MESH0]
//                                                 [--patch floor] [--samples K]
//                                                 [--picture OUT.png [--range MM] [--title TEXT]]
//                                                 [--on-floor] [--apart OTHER.msh]
//        build/samples/duct3d/duct_wall_distance --section x=V|y=V [--load cold|hot1|hot2] [--points N]
// MESH is a mesh of the duct (duct.msh, or a deformed.msh that hotmesh deform wrote); the load
// names the exact floor to measure against (default hot1, the load of floor.csv; hot2 that of
// floor_hot2.csv, the restart's; cold the undeformed floor). Prints JSON, in mm and over h
// (floor_distance.hpp defines each): the largest distance of the floor patch's nodes from the
// exact floor (node_distance), of its bilinear faces (mesh_to_floor), of the exact floor from
// the faces (floor_to_mesh), the two-sided distance (hausdorff), each with where it is reached;
// with --undeformed (the mesh before the motion), also material_point_error: how far each node
// is from the point the FEM field carries its material point to.
// --on-floor first puts every floor node of MESH (an undeformed mesh: the node at (x, y) is the
// floor point S(x, y)) where the load carries it, X(x, y): a floor moved exactly by the FEM
// field, whose distance is the faceting alone, the least a moved floor can be off.
// --apart adds nodes_apart: the largest distance between a node of MESH and the same node of
// OTHER (a mesh of the same nodes: a restarted run against a straight one), over every node and
// over the floor patch's nodes.
// --picture also draws the floor patch seen from above (x, y), each face filled by the mean of
// its four nodes' distances from the exact floor (from 0 to --range mm, default the largest).
// With --section (no mesh), prints instead where the plane x = V or y = V (mm) cuts the exact
// floor of the load: N + 1 points (default 400), one "a,b" line each, a the other of x and y
// and b = z, for pictures of a mesh cut by the same plane (section_picture --plane ... --curve).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "duct_floor.hpp"
#include "floor_distance.hpp"
#include "hotmesh/io/figure.hpp"
#include "hotmesh/io/gmsh.hpp"

namespace {

using namespace hotmesh::samples::duct3d;

/// The floor patch from above, faces filled by their nodes' mean distance from the exact floor.
void draw_floor(const hotmesh::mesh::Mesh& mesh, const DeflectedFloor& floor, const std::string& patch_name,
                const std::string& title, double range, const std::string& file) {
  const auto* patch = mesh.find_patch(patch_name);
  if (patch == nullptr) throw std::invalid_argument("no patch " + patch_name);
  std::vector<double> node(mesh.node_count(), 0.0);
  double largest = 0.0;
  for (const auto n : patch->nodes) {
    node[static_cast<std::size_t>(n)] = floor.closest(mesh.points[static_cast<std::size_t>(n)]).distance;
    largest = std::max(largest, node[static_cast<std::size_t>(n)]);
  }
  if (range <= 0.0) range = largest;
  hotmesh::io::Figure figure({.width = 1600, .height = 900, .title = title, .x_label = "x (mm)", .y_label = "y (mm)"});
  std::vector<hotmesh::io::PlotPoint> corners;
  for (std::size_t f = 0; f < patch->faces.size(); ++f) {
    corners.clear();
    double mean = 0.0;
    for (const auto n : patch->faces.nodes(f)) {
      const auto& p = mesh.points[static_cast<std::size_t>(n)];
      corners.push_back({p.x, p.y});
      mean += node[static_cast<std::size_t>(n)];
    }
    mean /= static_cast<double>(corners.size());
    figure.polygon(corners, hotmesh::io::colormap(mean / range), hotmesh::io::Stroke{hotmesh::io::colors::black, 0.3});
  }
  char label[96];
  std::snprintf(label, sizeof label, "node distance to the exact floor (mm), largest %.3g", largest);
  figure.color_bar(label, 0.0, range);
  figure.save(file);
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage =
      "usage: duct_wall_distance MESH [--load cold|hot1|hot2] [--undeformed MESH0] [--patch floor] [--samples K]\n"
      "                          [--picture OUT.png [--range MM] [--title TEXT]] [--on-floor] [--apart OTHER.msh]\n"
      "       duct_wall_distance --section x=V|y=V [--load cold|hot1|hot2] [--points N]\n";
  try {
    std::string mesh_file, undeformed_file, load = "hot1", section, picture, title, apart;
    int points = 400;
    double range = 0.0;
    bool on_floor = false;
    FloorDistanceOptions options;
    for (int i = 1; i < argc; ++i) {
      const std::string_view a = argv[i];
      const auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(std::string(a) + " needs a value");
        return argv[++i];
      };
      if (a == "--load") {
        load = value();
      } else if (a == "--undeformed") {
        undeformed_file = value();
      } else if (a == "--patch") {
        options.patch = value();
      } else if (a == "--section") {
        section = value();
      } else if (a == "--picture") {
        picture = value();
      } else if (a == "--on-floor") {
        on_floor = true;
      } else if (a == "--apart") {
        apart = value();
      } else if (a == "--title") {
        title = value();
      } else if (a == "--range") {
        range = std::stod(value());
      } else if (a == "--points") {
        points = std::stoi(value());
      } else if (a == "--samples") {
        options.samples = std::stoi(value());
      } else if (a == "-h" || a == "--help") {
        std::fputs(usage, stdout);
        return 0;
      } else if (!a.empty() && a[0] != '-' && mesh_file.empty()) {
        mesh_file = a;
      } else {
        throw std::invalid_argument("unexpected argument " + std::string(a));
      }
    }
    if (!section.empty()) {
      if (section.size() < 3 || (section[0] != 'x' && section[0] != 'y') || section[1] != '=' || points < 1) {
        throw std::invalid_argument("--section expects x=V or y=V (mm) and --points a positive count");
      }
      const DeflectedFloor floor(floor_surface(), load_named(load));
      const int axis = section[0] - 'x';
      const double value = std::stod(section.substr(2));
      std::printf("# exact deflected floor, load %s, plane %s = %g mm: %s,z (mm)\n", std::string(floor.load().name).c_str(),
                  axis == 0 ? "x" : "y", value, axis == 0 ? "y" : "x");
      for (const Vec3& x : floor_section(floor, axis, value, points)) std::printf("%.9g,%.9g\n", axis == 0 ? x.y : x.x, x.z);
      return 0;
    }
    if (mesh_file.empty()) {
      std::fputs(usage, stderr);
      return 2;
    }
    auto mesh = hotmesh::io::read_gmsh(mesh_file);
    std::optional<hotmesh::mesh::Mesh> undeformed;
    if (!undeformed_file.empty()) undeformed = hotmesh::io::read_gmsh(undeformed_file);
    const DeflectedFloor floor(floor_surface(), load_named(load));
    if (on_floor) {
      const auto* patch = mesh.find_patch(options.patch);
      if (patch == nullptr) throw std::invalid_argument(mesh_file + ": no patch " + options.patch);
      for (const auto n : patch->nodes) {
        auto& p = mesh.points[static_cast<std::size_t>(n)];
        p = floor.evaluate(p.x, p.y).x;
      }
    }
    const auto d = floor_distance(mesh, floor, options, undeformed ? &*undeformed : nullptr);
    const auto quoted = [](const std::string& text) {
      std::string q = "\"";
      for (const char c : text) {
        if (c == '"' || c == '\\') q += '\\';
        q += c;
      }
      return q + '"';
    };
    // The inputs first, then the measures.
    std::string json = to_json(d);
    json.insert(2, "  \"mesh\": " + quoted(mesh_file) + ",\n  \"load\": " + quoted(load) + ",\n  \"patch\": " +
                       quoted(options.patch) + ",\n");
    if (!apart.empty()) {
      const auto other = hotmesh::io::read_gmsh(apart);
      json.insert(json.size() - 3, ",\n  \"nodes_apart\": " + to_json(nodes_apart(mesh, other, options.patch), options.patch) +
                                       ",\n  \"other\": " + quoted(apart));
    }
    std::fputs(json.c_str(), stdout);
    if (!picture.empty()) {
      if (title.empty()) title = "floor of " + mesh_file + " against the exact floor of " + load;
      draw_floor(mesh, floor, options.patch, title, range, picture);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "duct_wall_distance: %s\n", e.what());
    return 2;
  }
}
