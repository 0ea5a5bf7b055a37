#include "hotmesh/mesh/solver_quality.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>

#include <vector>

#include "hotmesh/mesh/parallel_loops.hpp"
#include "solver_cells.hpp"

namespace hotmesh::mesh {

namespace {

using detail::Layer;
using detail::MeshFace;
using detail::Polygon;
using detail::SolverCells;

constexpr double kRootVSmall = 1e-150;  // OpenFOAM's ROOTVSMALL: keeps 0/0 finite
constexpr double kVSmall = 1e-300;      // OpenFOAM's VSMALL
constexpr double kDegenerateFace = 1e-9;  // of the cell's largest face: a face without area
constexpr double kOnTheAxis = 1e-6;       // of a 2D cell's largest thickness: a wedge's side on its axis
constexpr std::size_t kTypes = 7;  // ElementType's values

}  // namespace

FaceGeometry face_geometry(std::span<const Vec3> p) {
  const auto n = static_cast<int>(p.size());
  if (n == 3) return {(p[0] + p[1] + p[2]) / 3.0, 0.5 * cross(p[1] - p[0], p[2] - p[0])};
  Vec3 mean{};
  for (const Vec3& q : p) mean += q;
  mean = mean / n;
  Vec3 sum_normal{}, sum_weighted{};
  double sum_area = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vec3& a = p[static_cast<std::size_t>(i)];
    const Vec3& b = p[static_cast<std::size_t>((i + 1) % n)];
    const Vec3 normal = cross(b - a, mean - a);
    const double area = norm(normal);
    sum_normal += normal;
    sum_area += area;
    sum_weighted += area * (a + b + mean);
  }
  if (sum_area < kRootVSmall) return {mean, {}};
  return {sum_weighted / (3.0 * sum_area), 0.5 * sum_normal};
}

CellCentre cell_centre(std::span<const FaceGeometry> faces) {
  Vec3 estimate{};
  for (const FaceGeometry& face : faces) estimate += face.centre;
  estimate = estimate / static_cast<int>(faces.size());
  Vec3 weighted{};
  double volume3 = 0.0;
  for (const FaceGeometry& face : faces) {
    const double pyramid3 = dot(face.area, face.centre - estimate);
    weighted += pyramid3 * (0.75 * face.centre + 0.25 * estimate);
    volume3 += pyramid3;
  }
  return {std::abs(volume3) > kVSmall ? weighted / volume3 : estimate, volume3 / 3.0};
}

namespace {

double degrees(double cosine) { return std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi; }

FaceGeometry face_geometry(const Polygon& f) { return mesh::face_geometry(f.points()); }

using CellGeometry = CellMeasures;

// The distance from back to front at the two ends of a 2D cell's side face.
double side_thickness(const Polygon& side) { return std::max(norm(side[3] - side[0]), norm(side[2] - side[1])); }

double boundary_skewness(const Polygon& f, const FaceGeometry& g, const Vec3& cell_centre);

// The centre and volume from pyramids on the faces with their apex at the mean of the face
// centres (OpenFOAM's makeCellCentresAndVols), and the aspect ratio (cellClosedness).
CellGeometry cell_geometry(std::span<const Polygon> polygons, int sides, const Layer& layer) {
  CellGeometry cell;
  std::vector<FaceGeometry> large;
  std::array<FaceGeometry, kMaxElementFaces + 2> small{};
  if (polygons.size() > small.size()) large.resize(polygons.size());
  const std::span<FaceGeometry> g = large.empty() ? std::span<FaceGeometry>(small.data(), polygons.size()) : std::span<FaceGeometry>(large);
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    g[f] = face_geometry(polygons[f]);
    if (layer.planar && static_cast<int>(f) < sides) cell.thickness = std::max(cell.thickness, side_thickness(polygons[f]));
  }
  const CellCentre centre = cell_centre(g);
  cell.centre = centre.centre;
  cell.volume = centre.volume;
  Vec3 magnitudes{};
  for (const FaceGeometry& face : g) {
    magnitudes += Vec3{std::abs(face.area.x), std::abs(face.area.y), std::abs(face.area.z)};
    cell.largest_face = std::max(cell.largest_face, norm(face.area));
  }
  double smallest = 1e300, largest = -1e300;
  int dims = 0;
  for (int k = 0; k < 3; ++k) {
    if (!layer.axes[static_cast<std::size_t>(k)]) continue;
    ++dims;
    smallest = std::min(smallest, magnitudes[k]);
    largest = std::max(largest, magnitudes[k]);
  }
  cell.aspect_ratio = largest / (smallest + kRootVSmall);
  if (dims == 3) {
    const double v = std::max(kRootVSmall, cell.volume);
    cell.aspect_ratio =
        std::max(cell.aspect_ratio, (magnitudes.x + magnitudes.y + magnitudes.z) / 6.0 / std::pow(v, 2.0 / 3.0));
  }
  for (std::size_t f = static_cast<std::size_t>(sides); f < polygons.size(); ++f) {
    cell.planes_skewness = std::max(cell.planes_skewness, boundary_skewness(polygons[f], g[f], cell.centre));
  }
  return cell;
}

// The geometry of cell c: its faces, and a 2D cell's back and front planes.
CellGeometry cell_geometry(const SolverCells& cells, std::size_t c) {
  const int sides = cells.side_count(c);
  const bool planar = cells.layer().planar;
  const auto count = static_cast<std::size_t>(sides + (planar ? 2 : 0));
  std::vector<Polygon> large;
  std::array<Polygon, kMaxElementFaces + 2> small{};
  if (count > small.size()) large.resize(count);
  const std::span<Polygon> polygons = large.empty() ? std::span<Polygon>(small.data(), count) : std::span<Polygon>(large);
  for (int f = 0; f < sides; ++f) polygons[static_cast<std::size_t>(f)] = cells.polygon(c, f);
  if (planar) {
    auto planes = cells.planes(c);
    polygons[count - 2] = std::move(planes[0]);
    polygons[count - 1] = std::move(planes[1]);
  }
  return cell_geometry(polygons, sides, cells.layer());
}

// The skewness vector `sv` over the distance from the face centre to its edge along sv, at
// least `floor` (OpenFOAM's faceSkewness and boundaryFaceSkewness).
double normalised_skewness(const Polygon& f, const FaceGeometry& g, const Vec3& centre_to_face, const Vec3& d,
                           double floor) {
  const Vec3 sv = centre_to_face - (dot(g.area, centre_to_face) / (dot(g.area, d) + kRootVSmall)) * d;
  const Vec3 direction = sv / (norm(sv) + kRootVSmall);
  double reach = floor + kRootVSmall;
  for (int k = 0; k < f.size(); ++k) reach = std::max(reach, std::abs(dot(direction, f[k] - g.centre)));
  return norm(sv) / reach;
}

// A boundary face against the mirror image of its cell.
double boundary_skewness(const Polygon& f, const FaceGeometry& g, const Vec3& cell_centre) {
  const Vec3 to_face = g.centre - cell_centre;
  const Vec3 normal = g.area / (norm(g.area) + kRootVSmall);
  const Vec3 d = dot(normal, to_face) * normal;
  return normalised_skewness(f, g, to_face, d, 0.4 * norm(d));
}

void raise(WorstCell& worst, double value, CellId cell) {
  if (worst.cell < 0 || value > worst.value) worst = {value, cell};
}

// Adds the measures of one face to a summary (`internal`: between two cells).
struct Tally {
  SolverQualitySummary summary;
  double cosines = 0.0;
  bool seen = false;
  void add(const FaceMeasures& m, bool internal, CellId cell) {
    seen = true;
    raise(summary.max_skewness, m.skewness, cell);
    if (!internal) {
      raise(summary.max_boundary_non_orthogonality, m.non_orthogonality, cell);
      return;
    }
    ++summary.internal_faces;
    cosines += m.cosine;
    raise(summary.max_non_orthogonality, m.non_orthogonality, cell);
    if (m.non_orthogonality > kSevereNonOrthogonality) ++summary.severely_non_orthogonal_faces;
    raise(summary.max_volume_ratio, m.volume_ratio, cell);
  }
  void add_cell(double aspect_ratio, double planes_skewness, CellId cell) {
    seen = true;
    ++summary.cells;
    raise(summary.max_aspect_ratio, aspect_ratio, cell);
    raise(summary.max_skewness, planes_skewness, cell);
  }
  SolverQualitySummary finish() {
    if (summary.internal_faces > 0) {
      summary.mean_non_orthogonality = degrees(cosines / static_cast<double>(summary.internal_faces));
    }
    if (summary.max_volume_ratio.cell < 0) summary.max_volume_ratio.value = 1.0;
    return summary;
  }
};

// The measures of one face, between the cells of geometry `a` and `b` (nullptr: a boundary face).
FaceMeasures measure_face(const Polygon& polygon, const CellGeometry& a, const CellGeometry* b, const Layer& layer) {
  const FaceGeometry g = face_geometry(polygon);
  FaceMeasures m;
  const Vec3 to_face = g.centre - a.centre;
  if (b == nullptr) {
    // A face without area (a wedge's side on its axis) has no direction to measure.
    const bool on_axis = layer.planar && side_thickness(polygon) <= kOnTheAxis * a.thickness;
    if (!on_axis && norm(g.area) > kDegenerateFace * a.largest_face) {
      m.non_orthogonality = degrees(dot(g.area, to_face) / (norm(g.area) * norm(to_face) + kRootVSmall));
    }
    m.skewness = boundary_skewness(polygon, g, a.centre);
    return m;
  }
  const Vec3 d = b->centre - a.centre;
  m.cosine = dot(d, g.area) / (norm(d) * norm(g.area) + kRootVSmall);
  m.non_orthogonality = degrees(m.cosine);
  m.skewness = normalised_skewness(polygon, g, to_face, d, 0.2 * norm(d));
  const double small = std::min(std::abs(a.volume), std::abs(b->volume));
  const double large = std::max(std::abs(a.volume), std::abs(b->volume));
  m.volume_ratio = large / (small + kVSmall);
  return m;
}

// The values of the solver's cells given to every cell of the mesh (a polyhedron's to each of
// its pieces).
void spread_to_pieces(SolverQuality& q, const SolverCells& cells, std::size_t mesh_cells) {
  for (std::vector<double>* values : {&q.non_orthogonality, &q.skewness, &q.volume_ratio, &q.aspect_ratio}) {
    values->resize(mesh_cells);
    for (std::size_t c = cells.size(); c < mesh_cells; ++c) (*values)[c] = (*values)[cells.of_mesh_cell(c)];
  }
}

}  // namespace

SolverQuality solver_quality(const Mesh& mesh, std::span<const Vec3> points, const Extrusion& extrusion) {
  const SolverCells cells(mesh, points, detail::layer_of(mesh, points, extrusion));
  const auto n_cells = static_cast<std::ptrdiff_t>(cells.size());
  std::vector<CellGeometry> geometry(cells.size());
#pragma omp parallel for schedule(static) if (n_cells >= kParallelCells)
  for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
    geometry[static_cast<std::size_t>(c)] = cell_geometry(cells, static_cast<std::size_t>(c));
  }

  const std::vector<MeshFace> faces = cells.faces();
  const auto n_faces = static_cast<std::ptrdiff_t>(faces.size());
  std::vector<FaceMeasures> measures(faces.size());
#pragma omp parallel for schedule(static) if (n_faces >= kParallelCells)
  for (std::ptrdiff_t i = 0; i < n_faces; ++i) {
    const MeshFace& face = faces[static_cast<std::size_t>(i)];
    const auto own = static_cast<std::size_t>(face.owner.cell);
    const CellGeometry* other = face.neighbour.cell < 0 ? nullptr : &geometry[static_cast<std::size_t>(face.neighbour.cell)];
    measures[static_cast<std::size_t>(i)] = measure_face(cells.polygon(own, face.owner.local), geometry[own], other, cells.layer());
  }

  SolverQuality q;
  q.non_orthogonality.assign(cells.size(), 0.0);
  q.volume_ratio.assign(cells.size(), 1.0);
  q.skewness.resize(cells.size());
  q.aspect_ratio.resize(cells.size());
  Tally all;
  std::array<Tally, kTypes + 1> by_type;  // the last for polyhedra, which have no element type
  const auto type_of = [&](CellId c) {
    const auto type = cells.type(static_cast<std::size_t>(c));
    return type ? static_cast<std::size_t>(*type) : kTypes;
  };
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const auto id = static_cast<CellId>(c);
    q.aspect_ratio[c] = geometry[c].aspect_ratio;
    q.skewness[c] = geometry[c].planes_skewness;
    all.add_cell(geometry[c].aspect_ratio, geometry[c].planes_skewness, id);
    by_type[type_of(id)].add_cell(geometry[c].aspect_ratio, geometry[c].planes_skewness, id);
  }
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const MeshFace& face = faces[i];
    const FaceMeasures& m = measures[i];
    const bool internal = face.neighbour.cell >= 0;
    const CellId own = face.owner.cell;
    all.add(m, internal, own);
    by_type[type_of(own)].add(m, internal, own);
    for (CellId c : {own, face.neighbour.cell}) {
      if (c < 0) continue;
      const auto k = static_cast<std::size_t>(c);
      q.skewness[k] = std::max(q.skewness[k], m.skewness);
      if (!internal) continue;
      q.non_orthogonality[k] = std::max(q.non_orthogonality[k], m.non_orthogonality);
      q.volume_ratio[k] = std::max(q.volume_ratio[k], m.volume_ratio);
    }
    if (internal && type_of(face.neighbour.cell) != type_of(own)) by_type[type_of(face.neighbour.cell)].add(m, true, face.neighbour.cell);
  }
  q.summary = all.finish();
  for (std::size_t t = 0; t < kTypes; ++t) {
    if (by_type[t].seen) q.by_type[static_cast<ElementType>(t)] = by_type[t].finish();
  }
  spread_to_pieces(q, cells, mesh.cells.size());
  return q;
}

struct SolverFaces::Impl {
  SolverCells cells;
  std::vector<MeshFace> faces;
  std::vector<std::size_t> first;
  std::vector<std::uint32_t> cell_faces;
};

SolverFaces::SolverFaces(const Mesh& mesh, std::span<const Vec3> points, const Extrusion& layer)
    : impl_(std::make_unique<Impl>(Impl{SolverCells(mesh, points, detail::layer_of(mesh, points, layer)), {}, {}, {}})) {
  Impl& m = *impl_;
  m.faces = m.cells.faces();
  m.first.assign(m.cells.size() + 1, 0);
  for (const MeshFace& f : m.faces) {
    ++m.first[static_cast<std::size_t>(f.owner.cell) + 1];
    if (f.neighbour.cell >= 0) ++m.first[static_cast<std::size_t>(f.neighbour.cell) + 1];
  }
  for (std::size_t c = 0; c < m.cells.size(); ++c) m.first[c + 1] += m.first[c];
  m.cell_faces.resize(m.first.back());
  std::vector<std::size_t> next(m.first.begin(), m.first.end() - 1);
  for (std::size_t i = 0; i < m.faces.size(); ++i) {
    for (const CellId c : {m.faces[i].owner.cell, m.faces[i].neighbour.cell}) {
      if (c >= 0) m.cell_faces[next[static_cast<std::size_t>(c)]++] = static_cast<std::uint32_t>(i);
    }
  }
}

SolverFaces::~SolverFaces() = default;

std::size_t SolverFaces::cells() const { return impl_->cells.size(); }
std::size_t SolverFaces::size() const { return impl_->faces.size(); }
CellId SolverFaces::owner(std::size_t face) const { return impl_->faces[face].owner.cell; }
CellId SolverFaces::neighbour(std::size_t face) const { return impl_->faces[face].neighbour.cell; }
std::size_t SolverFaces::of_mesh_cell(std::size_t c) const { return impl_->cells.of_mesh_cell(c); }

std::span<const std::uint32_t> SolverFaces::of_cell(std::size_t c) const {
  return {impl_->cell_faces.data() + impl_->first[c], impl_->cell_faces.data() + impl_->first[c + 1]};
}

CellMeasures SolverFaces::cell(std::size_t c) const { return cell_geometry(impl_->cells, c); }

FaceMeasures SolverFaces::face(std::size_t i, const CellMeasures& owner, const CellMeasures* neighbour) const {
  const MeshFace& f = impl_->faces[i];
  return measure_face(impl_->cells.polygon(static_cast<std::size_t>(f.owner.cell), f.owner.local), owner,
                      f.neighbour.cell >= 0 ? neighbour : nullptr, impl_->cells.layer());
}

}  // namespace hotmesh::mesh
