// hotmesh sample stator_well: a structured multi-block quad mesher for a planar region.
//
// The region is bounded by one closed loop of B-spline curves (lines are degree-1 curves). It
// is covered by four-sided blocks given by their corner vertices; a block side on the loop
// follows the loop between its two corners (through any number of curves), every other side
// is a straight line. Node counts are matched automatically: opposite sides of a block carry
// the same count, so the sides of the whole layout fall into classes (chains of opposite
// sides) that share one count and one node distribution, found with a union-find.
//
// Spacing. Each class's distribution comes from a spacing field: cells of size `spacing` away
// from walls, growing geometrically by `growth` from `wall_spacing` at a wall, i.e. a spacing
// h(d) = min(spacing, wall_spacing + (growth - 1) d) at a distance d from the class's
// clustered ends. A class is clustered at an end where one of its sides meets a wall
// transversally there: the side leaves a wall, or runs along one wall into a corner with
// another (curves joined with a continuous tangent count as one wall). A refinement s divides
// the whole field by s, so counts grow like s and the distributions keep their shape.
//
// Blocks are filled by transfinite interpolation of their four sides' nodes. Nodes on the loop
// are evaluated on its curves, so they lie on them exactly.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "hotmesh/geometry/bspline_curve.hpp"

namespace hotmesh::samples {

class BoundaryLoop;
using geometry::BSplineCurve2d;
using geometry::Vec2;

/// One piece of the region's boundary loop.
struct LoopCurve {
  BSplineCurve2d curve;  ///< oriented along the loop; ends where the next curve starts
  bool wall = true;      ///< false for open boundaries (inlets, outlets): nothing clusters towards them
};

/// Spacing at refinement 1 (see the file comment).
struct SpacingField {
  double spacing = 1.0;
  double wall_spacing = 0.1;
  double growth = 1.2;  ///< > 1
};

struct BlockLayout {
  std::vector<LoopCurve> loop;             ///< closed, counter-clockwise: the region on its left
  std::vector<Vec2> vertices;
  std::vector<std::array<int, 4>> blocks;  ///< vertex ids, counter-clockwise
};

struct QuadMesh {
  std::vector<Vec2> nodes;
  std::vector<std::array<std::int32_t, 4>> quads;  ///< counter-clockwise
  struct Segment {
    std::int32_t a = 0, b = 0;  ///< nodes, in the direction of the loop
    int curve = 0;              ///< index into BlockLayout::loop
  };
  std::vector<Segment> boundary;  ///< every boundary edge of the mesh
  /// Each block as a structured grid: ni x nj nodes, node (i, j) at nodes[j ni + i]; i runs
  /// along the block's first side (P0 -> P1), j along its fourth (P0 -> P3). Its quads are
  /// those of `quads` in the same order, i fastest.
  struct Block {
    std::size_t ni = 0, nj = 0;
    std::vector<std::int32_t> nodes;
  };
  std::vector<Block> blocks;
};

class BlockMesher {
 public:
  /// Checks and analyses the layout. Throws std::invalid_argument naming the block, side or
  /// vertex if a block is not counter-clockwise, a side is used by more than two blocks or twice
  /// in one direction, a boundary side's corners are not on the loop, or counts cannot match.
  BlockMesher(BlockLayout layout, SpacingField field);
  BlockMesher(BlockMesher&&) noexcept;
  ~BlockMesher();

  const BlockLayout& layout() const { return layout_; }
  std::size_t class_count() const { return classes_.size(); }

  /// Cells along the sides of each class at refinement s (>= 1 each).
  std::vector<int> class_cells(double refinement) const;
  /// Quads of the mesh at refinement s, without building it.
  std::int64_t quad_count(double refinement) const;
  /// Nodes of the mesh at refinement s, without building it.
  std::int64_t node_count(double refinement) const;
  QuadMesh mesh(double refinement) const;

 private:
  struct Edge {
    int v0 = 0, v1 = 0;         ///< canonical direction: v0 < v1
    bool boundary = false;
    bool loop_forward = false;  ///< the loop runs v0 -> v1 (boundary edges)
    double s0 = 0.0, s1 = 0.0;  ///< loop coordinates of v0 and v1, one of them unwrapped past the length
    double length = 0.0;
    int klass = 0;
    bool flipped = false;       ///< runs against its class's reference direction
  };
  struct Class {
    double length = 0.0;        ///< mean length of its sides
    std::vector<double> u;      ///< fraction of length, in the reference direction ...
    std::vector<double> cells;  ///< ... and the cells of the spacing field up to it, at refinement 1
  };
  struct Side {
    int edge = 0;
    bool forward = true;  ///< the side runs v0 -> v1 of its edge
  };

  void build_edges();
  void find_boundary_spans();
  void build_classes();
  /// Does the side meet a wall transversally at its end v0 (end 0) or v1 (end 1)?
  bool meets_wall(const Edge& e, int end) const;
  std::vector<double> fractions(const Class& c, int n) const;

  BlockLayout layout_;
  SpacingField field_;
  std::unique_ptr<BoundaryLoop> loop_;
  std::vector<double> vertex_s_;                  // loop coordinate of each vertex, or -1
  std::vector<Edge> edges_;
  std::vector<int> uses_;                         // blocks per edge
  std::vector<std::array<Side, 4>> block_sides_;  // P0->P1, P1->P2, P3->P2, P0->P3
  std::vector<Class> classes_;
};

}  // namespace hotmesh::samples
