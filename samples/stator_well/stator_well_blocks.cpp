// hotmesh sample stator_well: the block layout of the meridional section (66 blocks).
//
// The cavities are lattices of rows (r) and columns (z) whose lines start at the corners of the
// profile: the rim lips, the seal land, the fin tips, the joint, and strips of width kStrip along
// the disc faces, the diaphragm faces and the lip undersides. Where a wall turns a corner
// through a fillet, the corner block of the lattice is dropped and its two neighbours along the
// walls meet on the fillet's bisector, from the fillet's middle M to the lattice point H: every
// block keeps four corners, and at M each meets the wall at a right angle. The seal is a row of
// chambers between the fins, with one block under each fin tip; the rim gaps and the annulus
// are one row of blocks each.
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "dimensions.hpp"
#include "stator_well.hpp"

namespace hotmesh::samples::stator_well {

namespace {

using dims::at;

/// Collects blocks given by their corner points; equal points become one vertex.
class Blocks {
 public:
  int vertex(Vec2 p) {
    for (std::size_t i = 0; i < layout.vertices.size(); ++i) {
      if (distance(layout.vertices[i], p) < 1e-12) return static_cast<int>(i);
    }
    layout.vertices.push_back(p);
    return static_cast<int>(layout.vertices.size()) - 1;
  }
  /// Corners counter-clockwise in (z, r).
  void add(Vec2 a, Vec2 b, Vec2 c, Vec2 d) { layout.blocks.push_back({vertex(a), vertex(b), vertex(c), vertex(d)}); }
  BlockLayout layout;
};

/// The point of a profile curve at radius r (mm); the curve must cross r once.
Vec2 at_radius(const ProfileCurve& c, double r_mm) {
  const double r = r_mm * 1e-3;
  double lo = c.curve.first_parameter(), hi = c.curve.last_parameter();
  const bool rising = c.curve.point(hi).y > c.curve.point(lo).y;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    ((c.curve.point(mid).y < r) == rising ? lo : hi) = mid;
  }
  return c.curve.point(0.5 * (lo + hi));
}

const ProfileCurve& find(const std::vector<ProfileCurve>& loop, const std::string& name) {
  for (const auto& c : loop) {
    if (c.name == name) return c;
  }
  throw std::logic_error("stator well profile has no curve " + name);
}

/// The middle of a fillet of radius `radius` about (zc, rc), at `angle` degrees.
Vec2 fillet_middle(double zc, double rc, double radius, double angle) {
  const double a = angle * std::numbers::pi / 180.0;
  return at(zc + radius * std::cos(a), rc + radius * std::sin(a));
}

/// Blocks of a lattice row between r0 and r1 over columns z[i]..z[i+1] (mm), i in [first, last).
void row(Blocks& b, const std::vector<double>& z, std::size_t first, std::size_t last, double r0, double r1) {
  for (std::size_t i = first; i < last; ++i) b.add(at(z[i], r0), at(z[i + 1], r0), at(z[i + 1], r1), at(z[i], r1));
}

}  // namespace

BlockLayout block_layout(const std::vector<ProfileCurve>& loop) {
  using namespace dims;
  Blocks b;
  const double t = kStrip;
  const double r_gap = kRJoint + kJointGap;

  // 1. Main annulus and rim gaps.
  const std::vector<double> up{kZInlet, kZRotorLipFront, kZStatorLipFront, kZStatorFront};
  const std::vector<double> down{kZStatorRear, kZStatorLipRear, kZRotorLipRear, kZOutlet};
  row(b, up, 0, 3, kRHub, kRCasing);
  row(b, down, 0, 3, kRHub, kRCasing);
  row(b, up, 1, 2, kRLip, kRHub);
  row(b, down, 1, 2, kRLip, kRHub);

  // 2. Upstream cavity. Columns: disc face strip | core | rim gap | core | diaphragm strip; rows
  // from the disc base: clearance, fin height, up to the joint, joint, up to the lips, lip strip.
  const ProfileCurve& upper_face = find(loop, "disc_up_upper.face");
  const ProfileCurve& lower_face = find(loop, "disc_up_lower.face");
  const std::vector<double> cu{kZDiscFront + t, kZRotorLipFront, kZStatorLipFront, kZStatorFront - t, kZStatorFront};
  const double ru[] = {kRDrum, kRFinTip, kRLand, kRJoint, r_gap, kRLip - t, kRLip};
  const auto face = [&](double r) { return at_radius(r > r_gap - 0.5 ? upper_face : lower_face, r); };
  // The two top corners turn through fillets: the strips meet on their bisectors.
  const Vec2 m_rotor = fillet_middle(kZDiscFront + kRotorFillet, kRLip - kRotorFillet, kRotorFillet, 135.0);
  const Vec2 m_stator = fillet_middle(kZStatorFront - kStatorFillet, kRLip - kStatorFillet, kStatorFillet, 45.0);
  for (std::size_t j = 0; j < 4; ++j) {
    b.add(face(ru[j]), at(cu[0], ru[j]), at(cu[0], ru[j + 1]), face(ru[j + 1]));
    row(b, cu, 0, 4, ru[j], ru[j + 1]);
  }
  b.add(face(ru[4]), at(cu[0], ru[4]), at(cu[0], ru[5]), m_rotor);
  row(b, cu, 0, 3, ru[4], ru[5]);
  b.add(at(cu[3], ru[4]), at(cu[4], ru[4]), m_stator, at(cu[3], ru[5]));
  b.add(at(cu[0], ru[5]), at(cu[1], ru[5]), at(cu[1], ru[6]), m_rotor);
  row(b, cu, 1, 2, ru[5], ru[6]);
  b.add(at(cu[2], ru[5]), at(cu[3], ru[5]), m_stator, at(cu[2], ru[6]));
  // The joint: one block in the slot.
  b.add(at(kZJointEnd, kRJoint), at(kZDiscFront, kRJoint), at(kZDiscFront, r_gap), at(kZJointEnd, r_gap));

  // 3. The seal: a chamber before, between and after the fins (two rows: the clearance, and the
  // fins' height up to the land) and one block under each fin tip.
  const double half_base = 0.5 * kFinBase, half_tip = 0.5 * kFinTip;
  const auto front = [&](std::size_t k, double r) {  // fin k's upstream side at radius r
    return kFinCentres[k] - half_tip - (half_base - half_tip) * (r - kRFinTip) / (kRLand - kRFinTip);
  };
  const auto back = [&](std::size_t k, double r) { return 2.0 * kFinCentres[k] - front(k, r); };
  for (std::size_t k = 0; k <= kFinCentres.size(); ++k) {
    const auto left = [&](double r) { return k == 0 ? kZStatorFront : back(k - 1, r); };
    const auto right = [&](double r) { return k == kFinCentres.size() ? kZStatorRear : front(k, r); };
    const double zl = left(kRFinTip), zr = right(kRFinTip);
    b.add(at(zl, kRDrum), at(zr, kRDrum), at(zr, kRFinTip), at(zl, kRFinTip));
    b.add(at(zl, kRFinTip), at(zr, kRFinTip), at(right(kRLand), kRLand), at(left(kRLand), kRLand));
    if (k < kFinCentres.size()) {
      const double z0 = kFinCentres[k] - half_tip, z1 = kFinCentres[k] + half_tip;
      b.add(at(z0, kRDrum), at(z1, kRDrum), at(z1, kRFinTip), at(z0, kRFinTip));
    }
  }

  // 4. Downstream cavity. Columns: diaphragm strip | core | rim gap | core | disc face strip.
  const ProfileCurve& rear_face = find(loop, "disc_down.face");
  const std::vector<double> cd{kZStatorRear, kZStatorRear + t, kZStatorLipRear, kZRotorLipRear, kZDiscRear - t};
  const double rd[] = {kRDrum, kRFinTip, kRLand, kRLip - t, kRLip};
  const Vec2 n_stator = fillet_middle(kZStatorRear + kStatorFillet, kRLip - kStatorFillet, kStatorFillet, 135.0);
  const Vec2 n_rotor = fillet_middle(kZDiscRear - kRotorFillet, kRLip - kRotorFillet, kRotorFillet, 45.0);
  const auto rear = [&](double r) { return at_radius(rear_face, r); };
  for (std::size_t j = 0; j < 2; ++j) {
    row(b, cd, 0, 4, rd[j], rd[j + 1]);
    b.add(at(cd[4], rd[j]), rear(rd[j]), rear(rd[j + 1]), at(cd[4], rd[j + 1]));
  }
  b.add(at(cd[0], rd[2]), at(cd[1], rd[2]), at(cd[1], rd[3]), n_stator);
  row(b, cd, 1, 4, rd[2], rd[3]);
  b.add(at(cd[4], rd[2]), rear(rd[2]), n_rotor, at(cd[4], rd[3]));
  b.add(at(cd[1], rd[3]), at(cd[2], rd[3]), at(cd[2], rd[4]), n_stator);
  row(b, cd, 2, 3, rd[3], rd[4]);
  b.add(at(cd[3], rd[3]), at(cd[4], rd[3]), n_rotor, at(cd[3], rd[4]));

  // 5. The loop, with open boundaries (inlet, outlet) marked: nothing clusters towards them.
  for (const ProfileCurve& c : loop) b.layout.loop.push_back({c.curve, c.patch != Patch::inlet && c.patch != Patch::outlet});
  return b.layout;
}

SpacingField spacing_field() { return {.spacing = 2.0e-3, .wall_spacing = 0.15e-3, .growth = 1.25}; }

}  // namespace hotmesh::samples::stator_well
