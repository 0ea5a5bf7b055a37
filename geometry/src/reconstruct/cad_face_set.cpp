// hotmesh geometry (internal): the CAD faces of a wall seen together (cad_face_set.hpp).
#include "reconstruct/cad_face_set.hpp"

#include <algorithm>

#include "hotmesh/geometry/trim_region.hpp"

namespace hotmesh::geometry::detail {

Box pole_box(const BSplineSurface& s) {
  Box b{s.poles().front(), s.poles().front()};
  for (const Vec3& p : s.poles()) {
    b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y), std::min(b.lo.z, p.z)};
    b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y), std::max(b.hi.z, p.z)};
  }
  return b;
}

FaceSet::FaceSet(std::span<const CadFace> faces) {
  Box all = pole_box(faces.front().surface);
  for (const CadFace& f : faces) {
    // Within the face's trimming loops, every loop binding: a point beyond one is no point of
    // the face (a node beside a strut is not one of the strut's surface running on below it).
    SurfacePatch patch = bspline_patch(f.surface);
    patch.region = trim_region(f, [](int) { return true; });
    projectors.emplace_back(std::vector<SurfacePatch>{std::move(patch)});
    boxes.push_back(pole_box(f.surface));
    all.lo = {std::min(all.lo.x, boxes.back().lo.x), std::min(all.lo.y, boxes.back().lo.y),
              std::min(all.lo.z, boxes.back().lo.z)};
    all.hi = {std::max(all.hi.x, boxes.back().hi.x), std::max(all.hi.y, boxes.back().hi.y),
              std::max(all.hi.z, boxes.back().hi.z)};
  }
  size = distance(all.lo, all.hi);
  for (std::size_t a = 0; a < faces.size(); ++a) find_edges(faces, a);
  crossing = crossing_edges(faces, projectors, 1e-6 * size);
}

void FaceSet::find_edges(std::span<const CadFace> faces, std::size_t a) {
  constexpr int kSamples = 5;
  const ParameterRectangle r = faces[a].surface.domain();
  std::array<int, 4> shared{-1, -1, -1, -1};
  std::array<bool, 4> point{};
  for (int side = 0; side < 4; ++side) {
    std::vector<Vec3> along;
    for (int k = 0; k < kSamples; ++k) {
      const auto [u, v] = on_side(r, side, (k + 0.5) / kSamples);
      along.push_back(faces[a].surface.point(u, v));
    }
    double length = 0.0;
    for (std::size_t k = 1; k < along.size(); ++k) length += distance(along[k], along[k - 1]);
    point[static_cast<std::size_t>(side)] = length <= 1e-9 * size;
    for (std::size_t b = 0; b < faces.size() && shared[static_cast<std::size_t>(side)] < 0; ++b) {
      const bool on_b = b != a && std::all_of(along.begin(), along.end(), [&](const Vec3& p) {
                          return projectors[b].project(p).distance <= 1e-6 * size;
                        });
      if (on_b) shared[static_cast<std::size_t>(side)] = static_cast<int>(b);
    }
  }
  neighbours.push_back(shared);
  collapsed.push_back(point);
}

}  // namespace hotmesh::geometry::detail
