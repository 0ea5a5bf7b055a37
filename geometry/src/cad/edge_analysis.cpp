// hotmesh geometry (internal): what a CAD edge is (edge_analysis.hpp).
#include "cad/edge_analysis.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRep_Tool.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopoDS_Vertex.hxx>

#include "cad/occt_convert.hpp"

namespace hotmesh::geometry {

const char* to_string(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::line: return "line";
    case EdgeKind::circle: return "circle";
    case EdgeKind::ellipse: return "ellipse";
    case EdgeKind::hyperbola: return "hyperbola";
    case EdgeKind::parabola: return "parabola";
    case EdgeKind::bezier: return "bezier";
    case EdgeKind::bspline: return "bspline";
    case EdgeKind::offset: return "offset";
    case EdgeKind::other: return "other";
    case EdgeKind::degenerated: return "degenerated";
  }
  return "?";
}

namespace detail {

namespace {

EdgeKind kind_of(GeomAbs_CurveType type) {
  switch (type) {
    case GeomAbs_Line: return EdgeKind::line;
    case GeomAbs_Circle: return EdgeKind::circle;
    case GeomAbs_Ellipse: return EdgeKind::ellipse;
    case GeomAbs_Hyperbola: return EdgeKind::hyperbola;
    case GeomAbs_Parabola: return EdgeKind::parabola;
    case GeomAbs_BezierCurve: return EdgeKind::bezier;
    case GeomAbs_BSplineCurve: return EdgeKind::bspline;
    case GeomAbs_OffsetCurve: return EdgeKind::offset;
    default: return EdgeKind::other;
  }
}

}  // namespace

EdgeInfo describe_edge(const TopoDS_Edge& edge, int id) {
  EdgeInfo info;
  info.id = id;
  if (BRep_Tool::Degenerated(edge)) {
    info.kind = EdgeKind::degenerated;
    if (const TopoDS_Vertex v = TopExp::FirstVertex(edge); !v.IsNull()) info.start = info.end = to_vec3(BRep_Tool::Pnt(v));
    return info;
  }
  try {
    const BRepAdaptor_Curve curve(edge);
    info.kind = kind_of(curve.GetType());
    info.start = to_vec3(curve.Value(curve.FirstParameter()));
    info.end = to_vec3(curve.Value(curve.LastParameter()));
    info.length = GCPnts_AbscissaPoint::Length(curve);
  } catch (const Standard_Failure&) {
    info.kind = EdgeKind::other;  // no curve to follow: listed, of no length
  }
  return info;
}

}  // namespace detail

}  // namespace hotmesh::geometry
