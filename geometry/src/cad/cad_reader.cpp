// hotmesh geometry: reading STEP and IGES files into a CadModel: the transfer (serialised,
// in the caller's length unit), the faces in file order with their names, kinds, bounds and
// axes, the edges numbered (those of the faces, then those outside any face), and clear errors
// for files that are not CAD, are empty or hold neither faces nor edges.
#include <BRepAdaptor_Curve.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <Bnd_Box.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <GeomConvert.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_CheckIterator.hxx>
#include <Interface_Check.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Transfer_TransientProcess.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESData_IGESEntity.hxx>
#include <OSD_Signal.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <StepRepr_RepresentationItem.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Compound.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <optional>
#include <string>

#include "cad/cad_model_impl.hpp"
#include "cad/edge_analysis.hpp"
#include "cad/face_analysis.hpp"
#include "cad/occt_convert.hpp"
#include "cad/occt_session.hpp"
#include "cad/step_entity_numbers.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/core/text.hpp"
#include "reconstruct/cad_face_set.hpp"

namespace hotmesh::geometry {

namespace {

enum class Format { step, iges };

Format format_of(const std::filesystem::path& path) {
  const std::string extension = ascii_lower(path.extension().string());
  if (extension == ".step" || extension == ".stp") return Format::step;
  if (extension == ".iges" || extension == ".igs") return Format::iges;
  throw InputError::in(path.string(), "unknown CAD format '" + path.extension().string() +
                                          "' (hotmesh reads STEP .step/.stp and IGES .iges/.igs)");
}

/// Checks what OpenCASCADE's parsers report badly: missing, unreadable, empty, not STEP.
void check_file(const std::filesystem::path& path, Format format) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw InputError::in(path.string(), "no such CAD file");
  require_input_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError::in(path.string(), "cannot open the CAD file");
  std::string head(256, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (trim(head, kWhiteSpace).empty()) throw InputError::in(path.string(), "the CAD file is empty");
  if (format == Format::step && !trim(head, kWhiteSpace).starts_with("ISO-10303-21")) {
    throw InputError::in(path.string(), "not a STEP file: it does not start with ISO-10303-21");
  }
}

/// A face's name as the file gives it: the STEP item's name or the IGES entity's name/label.
std::string face_name(const Handle(XSControl_TransferReader)& transfer, const TopoDS_Face& face) {
  Handle(Standard_Transient) entity = transfer->EntityFromShapeResult(face, 1);
  if (entity.IsNull()) entity = transfer->EntityFromShapeResult(face, -1);
  std::string name;
  if (const auto item = Handle(StepRepr_RepresentationItem)::DownCast(entity); !item.IsNull() && !item->Name().IsNull()) {
    name = item->Name()->ToCString();
  } else if (const auto iges = Handle(IGESData_IGESEntity)::DownCast(entity); !iges.IsNull()) {
    if (iges->HasName()) {
      name = iges->NameValue()->ToCString();
    } else if (iges->HasShortLabel()) {
      name = iges->ShortLabel()->ToCString();
    }
  }
  name = std::string(trim(name, kWhiteSpace));
  return name == "NONE" ? std::string() : name;  // STEP writers' word for "no name"
}

std::string status_text(IFSelect_ReturnStatus status) {
  switch (status) {
    case IFSelect_RetVoid: return "nothing could be read";
    case IFSelect_RetDone: return "read";
    case IFSelect_RetError: return "it has syntax errors or is truncated";
    case IFSelect_RetFail: return "the reader failed (is the file complete?)";
    case IFSelect_RetStop: return "the reader stopped";
  }
  return "unknown reader status";
}

/// A damaged entity (a reference to one that is missing or of the wrong type) fails to
/// translate, often with a fault that OpenCASCADE catches itself (FaultsAsFailures), and its
/// face would be left out silently, renumbering the faces after it: refused, naming them.
/// Real CAD files translate without a single failure.
template <class Reader>
void refuse_failed_entities(Reader& reader, const std::filesystem::path& path, const char* format_name) {
  const Handle(Interface_InterfaceModel) model = reader.WS()->Model();
  const Interface_CheckIterator checks = reader.WS()->TransferReader()->TransientProcess()->CheckList(false);
  std::vector<std::string> failed;
  for (checks.Start(); checks.More(); checks.Next()) {
    const Handle(Interface_Check)& check = checks.Value();
    if (check->NbFails() == 0) continue;
    std::string entity = "the file as a whole";
    if (const Handle(Standard_Transient) e = check->Entity(); !e.IsNull() && !model.IsNull() && model->Contains(e)) {
      entity = std::string("entity ") + model->StringLabel(e)->ToCString() + " (" + model->TypeName(e, false) + ")";
    } else if (checks.Number() > 0) {
      entity = "entity number " + std::to_string(checks.Number());
    }
    failed.push_back(entity + ": " + check->CFail(1));
  }
  if (failed.empty()) return;
  std::string list;
  for (std::size_t i = 0; i < std::min<std::size_t>(failed.size(), 5); ++i) list += "\n  " + failed[i];
  if (failed.size() > 5) list += "\n  ... and " + std::to_string(failed.size() - 5) + " more";
  throw InputError::in(path.string(), std::string("the ") + format_name + " file is damaged: " +
                                          std::to_string(failed.size()) + " of its entities could not be translated, "
                                          "so faces would be missing and the others renumbered:" + list);
}

/// Reads and transfers the file; fills the faces in exploration order and their names (while
/// the reader, which owns the entity records, is alive).
template <class Reader>
void transfer(Reader& reader, const std::filesystem::path& path, const char* format_name, TopoDS_Shape& shape,
              std::vector<TopoDS_Face>& faces, std::vector<std::string>& names) {
  const IFSelect_ReturnStatus status = reader.ReadFile(path.string().c_str());
  if (status != IFSelect_RetDone) {
    throw InputError::in(path.string(), std::string("cannot be read as ") + format_name + ": " + status_text(status));
  }
  if (reader.NbRootsForTransfer() == 0) {
    throw InputError::in(path.string(), std::string("the ") + format_name + " file holds no shapes");
  }
  reader.TransferRoots();
  refuse_failed_entities(reader, path, format_name);
  shape = reader.OneShape();
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(shape, TopAbs_FACE, map);
  if (map.IsEmpty()) {
    TopTools_IndexedMapOfShape edges;
    TopExp::MapShapes(shape, TopAbs_EDGE, edges);
    if (edges.IsEmpty()) {
      throw InputError::in(path.string(), "the file holds no faces and no edges: hotmesh needs the boundary's "
                                          "surfaces, or the edges of a 2D case's walls");
    }
  }
  const Handle(XSControl_TransferReader) records = reader.WS()->TransferReader();
  for (Standard_Integer i = 1; i <= map.Extent(); ++i) {
    faces.push_back(TopoDS::Face(map(i)));
    names.push_back(face_name(records, faces.back()));
  }
}

/// Faces from separate surfaces (an IGES file of trimmed surfaces rather than a solid, as CATIA
/// writes them) share no edge where they meet, so nothing joins them there. Where the faces have
/// free edges, they are sewn together on a copy (to 1e-5 of the model's size) and each face
/// replaced by its sewn self: the same surface, bounded by the edges it shares with the faces it
/// meets. A solid's faces, which have no free edges, are left as they are.
void sew_faces(std::vector<TopoDS_Face>& faces) {
  if (faces.size() < 2) return;
  TopoDS_Compound all;
  BRep_Builder builder;
  builder.MakeCompound(all);
  for (const TopoDS_Face& f : faces) builder.Add(all, f);
  TopTools_IndexedDataMapOfShapeListOfShape owners;
  TopExp::MapShapesAndAncestors(all, TopAbs_EDGE, TopAbs_FACE, owners);
  bool free = false;
  for (Standard_Integer i = 1; i <= owners.Extent() && !free; ++i) {
    const TopoDS_Edge& edge = TopoDS::Edge(owners.FindKey(i));
    free = owners(i).Extent() == 1 && !BRep_Tool::Degenerated(edge) &&
           !BRep_Tool::IsClosed(edge, TopoDS::Face(owners(i).First()));
  }
  if (!free) return;
  Bnd_Box box;
  BRepBndLib::Add(all, box);
  if (box.IsVoid()) return;
  BRepBuilderAPI_Sewing sewing(1e-5 * std::sqrt(box.SquareExtent()));
  for (const TopoDS_Face& f : faces) sewing.Add(f);
  sewing.Perform();
  for (TopoDS_Face& f : faces) {
    if (!sewing.IsModified(f)) continue;
    const TopoDS_Shape& sewn = sewing.Modified(f);
    if (!sewn.IsNull() && sewn.ShapeType() == TopAbs_FACE) f = TopoDS::Face(sewn);
  }
}

/// The (t, s) of the face's B-spline form `b` at the point `target` of OpenCASCADE's surface at
/// (u, v): (u, v) itself where the face is a B-spline or a plane; near it where the conversion
/// reparametrised (a cylinder's rational form runs at another speed between its knots), found
/// by Gauss-Newton from (u, v) within the rectangle. At a pole every t is the point: it stays.
Vec2 bspline_parameter(const BSplineSurface& b, const Vec3& target, Vec2 x, double tolerance) {
  const ParameterRectangle r = b.domain();
  x = {std::clamp(x.x, r.u_first, r.u_last), std::clamp(x.y, r.v_first, r.v_last)};
  for (int iteration = 0; iteration < 30; ++iteration) {
    const SurfaceDerivatives d = b.derivatives(x.x, x.y);
    const Vec3 miss = d.point - target;
    if (norm(miss) <= tolerance) break;
    const double a = dot(d.du, d.du), c = dot(d.du, d.dv), e = dot(d.dv, d.dv);
    const double g0 = dot(miss, d.du), g1 = dot(miss, d.dv);
    const double det = a * e - c * c;
    if (!(det > 1e-14 * a * e)) break;
    const Vec2 step{(c * g1 - e * g0) / det, (c * g0 - a * g1) / det};
    x = {std::clamp(x.x + step.x, r.u_first, r.u_last), std::clamp(x.y + step.y, r.v_first, r.v_last)};
    if (norm(step.x * d.du + step.y * d.dv) <= tolerance) break;
  }
  return x;
}

/// The curve of `edge` on face f in the (t, s) of the face's B-spline form, in the edge's
/// direction on the face: its pcurve sampled evenly in the edge's parameter, 64 segments
/// doubled until the polyline's midpoints are within 1e-6 of the rectangle's extent of the
/// pcurve's (4096 at most). `size`: the face's, for the tolerance of the mapping.
std::vector<Vec2> trim_points(const TopoDS_Face& f, const TopoDS_Edge& edge, const BSplineSurface& b, double size) {
  double first = 0.0, last = 0.0;
  const Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(edge, f, first, last);
  if (pcurve.IsNull()) throw Standard_Failure("no curve on the face");
  const ParameterRectangle r = b.domain();
  const double extent = std::max(r.u_last - r.u_first, r.v_last - r.v_first);
  const auto at = [&](int k, int n) {
    const gp_Pnt2d p = pcurve->Value(first + (last - first) * k / n);
    return Vec2{p.X(), p.Y()};
  };
  int n = 64;
  for (; n < 4096; n *= 2) {
    double deviation = 0.0;
    for (int k = 0; k < n; ++k) deviation = std::max(deviation, distance(at(2 * k + 1, 2 * n), 0.5 * (at(k, n) + at(k + 1, n))));
    if (deviation <= 1e-6 * extent) break;
  }
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(f);
  std::vector<Vec2> points;
  for (int k = 0; k <= n; ++k) {
    const Vec2 uv = at(k, n);
    points.push_back(bspline_parameter(b, detail::to_vec3(surface->Value(uv.x, uv.y)), uv, 1e-12 * size));
  }
  if (edge.Orientation() == TopAbs_REVERSED) std::reverse(points.begin(), points.end());
  return points;
}

}  // namespace

const char* to_string(LengthUnit unit) { return kLengthUnitNames.name(unit).data(); }

std::optional<LengthUnit> parse_length_unit(std::string_view text) { return kLengthUnitNames.parse(text); }

const char* to_string(SurfaceKind kind) {
  switch (kind) {
    case SurfaceKind::plane: return "plane";
    case SurfaceKind::cylinder: return "cylinder";
    case SurfaceKind::cone: return "cone";
    case SurfaceKind::sphere: return "sphere";
    case SurfaceKind::torus: return "torus";
    case SurfaceKind::revolution: return "revolution";
    case SurfaceKind::extrusion: return "extrusion";
    case SurfaceKind::bspline: return "bspline";
    case SurfaceKind::bezier: return "bezier";
    case SurfaceKind::offset: return "offset";
    case SurfaceKind::other: return "other";
  }
  return "?";
}

const char* to_string(AxisSource source) {
  switch (source) {
    case AxisSource::none: return "none";
    case AxisSource::analytic: return "analytic";
    case AxisSource::fitted: return "fitted";
  }
  return "?";
}

CadModel::CadModel(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CadModel::CadModel(CadModel&&) noexcept = default;
CadModel& CadModel::operator=(CadModel&&) noexcept = default;
CadModel::~CadModel() = default;

const std::filesystem::path& CadModel::path() const { return impl_->path; }
LengthUnit CadModel::unit() const { return impl_->unit; }
const std::vector<FaceInfo>& CadModel::faces() const { return impl_->info; }

const std::vector<EdgeInfo>& CadModel::edges() const { return impl_->edge_info; }

const EdgeInfo& CadModel::edge(int id) const {
  if (id < 1 || static_cast<std::size_t>(id) > impl_->edge_info.size()) {
    throw InputError::in(impl_->path.string(), "no edge " + std::to_string(id) + ": the edges are 1 to " +
                                                   std::to_string(impl_->edge_info.size()));
  }
  return impl_->edge_info[static_cast<std::size_t>(id - 1)];
}

const FaceInfo& CadModel::face(int id) const {
  if (id < 1 || static_cast<std::size_t>(id) > impl_->info.size()) {
    throw InputError::in(impl_->path.string(), "no face " + std::to_string(id) + ": the faces are 1 to " +
                                                   std::to_string(impl_->info.size()));
  }
  return impl_->info[static_cast<std::size_t>(id - 1)];
}

CadModel CadModel::read(const std::filesystem::path& path, const CadReadOptions& options) {
  const Format format = format_of(path);
  check_file(path, format);
  if (format == Format::step) detail::refuse_repeated_entity_numbers(path);
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->unit = options.unit;
  std::vector<std::string> names;
  try {
    detail::OcctSession session;
    session.use_unit(options.unit);
    // A damaged file (a reference to a missing or wrong entity) can make the translation
    // follow a null pointer: a bad input, not a crash.
    const detail::FaultsAsFailures faults;
    // The reader lives outside the jump's scope: after a fault it is destroyed as the failure
    // unwinds, with the file's model it holds (only what the faulting calls held is lost).
    std::optional<STEPControl_Reader> step;
    std::optional<IGESControl_Reader> iges;
    {
      OCC_CATCH_SIGNALS
      if (format == Format::step) {
        transfer(step.emplace(), path, "STEP", impl->shape, impl->faces, names);
      } else {
        transfer(iges.emplace(), path, "IGES", impl->shape, impl->faces, names);
      }
    }
    for (std::size_t i = 0; i < impl->faces.size(); ++i) {
      const TopoDS_Face& face = impl->faces[i];
      FaceInfo info;
      info.id = static_cast<int>(i) + 1;
      info.name = names[i];
      info.kind = detail::surface_kind(face);
      info.bounds = detail::face_bounds(face);
      const detail::FaceAxis axis = detail::face_axis(face, info.kind);
      info.axis = axis.axis;
      info.axis_source = axis.source;
      impl->info.push_back(std::move(info));
    }
    sew_faces(impl->faces);
    for (const TopoDS_Face& f : impl->faces) TopExp::MapShapes(f, TopAbs_EDGE, impl->edges);
    for (TopExp_Explorer it(impl->shape, TopAbs_EDGE, TopAbs_FACE); it.More(); it.Next()) impl->edges.Add(it.Current());
    for (Standard_Integer i = 1; i <= impl->edges.Extent(); ++i) {
      impl->edge_info.push_back(detail::describe_edge(TopoDS::Edge(impl->edges(i)), i));
    }
  } catch (const Standard_Failure& e) {
    // A fault (FaultsAsFailures) comes as OSD_SIGSEGV, or as a plain failure when it was a
    // stack overflow; either way the file, not hotmesh, is at fault.
    const std::string what = e.GetMessageString();
    const bool fault = e.IsKind(STANDARD_TYPE(OSD_Signal)) || what.find("Signal") != std::string::npos;
    throw InputError::in(path.string(), std::string("the ") + (format == Format::step ? "STEP" : "IGES") +
                                            " file is damaged: " +
                                            (fault ? "its translation faulted inside OpenCASCADE (an entity refers to "
                                                     "a missing one, to itself or to one of the wrong type)"
                                                   : "OpenCASCADE could not translate it: " + what));
  }
  return CadModel(std::move(impl));
}

CadFace CadModel::cad_face(int id) const {
  CadFace out{id, face_bspline(id), {}, {}};
  const TopoDS_Face& f = impl_->faces[static_cast<std::size_t>(id - 1)];
  bool every_trim = true;
  const detail::Box box = detail::pole_box(out.surface);
  const double size = distance(box.lo, box.hi);
  for (TopExp_Explorer it(f, TopAbs_EDGE); it.More(); it.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(it.Current());
    // A seam bounds the face on both sides of its parameter rectangle: it joins the face to
    // itself, not to another face.
    const bool own = BRep_Tool::Degenerated(edge) || BRep_Tool::IsClosed(edge, f);
    const int number = impl_->edges.FindIndex(edge);
    try {
      out.trims.push_back({own ? 0 : number, trim_points(f, edge, out.surface, size)});
    } catch (const Standard_Failure&) {
      every_trim = false;  // an edge without its curve on the face: the loops cannot close
    }
    if (own) continue;
    try {
      const BRepAdaptor_Curve curve(edge);
      const double first = curve.FirstParameter(), last = curve.LastParameter();
      FaceEdge traced{number, {}};
      for (int k = 0; k < kFaceEdgePoints; ++k) {
        traced.points.push_back(detail::to_vec3(curve.Value(first + (last - first) * k / (kFaceEdgePoints - 1))));
      }
      if (traced.edge > 0) out.edges.push_back(std::move(traced));
    } catch (const Standard_Failure&) {
      // An edge without a curve to follow: the face keeps the edges it has.
    }
  }
  if (!every_trim) out.trims.clear();  // the whole rectangle, rather than loops with a gap
  return out;
}

BSplineSurface CadModel::face_bspline(int id) const {
  face(id);
  const TopoDS_Face& f = impl_->faces[static_cast<std::size_t>(id - 1)];
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  try {
    const Handle(Geom_Surface) bounded = new Geom_RectangularTrimmedSurface(BRep_Tool::Surface(f), u0, u1, v0, v1);
    return detail::to_surface(GeomConvert::SurfaceToBSplineSurface(bounded));
  } catch (const Standard_Failure& e) {
    throw InputError::in(impl_->path.string(), "face " + std::to_string(id) +
                                                   " has no B-spline form: " + e.GetMessageString());
  }
}

}  // namespace hotmesh::geometry
