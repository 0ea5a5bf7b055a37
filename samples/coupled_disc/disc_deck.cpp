// hotmesh sample coupled_disc: the CalculiX deck of the rotor band (see disc_deck.hpp).
#include "disc_deck.hpp"

#include <cmath>
#include <cstdint>
#include <cctype>
#include <stdexcept>

#include <fmt/format.h>

#include "fem_tables.hpp"

namespace hotmesh::samples::coupled_disc {

namespace {

using stator_well::Patch;
using geometry::Vec2;

/// The wall nodes of the band, (z, r) along the loop, and the wall of each segment.
struct WallChain {
  std::vector<Vec2> points;
  std::vector<std::string> segment_walls;  ///< segment i joins points i and i + 1
};

WallChain wall_chain(const std::vector<stator_well::ProfileCurve>& loop) {
  const std::vector<stator_well::FemTable> tables = stator_well::fem_tables(loop);
  WallChain chain;
  std::int64_t last_id = -1;
  for (const Patch patch : kRotorWalls) {
    const std::string wall = deck_set(patch);
    for (const stator_well::FemTable& t : tables) {
      if (t.patch != patch) continue;
      for (const stator_well::FemNode& n : t.nodes) {
        if (n.id == last_id) continue;  // the corner the walls share
        if (!chain.points.empty()) chain.segment_walls.push_back(wall);
        chain.points.push_back(n.zr);
        last_id = n.id;
      }
    }
  }
  if (chain.points.size() < 2) throw std::logic_error("coupled_disc: no rotor walls in the profile");
  return chain;
}

/// The unit normal into the metal at each node: the fluid loop runs counter-clockwise in
/// (z, r), so the metal is on the right of the walls; averaged over a node's segments.
std::vector<Vec2> metal_normals(const std::vector<Vec2>& p) {
  const auto right_normal = [&](std::size_t i) {
    const Vec2 t = p[i + 1] - p[i];
    const double length = std::hypot(t.x, t.y);
    return Vec2{t.y / length, -t.x / length};
  };
  std::vector<Vec2> normals;
  for (std::size_t i = 0; i < p.size(); ++i) {
    Vec2 n{};
    if (i > 0) n += right_normal(i - 1);
    if (i + 1 < p.size()) n += right_normal(i);
    normals.push_back(n / std::hypot(n.x, n.y));
  }
  return normals;
}

struct BandMesh {
  std::vector<Vec2> zr;                  ///< node k * columns + i: layer k, column i
  std::size_t columns = 0;
  std::int64_t id(std::size_t column, int layer) const {
    return 1 + static_cast<std::int64_t>(static_cast<std::size_t>(layer) * columns + column);
  }
};

BandMesh band_mesh(const WallChain& chain, const Band& band) {
  const std::vector<Vec2> normals = metal_normals(chain.points);
  BandMesh mesh;
  mesh.columns = chain.points.size();
  for (int k = 0; k <= band.layers; ++k) {
    const double depth = band.thickness * k / band.layers;
    for (std::size_t i = 0; i < mesh.columns; ++i) mesh.zr.push_back(chain.points[i] + depth * normals[i]);
  }
  return mesh;
}

double temperature(const DiscLoad& load, double r) {
  return load.bore_temperature + (load.rim_temperature - load.bore_temperature) * (r - 0.31) / 0.11;
}

}  // namespace

std::string deck_set(Patch patch) {
  std::string name(stator_well::name(patch));
  for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return name;
}

std::string disc_mesh_deck(const std::vector<stator_well::ProfileCurve>& loop, const Band& band) {
  const WallChain chain = wall_chain(loop);
  const BandMesh mesh = band_mesh(chain, band);
  // CalculiX's axisymmetric plane: x = r, y = z.
  std::string text = "** hotmesh sample coupled_disc: the rotor band's nodes, elements and sets (x = r, y = z, m)\n"
                     "*NODE, NSET=NALL\n";
  for (std::size_t n = 0; n < mesh.zr.size(); ++n) {
    text += fmt::format("{}, {:.12g}, {:.12g}\n", n + 1, mesh.zr[n].y, mesh.zr[n].x);
  }
  text += "*ELEMENT, TYPE=CAX4, ELSET=EALL\n";
  std::vector<std::string> wall_faces(chain.segment_walls.size());  // "element, S<face>" of each wall segment
  std::int64_t element = 0;
  for (int k = 0; k < band.layers; ++k) {
    for (std::size_t i = 0; i + 1 < mesh.columns; ++i) {
      const std::int64_t a = mesh.id(i, k), b = mesh.id(i + 1, k), c = mesh.id(i + 1, k + 1), d = mesh.id(i, k + 1);
      // Counter-clockwise in (r, z): (a, b, c, d) when the wall runs that way, else (a, d, c, b).
      const Vec2 pa = mesh.zr[static_cast<std::size_t>(a - 1)], pb = mesh.zr[static_cast<std::size_t>(b - 1)],
                 pd = mesh.zr[static_cast<std::size_t>(d - 1)];
      const bool forward = (pb.y - pa.y) * (pd.x - pa.x) - (pb.x - pa.x) * (pd.y - pa.y) > 0.0;
      text += forward ? fmt::format("{}, {}, {}, {}, {}\n", ++element, a, b, c, d)
                      : fmt::format("{}, {}, {}, {}, {}\n", ++element, a, d, c, b);
      if (k == 0) wall_faces[i] = fmt::format("{}, {}", element, forward ? "S1" : "S4");  // the edge a-b
    }
  }
  for (const Patch patch : kRotorWalls) {
    const std::string wall = deck_set(patch);
    text += fmt::format("*SURFACE, NAME={}, TYPE=ELEMENT\n", wall);
    for (std::size_t i = 0; i < wall_faces.size(); ++i) {
      if (chain.segment_walls[i] == wall) text += wall_faces[i] + "\n";
    }
  }
  text += "** the bore: the drum's inner face\n*NSET, NSET=BORE\n";
  for (std::size_t i = 0; i < chain.segment_walls.size(); ++i) {
    if (chain.segment_walls[i] != "DISC_BASE") continue;
    text += fmt::format("{}, {},\n", mesh.id(i, band.layers), mesh.id(i + 1, band.layers));
  }
  return text;
}

std::string disc_deck(const std::vector<stator_well::ProfileCurve>& loop, const std::string& mesh_file,
                      const DiscLoad& load, const std::string& title, const Band& band) {
  const BandMesh mesh = band_mesh(wall_chain(loop), band);
  std::string temperatures;
  for (std::size_t n = 0; n < mesh.zr.size(); ++n) {
    temperatures += fmt::format("{}, {:.6g}\n", n + 1, temperature(load, mesh.zr[n].y));
  }
  return fmt::format(
      "*HEADING\n{}\n"
      "** hotmesh sample coupled_disc, written by make_coupled_disc. Run: ccx -i <this file without .inp>\n"
      "*INCLUDE, INPUT={}\n"
      "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.0e11, 0.3\n*EXPANSION\n1.2e-5\n*DENSITY\n7800.\n"
      "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n"
      "*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 20.\n"
      "*STEP\n*STATIC\n"
      "** the bore held axially where the shaft puts it, free radially\n*BOUNDARY\nBORE, 2, 2, {}\n"
      "** spinning about the engine axis (CalculiX's y axis), omega^2 in (rad/s)^2\n"
      "*DLOAD\nEALL, CENTRIF, {}, 0., 0., 0., 0., 1., 0.\n"
      "** metal temperatures: {} C at the bore to {} C at the rim, linear in r\n*TEMPERATURE\n{}"
      "*NODE FILE\nU, NT\n*END STEP\n",
      title, mesh_file, load.axial_shift, load.omega_squared, load.bore_temperature, load.rim_temperature,
      temperatures);
}

}  // namespace hotmesh::samples::coupled_disc
