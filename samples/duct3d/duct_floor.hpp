// hotmesh sample duct3d: a straight rectangular duct whose floor is a bicubic B-spline surface,
// the FEM loads that bulge and shear the floor, and the exact deflected floor.
//
// Units: millimetres. The duct is 4h long (x, inlet at x = 0, outlet at x = 4h), 2h wide
// (y, side_right at y = 0, side_left at y = 2h: left and right looking downstream with z up)
// and about h high (z, ceiling at z = h), with h = 10 mm.
//
// The floor S(t, s) is a bicubic B-spline over the parameter rectangle [0, 4h] x [0, 2h]. The x
// and y of its poles are the Greville abscissae of its knots, so that (B-splines reproduce
// linear functions) S(t, s) = (t, s, f(t, s)): t is x and s is y, and the floor is the graph of
// the bicubic f, a gentle waviness along the duct and a mild hump (a few percent of h). Its rows
// of poles next to the sides repeat the side rows, so the floor meets the side planes at right
// angles (S_s has no z there). The other five faces are planes; their edges on the floor are
// the floor's own edge curves, so the faces meet exactly.
//
// The FEM field (one Load) moves a floor point S(t, s), with xi = x / 4h and eta = y / 2h, by
//     delta = bulge * beta(xi, eta) * n(t, s) + shear * sigma(xi, eta) * e(t, s)
// where n is the floor's unit normal (into the duct), e = S_t / |S_t| its unit tangent along
// the duct, beta = (1 - r^2)^3 for r < 1 (0 beyond; C2) with
// r^2 = ((xi - centre_x) / radius_x)^2 + ((eta - centre_y) / radius_y)^2, a hump whose
// footprint stays inside the floor, and sigma = sin^2(pi xi) (0.7 + 0.3 cos(pi eta)), a
// tangential motion along the duct that vanishes at the inlet and outlet and varies across the
// duct (it shears the floor in its plane). So the deflected floor keeps the duct's outline: its
// edges stay in the inlet, outlet and side planes (at the sides beta = 0 and e lies in the
// side plane). The exact deflected floor is X(t, s) = S(t, s) + delta(t, s).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hotmesh/geometry/bspline_surface.hpp"
#include "hotmesh/geometry/cad_export.hpp"
#include "hotmesh/geometry/deflection_samples.hpp"
#include "hotmesh/core/vec3.hpp"
#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::samples::duct3d {

using geometry::Vec3;

// 1. Sizes, in millimetres.
inline constexpr double kH = 10.0;             ///< h, the duct's nominal height
inline constexpr double kLength = 4.0 * kH;    ///< along x
inline constexpr double kWidth = 2.0 * kH;     ///< along y
inline constexpr double kCeiling = kH;         ///< the ceiling plane z = h

// 2. The CAD model: faces in the order CadModel reads them back from duct.step (file order),
//    and the mesh's patches: tag i is the patch on face i.
inline constexpr int kFloorFace = 1;
inline constexpr int kCeilingFace = 2;
inline constexpr int kSideRightFace = 3;  ///< y = 0
inline constexpr int kSideLeftFace = 4;   ///< y = 2h
inline constexpr int kInletFace = 5;      ///< x = 0
inline constexpr int kOutletFace = 6;     ///< x = 4h
inline constexpr std::array<const char*, 6> kPatchNames = {"floor", "ceiling", "side_right", "side_left", "inlet", "outlet"};

inline constexpr const char* kCadFile = "duct.step";
inline constexpr const char* kIgesFile = "duct.iges";
inline constexpr const char* kMeshFile = "duct.msh";

/// The floor S(t, s) = (t, s, f(t, s)), bicubic, over [0, 4h] x [0, 2h].
geometry::BSplineSurface floor_surface();

/// The six faces of the duct, named as the patches, in face order (kFloorFace, ...), in
/// millimetres, with a fixed time stamp so that the files come out the same every time.
geometry::CadExport cad_model();

// 3. The CFD mesh.
struct MeshSize {
  int cells_x = 48;             ///< along the duct: dx = 4h / 48 = h / 12
  int cells_y = 16;             ///< across: dy = 2h / 16 = h / 8
  int cells_z = 12;             ///< floor to ceiling
  double first_layer = 0.025;   ///< the first cell's share of the height (growth about 1.2)
};

/// Structured hexes: node (i, j, k) at (1 - w_k) S(t_i, s_j) + w_k (t_i, s_j, h), with t_i and
/// s_j uniform and w_k growing geometrically from the floor (transfinite interpolation between
/// floor and ceiling along straight vertical lines). Floor nodes are (t_i, s_j, f(t_i, s_j)):
/// on S to rounding; the nodes of the five plane faces lie exactly on their planes. Patches
/// kPatchNames, tags 1 to 6 (the CAD face of each), faces oriented out of the duct.
mesh::Mesh duct_mesh(const geometry::BSplineSurface& floor, const MeshSize& size = {});

// 4. The FEM loads and the exact deflected floor.
struct Load {
  std::string_view name;
  double bulge = 0.0;      ///< mm, peak normal displacement (into the duct)
  double centre_x = 0.5;   ///< the bulge's peak, as a fraction of the length
  double centre_y = 0.5;   ///< ... and of the width
  double radius_x = 0.3;   ///< the semi-axes of its footprint, as fractions
  double radius_y = 0.3;
  double shear = 0.0;      ///< mm, peak tangential displacement along the duct
};

/// No deflection: the undeformed floor.
inline constexpr Load kCold{"cold"};
/// floor.csv: a bulge of 0.15 h a little upstream of the middle, and a shear of 0.05 h.
inline constexpr Load kHot1{"hot1", 0.15 * kH, 0.45, 0.50, 0.35, 0.42, 0.05 * kH};
/// floor_hot2.csv, the next coupling iteration: the bulge grown to 0.2 h and moved downstream
/// and towards side_right, the shear reversed.
inline constexpr Load kHot2{"hot2", 0.20 * kH, 0.60, 0.42, 0.30, 0.36, -0.03 * kH};
/// The loads by name ("cold", "hot1", "hot2"); throws std::invalid_argument for another name.
const Load& load_named(std::string_view name);

/// X(t, s) = S(t, s) + delta(t, s) and its first derivatives.
struct FloorPoint {
  Vec3 x;
  Vec3 xt;
  Vec3 xs;
};

/// A closest point: parameters, the point and its distance from the query.
struct Closest {
  double t = 0.0;
  double s = 0.0;
  Vec3 point;
  double distance = 0.0;
};

class DeflectedFloor {
 public:
  DeflectedFloor(geometry::BSplineSurface floor, const Load& load);

  const geometry::BSplineSurface& floor() const { return floor_; }
  const Load& load() const { return load_; }

  /// delta(t, s), the FEM deflection of the floor point S(t, s).
  Vec3 deflection(double t, double s) const;
  /// X(t, s) and its derivatives (exact: the chain rule through n and e, from S's second
  /// derivatives).
  FloorPoint evaluate(double t, double s) const;
  /// The closest point of X to p over the whole parameter rectangle: Gauss-Newton on (t, s)
  /// from (t0, s0), clamped to the rectangle. Converges to the closest point near the start;
  /// the start (p.x, p.y) is good for points near the floor (t is x before deflection, and the
  /// deflection moves points along x by at most |shear|).
  Closest closest(const Vec3& p, double t0, double s0) const;
  Closest closest(const Vec3& p) const { return closest(p, p.x, p.y); }

 private:
  geometry::BSplineSurface floor_;
  Load load_;
};

// 5. The FEM tables: the nodes of an FEM surface mesh of the floor, 23 x 10 (spacing 1.82 mm x
//    2.22 mm), about half as fine as the CFD mesh's 49 x 17 floor nodes (0.83 mm x 1.25 mm). On
//    the grid only 6 FEM nodes coincide with CFD nodes (where x = 0, 2h, 4h meets the sides);
//    scattered, only the 4 corners.
inline constexpr int kFemNodesX = 23;
inline constexpr int kFemNodesY = 10;

enum class FemLayout {
  grid,       ///< a tensor grid in (t, s): interpolated by hotmesh
  scattered,  ///< the grid jittered by up to 30 % of its spacing, edges kept on the edges: fitted
};

/// The FEM nodes' parameters (t, s), id 1 + i + 23 j for node (i, j), in id order.
std::vector<std::pair<double, double>> fem_parameters(FemLayout layout);
/// The table: nodes S(t, s), deflections delta(t, s) of the load, ids.
geometry::DeflectionSamples fem_table(const DeflectedFloor& floor, FemLayout layout);
/// The table as CSV (id,x,y,z,dx,dy,dz, shortest round-trip numbers) after comment lines.
std::string fem_table_csv(const DeflectedFloor& floor, FemLayout layout);

}  // namespace hotmesh::samples::duct3d
