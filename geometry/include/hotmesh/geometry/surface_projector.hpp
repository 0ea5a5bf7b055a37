// hotmesh geometry: closest points on a set of parametric surface patches, with unit normals
// (issue 23, section 4.2 for surfaces: FEM nodes projected onto the undeformed faces S(t, s) to
// get their parameters, sliding nodes projected onto the deformed faces S + d after every
// Newton step of the mesh motion).
//
// A patch is any S(u, v) that gives its point and first and second derivatives over a parameter
// rectangle (SurfacePatch): a B-spline face, or a face plus a displacement field. The projector
// samples every patch once at construction into sub-patches (sub-rectangles whose surface lies
// within a deviation bound of two triangles through their corners), keeps their boxes in a tree,
// and answers a query by
//  - a global search: sub-patches visited nearest box first, Newton from the nearest point of
//    each one that may hold a closer point than the best found, pruning by that best; sub-patches
//    next to a minimum already found, where the surface is one sheet too gently curved to come
//    nearer, are skipped;
//  - with a hint (the previous projection of a nearby point), Newton on the hint's patch from the
//    hint first, its result the distance the global search has to beat: near the surface only a
//    few sub-patches are then visited, and other patches, or folds of the same one, that come
//    nearer are still found (SurfaceProjectorOptions::verify_warm_starts).
// Newton minimises |S - p|^2 with the full Hessian, a line search, and the rectangle as bounds:
// a minimum on an edge of the rectangle is found as a 1D problem along the edge, a corner ends it.
// A trimmed patch (SurfacePatch::region) answers only inside its trimming loops: a Newton result
// outside them moves to the nearest point of a binding loop (a golden-section search along its
// polyline), unless the nearest loop is free, where the patch reaches on.
//
// project() and at() are const and keep no caches: safe to call from parallel loops over mesh
// nodes, as long as each patch's `evaluate` is (those built here are).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "hotmesh/geometry/bspline_surface.hpp"
#include "hotmesh/geometry/parametric_surface.hpp"
#include "hotmesh/geometry/trim_region.hpp"

namespace hotmesh::geometry {

/// One parametric patch. `evaluate` must be callable concurrently (const, no shared mutable
/// state) and is only called with (u, v) inside `domain`.
struct SurfacePatch {
  std::function<SurfaceDerivatives(double u, double v)> evaluate;
  ParameterRectangle domain;
  /// Optional: parameters where the patch may be less smooth (B-spline knots). Set-up samples
  /// never straddle them, so second derivatives sampled in a sub-patch are continuous there.
  std::vector<double> u_breaks;
  std::vector<double> v_breaks;
  /// Optional: the trimming loops of a face whose surface covers only part of `domain`.
  std::shared_ptr<const TrimRegion> region;
};

/// The patch of a B-spline surface over its whole parameter rectangle.
SurfacePatch bspline_patch(BSplineSurface surface);
/// The deformed face S(u, v) + scale d(u, v), d a displacement field given as a B-spline surface
/// whose poles are displacement vectors, over the same parameter rectangle as S (scale: a stage
/// of the deformation, 1 for the full one). Throws std::invalid_argument if the rectangles differ.
SurfacePatch displaced_patch(BSplineSurface surface, BSplineSurface displacement, double scale = 1.0);

/// A point of the patch set: patch index and parameters; patch -1 is no point (no hint).
struct SurfaceParameter {
  int patch = -1;
  double u = 0.0;
  double v = 0.0;
};

struct SurfaceProjection {
  Vec3 point;
  /// Unit S_u x S_v; where it vanishes (a pole, a collapsed edge) its limit from inside the
  /// patch's rectangle. On a trimming loop that p lies off, the unit direction to p.
  Vec3 normal;
  SurfaceParameter where;
  double distance = 0.0;     ///< from the projected point (0 for at())
  /// The point lies on an edge of its patch's rectangle (to 1e-10 of the length scale): a
  /// boundary of the face, a pole or collapsed edge, or the seam of a closed surface; or on a
  /// binding trimming loop of its patch.
  bool on_boundary = false;
  int iterations = 0;        ///< Newton iterations, all starts together
  bool from_hint = false;    ///< the answer is the warm start's (no nearer point was found)
};

struct SurfaceProjectorOptions {
  /// Sub-rectangles per direction of a patch before refinement (each break interval at least
  /// one).
  int initial_grid = 8;
  /// Sub-patches are split until their surface lies within this distance of the two triangles
  /// through their corners, relative to the length scale. Smaller: more sub-patches, tighter
  /// pruning.
  double sampling_deviation = 2e-3;
  /// Newton stops when its step moves the point by less than this, relative to the length scale.
  double tolerance = 1e-12;
  int max_iterations = 50;
  /// A warm start's result is checked by a global search that has to beat it: cheap, as only
  /// sub-patches nearer than it are visited. Off, a warm start that converges inside its
  /// rectangle is taken as it is: faster, but a nearer point on another patch (near a concave
  /// corner) or on a fold of the same patch is then missed.
  bool verify_warm_starts = true;
};

/// Edges of a patch's parameter rectangle.
enum class PatchEdge { u_first, u_last, v_first, v_last };

/// Where a patch's normal S_u x S_v vanishes at set-up samples. A whole edge (a pole of a
/// sphere, a collapsed edge of a cone's apex) is legitimate: the projector uses the normal's limit
/// from inside there. Isolated interior points say the parametrisation degenerates inside.
struct DegeneracyReport {
  struct Edge {
    int patch = 0;
    PatchEdge edge = PatchEdge::u_first;
    bool collapsed = false;  ///< the whole edge is one point (a pole)
  };
  std::vector<Edge> edges;
  std::vector<SurfaceParameter> points;  ///< interior samples where the normal vanishes

  bool empty() const { return edges.empty() && points.empty(); }
  /// One line per finding, for a log or a user message.
  std::string describe() const;
};

class SurfaceProjector {
 public:
  /// Samples the patches and builds the search tree. Throws std::invalid_argument for no
  /// patches, a patch without `evaluate`, an empty or non-finite rectangle, or a patch whose
  /// evaluation is not finite at a sample.
  explicit SurfaceProjector(std::vector<SurfacePatch> patches, const SurfaceProjectorOptions& options = {});

  std::size_t patch_count() const { return patches_.size(); }
  const SurfacePatch& patch(std::size_t i) const { return patches_[i]; }
  /// Diagonal of the box of all samples: the length scale of tolerances.
  double length_scale() const { return scale_; }
  std::size_t sub_patch_count() const { return subs_.size(); }
  const DegeneracyReport& degeneracies() const { return report_; }

  /// The closest point to p over all patches (within each one's rectangle, boundary included).
  /// With a hint (patch >= 0; parameters are clamped), a warm start first. Ties within
  /// rounding: the hint's patch, else the lowest patch index.
  SurfaceProjection project(const Vec3& p, const SurfaceParameter& hint = {}) const;
  /// The point and normal at a parameter (patch index and parameters clamped to the valid ones).
  SurfaceProjection at(const SurfaceParameter& where) const;

 private:
  struct Box {
    Vec3 lo;
    Vec3 hi;
  };
  /// A sub-rectangle of a patch: its corner points (u0v0, u1v0, u0v1, u1v1), the bound on the
  /// distance of its surface from the two triangles (c00, c10, c11) and (c00, c11, c01), and a
  /// box that holds its surface.
  struct SubPatch {
    std::array<Vec3, 4> corner;
    ParameterRectangle rect;
    double deviation;
    Box box;
    int patch;
  };
  /// Tree node: count == 0: children at first and first + 1; else sub-patches [first, first + count).
  struct Node {
    Box box;
    std::uint32_t first;
    std::uint32_t count;
  };
  struct Local {
    SurfaceParameter where;
    SurfaceDerivatives value;
    double distance;
    int iterations;
    bool converged;
    bool on_rim = false;  ///< moved onto a trimming loop: not a minimum with p on its normal
  };
  /// Extreme values over the set-up samples in one cell of a patch's initial grid.
  struct CellBounds {
    double du = 0.0;            // max |S_u|
    double dv = 0.0;            // max |S_v|
    double bending = 0.0;       // max of max(|n.S_uu|, |n.S_vv|) + |n.S_uv|: bounds |II(t, t)|, |t| = 1
    double metric = 0.0;        // min of the smaller eigenvalue of J^T J, J = [S_u S_v]
  };
  /// A patch's initial grid (cells between knots, or even) and the bounds in each cell
  /// (bounds[i * (vs.size() - 1) + j] for [us[i], us[i+1]] x [vs[j], vs[j+1]]).
  struct Cells {
    std::vector<double> us;
    std::vector<double> vs;
    std::vector<CellBounds> bounds;
    double normal_scale = 0.0;  // max |S_u| |S_v| over the patch
  };
  struct Minimum {
    SurfaceParameter where;
    double distance;
  };
  struct Grid;  // a patch's initial samples (constructor only)

  void sample(const SurfaceProjectorOptions& options);
  void refine(int patch, std::size_t cell, const ParameterRectangle& rect,
              const std::array<SurfaceDerivatives, 4>& corners, int depth);
  void note(int patch, std::size_t cell, const SurfaceDerivatives& d);
  void report_degeneracies(const std::vector<Grid>& grids);
  void build_tree();
  /// rims_: the trimmed patches' loops on the surface (surface_projector_rims.cpp).
  void sample_rims();
  void build_node(std::vector<std::uint32_t>& order, std::uint32_t first, std::uint32_t count, std::uint32_t index);

  SurfaceDerivatives evaluate(int patch, double u, double v) const;
  /// The last result outside a patch's loops and where to_rim moved it, within one search.
  struct RimCache {
    int patch = -1;
    double u = 0.0;
    double v = 0.0;
    Local rim{};
  };
  /// Newton within the patch's rectangle, then onto its region (to_rim; `cache` reused where
  /// Newton ends where it ended last).
  Local newton(const Vec3& p, int patch, double u, double v, RimCache* cache = nullptr) const;
  Local newton_in_rectangle(const Vec3& p, int patch, double u, double v) const;
  /// Newton's final step d from x, below the tolerance, taken where it does not move away from p.
  void take_short_step(const Vec3& p, int patch, const double (&lo)[2], const double (&hi)[2], const double (&d)[2],
                       double (&x)[2], SurfaceDerivatives& e, double& f) const;
  /// `outside`, a point of a trimmed patch outside its loops, moved to the nearest point of the
  /// loops, or kept where the nearest loop is free.
  Local to_rim(const Vec3& p, const Local& outside) const;
  Local global_search(const Vec3& p, const SurfaceParameter& hint, const Local* seed, RimCache& rim) const;
  /// Whether the surface over the parameter box spanning `sub` and the minimum `m` found on its
  /// patch is a sheet curved too little to come nearer to p than m: then `sub` holds no nearer point.
  bool outside_ball(const SubPatch& sub, const Minimum& m) const;
  /// Whether `a` is a better answer than `b`: nearer, or tied and converged where b is not, or
  /// tied on a preferred patch (the hint's, else the lower index); on the same patch the first
  /// found stays.
  bool better(const Local& a, const Local& b, int hint_patch) const;
  bool on_boundary(const SurfaceParameter& where, const SurfaceDerivatives& d) const;
  Vec3 unit_normal(const SurfaceParameter& where, const SurfaceDerivatives& d, const Vec3& p) const;
  SurfaceProjection finish(const Vec3& p, const Local& local) const;

  std::vector<SurfacePatch> patches_;
  std::vector<Cells> cells_;
  std::vector<SubPatch> subs_;
  std::vector<Node> tree_;
  /// Per patch and trimming curve, the surface at the curve's polyline vertices (empty for
  /// patches without a region).
  std::vector<std::vector<std::vector<Vec3>>> rims_;
  DegeneracyReport report_;
  double scale_ = 1.0;
  double target_ = 0.0;     // sub-patch deviation aimed at
  double tolerance_ = 0.0;  // Newton step length at which it stops
  double tie_ = 0.0;        // distances this close are tied
  int max_iterations_ = 50;
  bool verify_ = true;
};

}  // namespace hotmesh::geometry
