// hotmesh geometry: distance from points to B-spline surfaces (see surface_distance.hpp), with
// OpenCASCADE's ShapeAnalysis_Surface: a projection that falls back to the boundary of the
// parameter rectangle when the closest point is not inside it.
#include "hotmesh/geometry/surface_distance.hpp"

#include <ShapeAnalysis_Surface.hxx>
#include <Standard_Failure.hxx>

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "cad/occt_convert.hpp"

namespace hotmesh::geometry {

struct SurfaceDistance::Impl {
  std::vector<Handle(ShapeAnalysis_Surface)> surfaces;
  std::vector<double> precision;  // per surface: 1e-9 of its pole box diagonal
};

SurfaceDistance::SurfaceDistance(const std::vector<BSplineSurface>& surfaces) : impl_(std::make_unique<Impl>()) {
  if (surfaces.empty()) throw std::invalid_argument("SurfaceDistance: no surface");
  for (const BSplineSurface& surface : surfaces) {
    impl_->surfaces.push_back(new ShapeAnalysis_Surface(detail::to_occt(surface)));
    Vec3 lo = surface.poles().front(), hi = lo;
    for (const Vec3& p : surface.poles()) {
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    }
    impl_->precision.push_back(std::max(1e-9 * distance(lo, hi), 1e-15));
  }
}

SurfaceDistance::SurfaceDistance(SurfaceDistance&&) noexcept = default;
SurfaceDistance& SurfaceDistance::operator=(SurfaceDistance&&) noexcept = default;
SurfaceDistance::~SurfaceDistance() = default;

SurfaceDistance::Result SurfaceDistance::nearest(const Vec3& p) {
  Result best;
  best.distance = std::numeric_limits<double>::infinity();
  const gp_Pnt point = detail::to_pnt(p);
  for (std::size_t i = 0; i < impl_->surfaces.size(); ++i) {
    const Handle(ShapeAnalysis_Surface)& surface = impl_->surfaces[i];
    try {
      const gp_Pnt2d uv = surface->ValueOfUV(point, impl_->precision[i]);
      const gp_Pnt closest = surface->Value(uv);
      const double d = closest.Distance(point);
      if (d < best.distance) best = {d, detail::to_vec3(closest), i};
    } catch (const Standard_Failure& e) {
      throw std::runtime_error(std::string("projection onto a CAD surface failed: ") + e.GetMessageString());
    }
  }
  return best;
}

}  // namespace hotmesh::geometry
