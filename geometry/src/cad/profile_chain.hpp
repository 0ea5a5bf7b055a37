// hotmesh geometry (internal): joining the meridional curves of several faces (or several
// pieces of one face's section), or the curves of several planar edges, into one profile curve. Pieces that repeat part of a longer
// one (the halves of a revolved face, faces split by a slot) are dropped; the rest are ordered
// end to end and oriented, each given a parameter interval proportional to its length, raised
// to a common degree, and concatenated into one B-spline with parameter [0, 1], C0 where the
// pieces meet. Pieces that form several separate profiles (a casing interrupted by a blade
// row) can also be joined into one profile per connected group.
#pragma once

#include <string>
#include <vector>

#include "hotmesh/geometry/bspline_curve.hpp"

namespace hotmesh::geometry::detail {

struct ProfilePiece {
  BSplineCurve2d curve;
  int id = 0;  ///< the CAD face (or edge) it comes from
};

struct Profile {
  BSplineCurve2d curve;
  std::vector<int> faces;           ///< in order along the curve (a face, or edge, once)
  std::vector<double> face_breaks;  ///< parameter where each of `faces` starts, then 1
};

/// What messages call the pieces' sources and their curves.
struct PieceWords {
  const char* piece;  ///< "face", "edge"
  const char* curve;  ///< "meridional curve", "curve"
  const char* whole;  ///< "one connected profile", "one chain"
};
inline constexpr PieceWords kFaceWords{"face", "meridional curve", "one connected profile"};
inline constexpr PieceWords kEdgeWords{"edge", "curve", "one chain"};

/// Throws hotmesh::InputError (naming `source` and the faces, or edges, as `words` call them)
/// if the pieces do not form one chain with ends within `tolerance`.
Profile join_profile(std::vector<ProfilePiece> pieces, double tolerance, const std::string& source,
                     const PieceWords& words = kFaceWords);

/// One profile per connected group of pieces (pieces whose ends meet within `tolerance`,
/// directly or through others), in the order of each group's first face among `pieces`.
/// Throws hotmesh::InputError if a group does not form one chain (it branches).
std::vector<Profile> join_profiles(std::vector<ProfilePiece> pieces, double tolerance, const std::string& source);

/// Orientation rule of profiles: z grows from start to end; at equal z, r grows.
bool runs_backwards(const Vec2& start, const Vec2& end, double tolerance);

}  // namespace hotmesh::geometry::detail
