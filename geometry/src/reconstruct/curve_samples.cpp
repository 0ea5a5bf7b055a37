// hotmesh geometry: FEM samples brought into the plane of a curve: (x, y) for 2D cases, (r, z)
// about an axis for axisymmetric ones (Fig. 4: everything happens in the meridional plane), and
// (z, r) for 2D axisymmetric meshes, drawn in that plane with x along the axis.
#include <algorithm>
#include <cmath>
#include <string>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/reconstruction.hpp"

namespace hotmesh::geometry {

namespace {

CurveSamples copy_labels(const DeflectionSamples& samples) {
  if (samples.deflections.size() != samples.points.size() ||
      (!samples.ids.empty() && samples.ids.size() != samples.points.size()) ||
      (!samples.lines.empty() && samples.lines.size() != samples.points.size())) {
    throw InputError::in(samples.source, "deflection samples have inconsistent sizes");
  }
  CurveSamples out;
  out.ids = samples.ids;
  out.lines = samples.lines;
  out.source = samples.source;
  out.points.reserve(samples.size());
  out.deflections.reserve(samples.size());
  return out;
}

}  // namespace

std::string CurveSamples::label(std::size_t j) const { return sample_label(ids, lines, j); }

CurveSamples planar_samples(const DeflectionSamples& samples) {
  if (samples.frame != SampleFrame::planar) {
    throw InputError::in(samples.source, std::string("a 2D curve needs planar (x, y) samples, got ") +
                                             to_string(samples.frame));
  }
  CurveSamples out = copy_labels(samples);
  for (std::size_t j = 0; j < samples.size(); ++j) {
    out.points.push_back({samples.points[j].x, samples.points[j].y});
    out.deflections.push_back({samples.deflections[j].x, samples.deflections[j].y});
    out.max_out_of_plane_deflection = std::max(out.max_out_of_plane_deflection, std::abs(samples.deflections[j].z));
  }
  return out;
}

CurveSamples meridional_samples(const DeflectionSamples& samples, const Axis& axis) {
  if (samples.frame == SampleFrame::planar) {
    throw InputError::in(samples.source,
                         "an axisymmetric boundary needs cartesian (x, y, z) or meridional (r, z) samples, "
                         "got planar (x, y)");
  }
  CurveSamples out = copy_labels(samples);
  for (std::size_t j = 0; j < samples.size(); ++j) {
    const Vec3& q = samples.points[j];
    const Vec3& d = samples.deflections[j];
    if (samples.frame == SampleFrame::meridional) {
      out.points.push_back({q.x, q.y});
      out.deflections.push_back({d.x, d.y});
      continue;
    }
    const Cylindrical c = axis.to_cylindrical(q);
    const Vec3 radial = axis.meridional_vector(c.theta, 1.0, 0.0);
    const Vec3 circumferential = cross(axis.direction(), radial);
    out.points.push_back({c.r, c.z});
    out.deflections.push_back({dot(d, radial), dot(d, axis.direction())});
    out.max_out_of_plane_deflection = std::max(out.max_out_of_plane_deflection, std::abs(dot(d, circumferential)));
  }
  return out;
}

CurveSamples axial_plane_samples(const DeflectionSamples& samples, const Axis& axis) {
  CurveSamples out = meridional_samples(samples, axis);
  for (Vec2& p : out.points) p = {p.y, p.x};
  for (Vec2& d : out.deflections) d = {d.y, d.x};
  return out;
}

}  // namespace hotmesh::geometry
