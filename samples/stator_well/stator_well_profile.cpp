// hotmesh sample stator_well: the meridional profile (lines, B-spline disc faces, circular
// fillets as rational B-splines), its CAD face numbering and the revolved CAD model.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "dimensions.hpp"
#include "stator_well.hpp"

namespace hotmesh::samples::stator_well {

namespace {

using dims::at;

BSplineCurve2d line(Vec2 a, Vec2 b) { return BSplineCurve2d(1, {0, 0, 1, 1}, {a, b}); }

/// A circular arc of at most 90 degrees, exact as a rational quadratic, from angle a0 to a1
/// (degrees, in the (z, r) plane) about `centre` (mm).
BSplineCurve2d arc(double zc, double rc, double radius, double a0, double a1) {
  const double t0 = a0 * std::numbers::pi / 180.0, t1 = a1 * std::numbers::pi / 180.0;
  const double half = 0.5 * (t1 - t0);
  const Vec2 p0 = at(zc + radius * std::cos(t0), rc + radius * std::sin(t0));
  const Vec2 p2 = at(zc + radius * std::cos(t1), rc + radius * std::sin(t1));
  const double reach = radius / std::cos(half);  // where the end tangents meet
  const Vec2 p1 = at(zc + reach * std::cos(t0 + half), rc + reach * std::sin(t0 + half));
  return BSplineCurve2d(2, {0, 0, 0, 1, 1, 1}, {p0, p1, p2}, {1.0, std::cos(half), 1.0});
}

/// A clamped cubic B-spline through the control points (mm), uniform knots.
BSplineCurve2d cubic(std::initializer_list<std::array<double, 2>> points) {
  std::vector<Vec2> poles;
  for (const auto& p : points) poles.push_back(at(p[0], p[1]));
  const std::size_t spans = poles.size() - 3;
  std::vector<double> knots{0, 0, 0, 0};
  for (std::size_t i = 1; i < spans; ++i) knots.push_back(static_cast<double>(i) / static_cast<double>(spans));
  knots.insert(knots.end(), {1, 1, 1, 1});
  return BSplineCurve2d(3, std::move(knots), std::move(poles));
}

}  // namespace

std::string_view name(Patch patch) {
  static constexpr std::array<std::string_view, kPatchCount> names{
      "inlet",  "outlet",        "casing", "blade",         "stator_outer", "stator_front", "fins",
      "stator_rear", "rim_up",   "disc_up_upper", "joint", "disc_up_lower", "disc_base",  "disc_down",
      "rim_down", "per_lo",      "per_hi"};
  return names[static_cast<std::size_t>(patch)];
}

std::vector<ProfileCurve> profile() {
  using namespace dims;
  std::vector<ProfileCurve> loop;
  const auto add = [&](Patch patch, const std::string& part, BSplineCurve2d curve) {
    loop.push_back({std::string(name(patch)) + "." + part, patch, std::move(curve)});
  };
  const auto seg = [](double z0, double r0, double z1, double r1) { return line(at(z0, r0), at(z1, r1)); };
  const double bulge = kZDiscFront + kDiscBulge, hollow = kZDiscRear - kDiscBulge;
  const double r_top = kRLip - kRotorFillet;  // where the disc faces' fillets end
  const double r_gap = kRJoint + kJointGap;

  // Inlet, then the upstream rotor: platform, lip, disc face with the joint, down to the disc base.
  add(Patch::inlet, "inlet", seg(kZInlet, kRCasing, kZInlet, kRHub));
  add(Patch::rim_up, "platform", seg(kZInlet, kRHub, kZRotorLipFront, kRHub));
  add(Patch::rim_up, "lip_face", seg(kZRotorLipFront, kRHub, kZRotorLipFront, kRLip));
  add(Patch::disc_up_upper, "lip_underside", seg(kZRotorLipFront, kRLip, kZDiscFront + kRotorFillet, kRLip));
  add(Patch::disc_up_upper, "fillet", arc(kZDiscFront + kRotorFillet, r_top, kRotorFillet, 90.0, 180.0));
  add(Patch::disc_up_upper, "face",
      cubic({{kZDiscFront, r_top}, {kZDiscFront, r_top - 8.0}, {bulge, 389.0}, {bulge, 380.0}, {kZDiscFront, r_gap}}));
  add(Patch::joint, "upper_wall", seg(kZDiscFront, r_gap, kZJointEnd, r_gap));
  add(Patch::joint, "end", seg(kZJointEnd, r_gap, kZJointEnd, kRJoint));
  add(Patch::joint, "lower_wall", seg(kZJointEnd, kRJoint, kZDiscFront, kRJoint));
  add(Patch::disc_up_lower, "face",
      cubic({{kZDiscFront, kRJoint}, {bulge, 360.0}, {bulge, 342.0}, {kZDiscFront, 332.0}, {kZDiscFront, kRDrum}}));
  // The disc base, then the downstream rotor: disc face, fillet, lip, platform; the outlet.
  add(Patch::disc_base, "drum", seg(kZDiscFront, kRDrum, kZDiscRear, kRDrum));
  add(Patch::disc_down, "face",
      cubic({{kZDiscRear, kRDrum}, {kZDiscRear, 332.0}, {hollow, 348.0}, {hollow, 380.0}, {kZDiscRear, r_top - 10.0},
             {kZDiscRear, r_top}}));
  add(Patch::disc_down, "fillet", arc(kZDiscRear - kRotorFillet, r_top, kRotorFillet, 0.0, 90.0));
  add(Patch::disc_down, "lip_underside", seg(kZDiscRear - kRotorFillet, kRLip, kZRotorLipRear, kRLip));
  add(Patch::rim_down, "lip_face", seg(kZRotorLipRear, kRLip, kZRotorLipRear, kRHub));
  add(Patch::rim_down, "platform", seg(kZRotorLipRear, kRHub, kZOutlet, kRHub));
  add(Patch::outlet, "outlet", seg(kZOutlet, kRHub, kZOutlet, kRCasing));
  // Back over the casing and the vane; the stator's rear lip and diaphragm face, the land with
  // the fins (from the last to the first), the diaphragm's front face and lip.
  add(Patch::casing, "rear", seg(kZOutlet, kRCasing, kZStatorRear, kRCasing));
  add(Patch::blade, "trailing", seg(kZStatorRear, kRCasing, kZStatorRear, kRHub));
  add(Patch::stator_outer, "rear", seg(kZStatorRear, kRHub, kZStatorLipRear, kRHub));
  const double rs = kRLip - kStatorFillet;
  add(Patch::stator_rear, "lip_face", seg(kZStatorLipRear, kRHub, kZStatorLipRear, kRLip));
  add(Patch::stator_rear, "lip_underside", seg(kZStatorLipRear, kRLip, kZStatorRear + kStatorFillet, kRLip));
  add(Patch::stator_rear, "fillet", arc(kZStatorRear + kStatorFillet, rs, kStatorFillet, 90.0, 180.0));
  add(Patch::stator_rear, "face", seg(kZStatorRear, rs, kZStatorRear, kRLand));
  const double half_base = 0.5 * kFinBase, half_tip = 0.5 * kFinTip;
  double z = kZStatorRear;
  for (std::size_t k = kFinCentres.size(); k-- > 0;) {
    const double c = kFinCentres[k];
    const std::string fin = "fin" + std::to_string(k + 1);
    add(Patch::fins, "land" + std::to_string(k + 2), seg(z, kRLand, c + half_base, kRLand));
    add(Patch::fins, fin + "_back", seg(c + half_base, kRLand, c + half_tip, kRFinTip));
    add(Patch::fins, fin + "_tip", seg(c + half_tip, kRFinTip, c - half_tip, kRFinTip));
    add(Patch::fins, fin + "_front", seg(c - half_tip, kRFinTip, c - half_base, kRLand));
    z = c - half_base;
  }
  add(Patch::fins, "land1", seg(z, kRLand, kZStatorFront, kRLand));
  add(Patch::stator_front, "face", seg(kZStatorFront, kRLand, kZStatorFront, rs));
  add(Patch::stator_front, "fillet", arc(kZStatorFront - kStatorFillet, rs, kStatorFillet, 0.0, 90.0));
  add(Patch::stator_front, "lip_underside", seg(kZStatorFront - kStatorFillet, kRLip, kZStatorLipFront, kRLip));
  add(Patch::stator_front, "lip_face", seg(kZStatorLipFront, kRLip, kZStatorLipFront, kRHub));
  add(Patch::stator_outer, "front", seg(kZStatorLipFront, kRHub, kZStatorFront, kRHub));
  add(Patch::blade, "leading", seg(kZStatorFront, kRHub, kZStatorFront, kRCasing));
  add(Patch::casing, "front", seg(kZStatorFront, kRCasing, kZInlet, kRCasing));
  return loop;
}

std::vector<int> cad_face_order(const std::vector<ProfileCurve>& loop) {
  // A patch's curves form runs of consecutive curves along the loop (one run for a wall, two for
  // the casing, blade and stator_outer). Each run is taken the way z grows from its start to its
  // end (at equal z, r), as hotmesh orients meridional curves; runs in order of their first z.
  const auto start = [&](int i) { const auto& c = loop[static_cast<std::size_t>(i)].curve; return c.point(c.first_parameter()); };
  const auto end = [&](int i) { const auto& c = loop[static_cast<std::size_t>(i)].curve; return c.point(c.last_parameter()); };
  const auto before = [](Vec2 a, Vec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; };
  std::vector<int> order;
  for (int p = 0; p < kPatchCount; ++p) {
    std::vector<std::vector<int>> runs;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      if (static_cast<int>(loop[i].patch) != p) continue;
      const bool joins = !runs.empty() && runs.back().back() + 1 == static_cast<int>(i);
      if (!joins) runs.emplace_back();
      runs.back().push_back(static_cast<int>(i));
    }
    for (auto& run : runs) {
      if (before(end(run.back()), start(run.front()))) std::reverse(run.begin(), run.end());
    }
    std::sort(runs.begin(), runs.end(), [&](const auto& a, const auto& b) {
      return before(std::min(start(a.front()), end(a.back()), before), std::min(start(b.front()), end(b.back()), before));
    });
    for (const auto& run : runs) order.insert(order.end(), run.begin(), run.end());
  }
  return order;
}

std::vector<int> cad_faces(const std::vector<ProfileCurve>& loop, Patch patch) {
  const auto order = cad_face_order(loop);
  std::vector<int> ids;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (loop[static_cast<std::size_t>(order[k])].patch == patch) ids.push_back(static_cast<int>(k) + 1);
  }
  return ids;
}

geometry::RevolvedModel cad_model(const std::vector<ProfileCurve>& loop) {
  geometry::RevolvedModel model;
  model.axis = geometry::Axis({0, 0, 0}, {0, 0, 1});
  model.angle = kSectorDegrees * std::numbers::pi / 180.0;
  model.time_stamp = "2024-01-01T00:00:00";  // fixed, so the file is reproducible
  for (int i : cad_face_order(loop)) {
    const ProfileCurve& c = loop[static_cast<std::size_t>(i)];
    std::vector<Vec2> poles;
    for (const Vec2& p : c.curve.poles()) poles.push_back(to_rz(p));
    model.faces.push_back({c.name, BSplineCurve2d(c.curve.degree(), c.curve.knots(), std::move(poles), c.curve.weights())});
  }
  return model;
}

}  // namespace hotmesh::samples::stator_well
