// hotmesh sample tool: how far a duct3d mesh's floor is from the exact deflected floor.
//
// Run:   build/samples/duct3d/duct_wall_distance MESH [--load cold|hot1|hot2] [--undeformed MESH0]
//                                                 [--patch floor] [--samples K]
// MESH is a mesh of the duct (duct.msh, or a deformed.msh that hotmesh deform wrote); the load
// names the exact floor to measure against (default hot1, the load of floor.csv; hot2 that of
// floor_hot2.csv, the restart's; cold the undeformed floor). Prints JSON, in mm and over h
// (wall_distance.hpp defines each): the largest distance of the floor patch's nodes from the
// exact floor (node_distance), of its bilinear faces (mesh_to_floor), of the exact floor from
// the faces (floor_to_mesh), the two-sided distance (hausdorff), each with where it is reached;
// with --undeformed (the mesh before the motion), also material_point_error: how far each node
// is from the point the FEM field carries its material point to.
#include <cstdio>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "duct_floor.hpp"
#include "floor_distance.hpp"
#include "hotmesh/io/gmsh.hpp"

int main(int argc, char** argv) {
  using namespace hotmesh::samples::duct3d;
  const char* usage =
      "usage: duct_wall_distance MESH [--load cold|hot1|hot2] [--undeformed MESH0] [--patch floor] [--samples K]\n";
  try {
    std::string mesh_file, undeformed_file, load = "hot1";
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
    if (mesh_file.empty()) {
      std::fputs(usage, stderr);
      return 2;
    }
    const auto mesh = hotmesh::io::read_gmsh(mesh_file);
    std::optional<hotmesh::mesh::Mesh> undeformed;
    if (!undeformed_file.empty()) undeformed = hotmesh::io::read_gmsh(undeformed_file);
    const DeflectedFloor floor(floor_surface(), load_named(load));
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
    std::fputs(json.c_str(), stdout);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "duct_wall_distance: %s\n", e.what());
    return 2;
  }
}
