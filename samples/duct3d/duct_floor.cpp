// hotmesh sample duct3d: the floor, the CAD model, the mesh, the loads and the FEM tables
// (duct_floor.hpp says what each is).
#include "duct_floor.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "closest_point.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"

namespace hotmesh::samples::duct3d {

namespace {

using geometry::BSplineSurface;
constexpr double kPi = std::numbers::pi;

// The floor's control net: 12 x 6 cubic spans, uniform knots.
constexpr int kDegree = 3;
constexpr int kSpansX = 12;
constexpr int kSpansY = 6;

/// Clamped uniform knots of `spans` cubic spans over [0, length].
std::vector<double> clamped_knots(int spans, double length) {
  std::vector<double> knots(kDegree, 0.0);
  for (int i = 0; i <= spans; ++i) knots.push_back(length * i / spans);
  knots.insert(knots.end(), kDegree, length);
  return knots;
}

/// The Greville abscissae of a knot vector: poles placed there make the B-spline reproduce
/// the linear function t exactly, so that S(t, s) has x = t and y = s.
std::vector<double> greville(const std::vector<double>& knots) {
  std::vector<double> g;
  for (std::size_t i = 0; i + kDegree + 1 < knots.size(); ++i) g.push_back((knots[i + 1] + knots[i + 2] + knots[i + 3]) / 3.0);
  return g;
}

/// The floor's height at a pole (xi, eta in [0, 1]): a waviness of 0.05 h, one and a half waves
/// along the duct and a little less near the middle of its width, and a hump of 0.08 h
/// downstream, off the centre line.
double floor_height(double xi, double eta) {
  const double waves = 0.05 * std::sin(3.0 * kPi * xi) * (0.8 + 0.2 * std::cos(2.0 * kPi * eta));
  const double hump = 0.08 * std::exp(-std::pow((xi - 0.72) / 0.10, 2) - std::pow((eta - 0.35) / 0.22, 2));
  return kH * (waves + hump);
}

/// A face between an edge curve of the floor (cubic poles `edge` along knots `knots`) and the
/// straight line above it in the ceiling: degree 3 along the edge, 1 upwards. It is planar when
/// the edge lies in a vertical plane (the sides, the inlet and the outlet).
BSplineSurface wall_above(const std::vector<double>& knots, const std::vector<Vec3>& edge) {
  std::vector<Vec3> poles;
  for (const Vec3& p : edge) {
    poles.push_back(p);
    poles.push_back({p.x, p.y, kCeiling});
  }
  return BSplineSurface(kDegree, 1, knots, {0.0, 0.0, kH, kH}, std::move(poles));
}

/// splitmix64: a fixed, portable sequence of 64-bit numbers (std's distributions are not
/// portable), turned into [-1, 1).
double jitter(std::uint64_t key) {
  std::uint64_t z = key + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return 2.0 * static_cast<double>(z >> 11) / 9007199254740992.0 - 1.0;  // 53 bits
}

}  // namespace

// 1. The floor and the CAD model.

BSplineSurface floor_surface() {
  const auto tk = clamped_knots(kSpansX, kLength);
  const auto sk = clamped_knots(kSpansY, kWidth);
  const auto xs = greville(tk);
  const auto ys = greville(sk);
  std::vector<Vec3> poles;
  for (const double x : xs) {
    for (std::size_t j = 0; j < ys.size(); ++j) {
      // The rows next to the sides repeat the heights of the side rows: S_s has no z at the sides.
      const std::size_t row = std::clamp<std::size_t>(j, 1, ys.size() - 2);
      poles.push_back({x, ys[j], floor_height(x / kLength, ys[row] / kWidth)});
    }
  }
  return BSplineSurface(kDegree, kDegree, tk, sk, std::move(poles));
}

geometry::CadExport cad_model() {
  const BSplineSurface floor = floor_surface();
  const std::size_t nu = floor.u_count(), nv = floor.v_count();
  const auto pole = [&](std::size_t i, std::size_t j) { return floor.poles()[i * nv + j]; };
  std::vector<Vec3> right, left, inlet, outlet;  // the floor's edge curves
  for (std::size_t i = 0; i < nu; ++i) {
    right.push_back(pole(i, 0));
    left.push_back(pole(i, nv - 1));
  }
  for (std::size_t j = 0; j < nv; ++j) {
    inlet.push_back(pole(0, j));
    outlet.push_back(pole(nu - 1, j));
  }
  const BSplineSurface ceiling(1, 1, {0.0, 0.0, kLength, kLength}, {0.0, 0.0, kWidth, kWidth},
                               {{0.0, 0.0, kCeiling}, {0.0, kWidth, kCeiling}, {kLength, 0.0, kCeiling},
                                {kLength, kWidth, kCeiling}});
  geometry::CadExport cad;
  cad.unit = geometry::LengthUnit::millimetre;
  cad.time_stamp = "2024-01-01T00:00:00";  // fixed, so the files are reproducible
  cad.surfaces = {{kPatchNames[0], floor},
                  {kPatchNames[1], ceiling},
                  {kPatchNames[2], wall_above(floor.u_knots(), right)},
                  {kPatchNames[3], wall_above(floor.u_knots(), left)},
                  {kPatchNames[4], wall_above(floor.v_knots(), inlet)},
                  {kPatchNames[5], wall_above(floor.v_knots(), outlet)}};
  return cad;
}

// 2. The mesh.

mesh::Mesh duct_mesh(const BSplineSurface& floor, const MeshSize& size) {
  const auto ts = mesh::uniform_line(0.0, kLength, size.cells_x);
  const auto ss = mesh::uniform_line(0.0, kWidth, size.cells_y);
  const auto ws = mesh::stretched_line(0.0, 1.0, size.cells_z, size.first_layer);
  // The unit block (t, s, w); structured_hexes names its sides xmin, xmax, ymin, ymax, zmin, zmax.
  mesh::Mesh m = mesh::structured_hexes(ts, ss, ws, {"inlet", "outlet", "side_right", "side_left", "floor", "ceiling"});
  for (Vec3& p : m.points) {
    // Transfinite interpolation between the floor point S(t, s) = (t, s, f(t, s)) and the
    // ceiling point (t, s, h) above it, along a vertical line. x = t and y = s are taken as they
    // are (S gives them to rounding), so the inlet, outlet and side nodes lie exactly on their
    // planes; std::lerp is exact at w = 0 and 1, so the ceiling nodes lie exactly on z = h.
    p = {p.x, p.y, std::lerp(floor.point(p.x, p.y).z, kCeiling, p.z)};
  }
  // Patches in CAD face order, tag = face number.
  std::vector<mesh::Patch> patches;
  for (std::size_t i = 0; i < kPatchNames.size(); ++i) {
    auto it = std::find_if(m.patches.begin(), m.patches.end(), [&](const mesh::Patch& p) { return p.name == kPatchNames[i]; });
    patches.push_back(std::move(*it));
    patches.back().tag = static_cast<int>(i) + 1;
  }
  m.patches = std::move(patches);
  m.derive_node_sets();
  return m;
}

// 3. The loads and the exact deflected floor.

const Load& load_named(std::string_view name) {
  for (const Load* load : {&kCold, &kHot1, &kHot2}) {
    if (load->name == name) return *load;
  }
  throw std::invalid_argument(fmt::format("no load '{}' (cold, hot1, hot2)", name));
}

DeflectedFloor::DeflectedFloor(BSplineSurface floor, const Load& load) : floor_(std::move(floor)), load_(load) {}

namespace {

/// A scalar amplitude and its derivatives along t and s.
struct Amplitude {
  double value = 0.0, t = 0.0, s = 0.0;
};

/// beta and sigma at the floor point of derivatives d (see duct_floor.hpp), by the chain rule
/// through xi = x / 4h and eta = y / 2h.
std::pair<Amplitude, Amplitude> amplitudes(const Load& load, const geometry::SurfaceDerivatives& d) {
  const double xi = d.point.x / kLength, eta = d.point.y / kWidth;
  const double xi_t = d.du.x / kLength, xi_s = d.dv.x / kLength;
  const double eta_t = d.du.y / kWidth, eta_s = d.dv.y / kWidth;
  // beta = (1 - q)^3 for q < 1, q = ((xi - cx) / rx)^2 + ((eta - cy) / ry)^2.
  Amplitude beta;
  const double ax = (xi - load.centre_x) / load.radius_x, ay = (eta - load.centre_y) / load.radius_y;
  const double q = ax * ax + ay * ay;
  if (q < 1.0) {
    const double dq = -3.0 * (1.0 - q) * (1.0 - q);
    const double q_xi = 2.0 * ax / load.radius_x, q_eta = 2.0 * ay / load.radius_y;
    beta = {(1.0 - q) * (1.0 - q) * (1.0 - q), dq * (q_xi * xi_t + q_eta * eta_t), dq * (q_xi * xi_s + q_eta * eta_s)};
  }
  // sigma = sin^2(pi xi) (0.7 + 0.3 cos(pi eta)).
  const double across = 0.7 + 0.3 * std::cos(kPi * eta), across_eta = -0.3 * kPi * std::sin(kPi * eta);
  const double along = std::pow(std::sin(kPi * xi), 2), along_xi = kPi * std::sin(2.0 * kPi * xi);
  const double sigma_xi = along_xi * across, sigma_eta = along * across_eta;
  const Amplitude sigma{along * across, sigma_xi * xi_t + sigma_eta * eta_t, sigma_xi * xi_s + sigma_eta * eta_s};
  return {beta, sigma};
}

/// The unit vector of v and its derivatives, given v's derivatives vt, vs.
struct UnitVector {
  Vec3 value, t, s;
};
UnitVector unit(const Vec3& v, const Vec3& vt, const Vec3& vs) {
  const double length = norm(v);
  const Vec3 u = v / length;
  return {u, (vt - dot(u, vt) * u) / length, (vs - dot(u, vs) * u) / length};
}

}  // namespace

FloorPoint DeflectedFloor::evaluate(double t, double s) const {
  const auto d = floor_.derivatives(t, s);
  const auto [beta, sigma] = amplitudes(load_, d);
  // n = (S_t x S_s) / |...| and e = S_t / |S_t| with their derivatives.
  const UnitVector n = unit(cross(d.du, d.dv), cross(d.duu, d.dv) + cross(d.du, d.duv),
                            cross(d.duv, d.dv) + cross(d.du, d.dvv));
  const UnitVector e = unit(d.du, d.duu, d.duv);
  const double a = load_.bulge, b = load_.shear;
  return {d.point + a * beta.value * n.value + b * sigma.value * e.value,
          d.du + a * (beta.t * n.value + beta.value * n.t) + b * (sigma.t * e.value + sigma.value * e.t),
          d.dv + a * (beta.s * n.value + beta.value * n.s) + b * (sigma.s * e.value + sigma.value * e.s)};
}

Vec3 DeflectedFloor::deflection(double t, double s) const { return evaluate(t, s).x - floor_.point(t, s); }

Closest DeflectedFloor::closest(const Vec3& p, double t0, double s0) const {
  const auto evaluate = [this](double t, double s) { return this->evaluate(t, s); };
  return detail::closest_on_patch(evaluate, p, t0, s0, {0.0, kLength, 0.0, kWidth});
}

// 4. The FEM tables.

std::vector<std::pair<double, double>> fem_parameters(FemLayout layout) {
  const double dt = kLength / (kFemNodesX - 1), ds = kWidth / (kFemNodesY - 1);
  std::vector<std::pair<double, double>> ts;
  for (int j = 0; j < kFemNodesY; ++j) {
    for (int i = 0; i < kFemNodesX; ++i) {
      double t = i * dt, s = j * ds;
      if (layout == FemLayout::scattered) {
        // Up to 30 % of the spacing each way; nodes on an edge move along it, corners stay.
        const auto id = static_cast<std::uint64_t>(1 + i + kFemNodesX * j);
        if (i > 0 && i < kFemNodesX - 1) t += 0.3 * dt * jitter(2 * id);
        if (j > 0 && j < kFemNodesY - 1) s += 0.3 * ds * jitter(2 * id + 1);
      }
      ts.emplace_back(t, s);
    }
  }
  return ts;
}

geometry::DeflectionSamples fem_table(const DeflectedFloor& floor, FemLayout layout) {
  geometry::DeflectionSamples table;
  table.frame = geometry::SampleFrame::cartesian;
  std::int64_t id = 1;
  for (const auto& [t, s] : fem_parameters(layout)) {
    const Vec3 p = floor.floor().point(t, s);
    table.points.push_back(p);
    table.deflections.push_back(floor.evaluate(t, s).x - p);
    table.ids.push_back(id++);
  }
  return table;
}

std::string fem_table_csv(const DeflectedFloor& floor, FemLayout layout) {
  const Load& l = floor.load();
  std::string header = fmt::format(
      "# hotmesh sample duct3d: FEM nodes of the duct's floor (face {} of {}) and their deflections, load {}\n"
      "# millimetres; {} x {} nodes of the floor surface, {}\n"
      "# bulge {:g} mm (normal) at x = {:g} mm, y = {:g} mm; shear {:g} mm (along the duct); see duct_floor.hpp\n",
      kFloorFace, kCadFile, l.name, kFemNodesX, kFemNodesY,
      layout == FemLayout::grid ? "a tensor grid in (x, y)" : "a grid jittered by up to 30 % of its spacing",
      l.bulge, l.centre_x * kLength, l.centre_y * kWidth, l.shear);
  return header + io::format_deflection_csv(fem_table(floor, layout));
}

}  // namespace hotmesh::samples::duct3d
