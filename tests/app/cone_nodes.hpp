// hotmesh tests: FEM nodes on the CATIA cone of tests/data/cad (OCC8842_cone_CATIA.igs: apex
// (0, 0, 80) mm, base radius 60 at z = -70) at 30 degrees, cartesian in mm, written out of
// order, with deflection (dr, dz) = (0.5 s^2, -0.2 s), s = 0 at the apex and 1 at the base.
// Node k has id 100 + k; `far_offset` moves node 3 off the cone radially.
#pragma once

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace hotmesh::test {

inline std::string cone_nodes(int count, double far_offset = 0.0) {
  std::ostringstream out;
  out.precision(17);
  out << "id,x,y,z,dx,dy,dz\n";
  const double theta = std::numbers::pi / 6;
  for (int pass = 0; pass < 2; ++pass) {
    for (int k = pass; k < count; k += 2) {
      const double s = static_cast<double>(k) / (count - 1);
      const double r = 60 * s + (k == 3 ? far_offset : 0.0);
      out << 100 + k << "," << r * std::cos(theta) << "," << r * std::sin(theta) << "," << 80 - 150 * s << ","
          << 0.5 * s * s * std::cos(theta) << "," << 0.5 * s * s * std::sin(theta) << "," << -0.2 * s << "\n";
    }
  }
  return out.str();
}

}  // namespace hotmesh::test
