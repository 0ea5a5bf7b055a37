// hotmesh geometry: the wall of a 2D case drawn in CAD (section 4.2 in the plane): the curves of
// some edges in the mesh's plane z = 0, converted exactly to B-splines (circles stay circles:
// rational) and joined end to end into one curve r(t) in (x, y), C0 at the vertices the edges
// share, so that the deflected wall keeps the CAD's corners (DeflectedCurve::corners) and,
// in displacement form (eq. 21), its curvature between FEM nodes.
#include <BRepBndLib.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Curve.hxx>
#include <Standard_Failure.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "cad/cad_model_impl.hpp"
#include "cad/occt_convert.hpp"
#include "cad/profile_chain.hpp"
#include "hotmesh/core/input_error.hpp"

namespace hotmesh::geometry {

namespace {

std::string number(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

/// The edges' size: the diagonal of their bounding box.
double size_of(const TopTools_IndexedMapOfShape& edges, std::span<const int> ids) {
  Bnd_Box box;
  for (const int id : ids) BRepBndLib::Add(edges(id), box);
  return box.IsVoid() ? 0.0 : std::sqrt(box.SquareExtent());
}

/// The edge's curve in the plane z = 0, as (y, x): join_profile orients its curves so that their
/// second coordinate grows, which is then x. Throws hotmesh::InputError naming the edge.
detail::ProfilePiece plane_piece(const TopoDS_Edge& edge, int id, double tolerance, const std::string& source) {
  const std::string name = "edge " + std::to_string(id);
  if (BRep_Tool::Degenerated(edge)) throw InputError::in(source, name + " is collapsed to a point: it is no wall");
  double first = 0.0, last = 0.0;
  const Handle(Geom_Curve) curve = BRep_Tool::Curve(edge, first, last);
  if (curve.IsNull() || !(last > first)) throw InputError::in(source, name + " has no 3D curve to follow");
  const Handle(Geom_BSplineCurve) bspline = detail::to_bspline(curve, first, last);
  // The curve lies within the hull of its poles: poles within the tolerance of the plane keep
  // the whole edge there.
  double off = 0.0;
  for (Standard_Integer i = 1; i <= bspline->NbPoles(); ++i) off = std::max(off, std::abs(bspline->Pole(i).Z()));
  if (off > std::max(tolerance, BRep_Tool::Tolerance(edge))) {
    throw InputError::in(source, name + " is not in the mesh's plane z = 0: it reaches " + number(off) +
                                     " from it (tolerance " + number(tolerance) +
                                     "); a 2D case's edges are drawn in that plane, in the mesh's coordinates");
  }
  return {detail::to_plane_curve(bspline, [](const Vec3& p) { return Vec2{p.y, p.x}; }), id};
}

}  // namespace

PlanarCurve CadModel::planar_curve(std::span<const int> edge_ids, const PlanarCurveOptions& options) const {
  const std::string source = impl_->path.string();
  if (edge_ids.empty()) throw InputError::in(source, "no edges given for the curve");
  for (const int id : edge_ids) {
    edge(id);
    if (std::count(edge_ids.begin(), edge_ids.end(), id) > 1) {
      throw InputError::in(source, "edge " + std::to_string(id) + " is given twice");
    }
  }
  const double tolerance = options.relative_tolerance * size_of(impl_->edges, edge_ids);
  std::vector<detail::ProfilePiece> pieces;
  try {
    for (const int id : edge_ids) pieces.push_back(plane_piece(TopoDS::Edge(impl_->edges(id)), id, tolerance, source));
  } catch (const Standard_Failure& e) {
    throw InputError::in(source, std::string("OpenCASCADE failed on the edges' curves: ") + e.GetMessageString());
  }
  detail::Profile profile = detail::join_profile(std::move(pieces), tolerance, source, detail::kEdgeWords);
  return {profile.curve.swapped_coordinates(), std::move(profile.faces), std::move(profile.face_breaks), tolerance};
}

}  // namespace hotmesh::geometry
