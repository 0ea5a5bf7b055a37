#include "hotmesh/geometry/deflection_samples.hpp"

namespace hotmesh::geometry {

const char* to_string(SampleFrame frame) {
  switch (frame) {
    case SampleFrame::planar: return "planar (x, y)";
    case SampleFrame::cartesian: return "cartesian (x, y, z)";
    case SampleFrame::meridional: return "meridional (r, z)";
  }
  return "?";
}

}  // namespace hotmesh::geometry
