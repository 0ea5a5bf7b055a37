#include "hotmesh/mesh/solver_quality.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "hotmesh/mesh/mesh_topology.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

namespace hotmesh::mesh {

namespace {

constexpr double kRootVSmall = 1e-150;  // OpenFOAM's ROOTVSMALL: keeps 0/0 finite
constexpr double kVSmall = 1e-300;      // OpenFOAM's VSMALL
constexpr int kPolygonPoints = 4;
constexpr double kDegenerateFace = 1e-9;  // of the cell's largest face: a face without area
constexpr double kOnTheAxis = 1e-6;       // of a 2D cell's largest thickness: a wedge's side on its axis
constexpr std::size_t kTypes = 7;  // ElementType's values

double degrees(double cosine) { return std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi; }

struct Polygon {
  std::array<Vec3, kPolygonPoints> p{};
  int n = 0;
};

struct FaceGeometry {
  Vec3 centre, area;
};

// The face centre and area vector: for a triangle its centroid and half the cross product;
// otherwise the triangles from each edge to the points' mean, their centroids weighted by
// their areas, and half the sum of their normals (OpenFOAM's makeFaceCentresAndAreas).
FaceGeometry face_geometry(const Polygon& f) {
  const auto& p = f.p;
  if (f.n == 3) return {(p[0] + p[1] + p[2]) / 3.0, 0.5 * cross(p[1] - p[0], p[2] - p[0])};
  Vec3 mean{};
  for (int i = 0; i < f.n; ++i) mean += p[static_cast<std::size_t>(i)];
  mean = mean / f.n;
  Vec3 sum_normal{}, sum_weighted{};
  double sum_area = 0.0;
  for (int i = 0; i < f.n; ++i) {
    const Vec3& a = p[static_cast<std::size_t>(i)];
    const Vec3& b = p[static_cast<std::size_t>((i + 1) % f.n)];
    const Vec3 normal = cross(b - a, mean - a);
    const double area = norm(normal);
    sum_normal += normal;
    sum_area += area;
    sum_weighted += area * (a + b + mean);
  }
  if (sum_area < kRootVSmall) return {mean, {}};
  return {sum_weighted / (3.0 * sum_area), 0.5 * sum_normal};
}

// How a 2D mesh's cells stand in 3D, and which Cartesian axes the aspect ratio compares.
struct Layer {
  bool planar = false;  // a 2D mesh, measured as the prisms of `extrusion`
  Extrusion extrusion;
  std::array<bool, 3> axes{true, true, true};
  Vec3 back(const Vec3& p) const { return extrusion.back.at(p); }
  Vec3 front(const Vec3& p) const { return extrusion.front.at(p); }
};

Layer layer_of(const Mesh& mesh, std::span<const Vec3> points, const Extrusion& extrusion) {
  Layer layer;
  if (mesh.dimension != 2 || points.empty()) return layer;
  layer.planar = true;
  layer.extrusion = extrusion;
  // The prisms must run from back to front along the right-hand normal of the 2D cells (which
  // validate_mesh orients counter-clockwise), so that every face's area vector points out.
  Vec3 centre{};
  for (const Vec3& p : points) centre += p;
  centre = centre / static_cast<double>(points.size());
  const Vec3 through = extrusion.front.at(centre) - extrusion.back.at(centre);
  if (dot(cross(extrusion.back.u, extrusion.back.v), through) < 0.0) std::swap(layer.extrusion.back, layer.extrusion.front);
  // The axis the layer is thin along (an empty or wedge direction) is left out, as OpenFOAM
  // leaves out the directions that are not geometric.
  int thin = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(through[k]) > std::abs(through[thin])) thin = k;
  }
  layer.axes[static_cast<std::size_t>(thin)] = false;
  return layer;
}

// Face `local` of cell `c` as a polygon in 3D, outward: a 3D cell's face, or the side of a 2D
// cell's prism over its edge `local`.
Polygon face_polygon(const ElementList& cells, std::size_t c, int local, std::span<const Vec3> points,
                     const Layer& layer) {
  const LocalFace& f = faces(cells.type(c))[static_cast<std::size_t>(local)];
  const auto nodes = cells.nodes(c);
  const auto point = [&](int k) { return points[static_cast<std::size_t>(nodes[f.nodes[static_cast<std::size_t>(k)]])]; };
  Polygon polygon;
  if (!layer.planar) {
    polygon.n = f.count;
    for (int k = 0; k < f.count; ++k) polygon.p[static_cast<std::size_t>(k)] = point(k);
    return polygon;
  }
  const Vec3 a = point(0), b = point(1);
  polygon.n = 4;
  polygon.p = {layer.back(a), layer.back(b), layer.front(b), layer.front(a)};
  return polygon;
}

struct CellGeometry {
  Vec3 centre;
  double volume = 0.0;
  double aspect_ratio = 1.0;
  double planes_skewness = 0.0;  // a 2D cell's back and front faces
  double largest_face = 0.0;     // the area of its largest face
  double thickness = 0.0;        // a 2D cell's largest distance from back to front
};

// The distance from back to front at the two ends of a 2D cell's side face.
double side_thickness(const Polygon& side) { return std::max(norm(side.p[3] - side.p[0]), norm(side.p[2] - side.p[1])); }

double boundary_skewness(const Polygon& f, const FaceGeometry& g, const Vec3& cell_centre);

// The centre and volume from pyramids on the faces with their apex at the mean of the face
// centres (OpenFOAM's makeCellCentresAndVols), and the aspect ratio (cellClosedness).
CellGeometry cell_geometry(const ElementList& cells, std::size_t c, std::span<const Vec3> points, const Layer& layer) {
  std::array<Polygon, kMaxElementFaces + 2> polygons{};
  const auto sides = static_cast<int>(faces(cells.type(c)).size());
  int count = 0;
  CellGeometry cell;
  for (int f = 0; f < sides; ++f) {
    polygons[static_cast<std::size_t>(count)] = face_polygon(cells, c, f, points, layer);
    if (layer.planar) cell.thickness = std::max(cell.thickness, side_thickness(polygons[static_cast<std::size_t>(count)]));
    ++count;
  }
  if (layer.planar) {
    const auto nodes = cells.nodes(c);
    const auto n = static_cast<int>(nodes.size());
    Polygon& back = polygons[static_cast<std::size_t>(count++)];
    Polygon& front = polygons[static_cast<std::size_t>(count++)];
    back.n = front.n = n;
    for (int k = 0; k < n; ++k) {
      const Vec3& p = points[static_cast<std::size_t>(nodes[static_cast<std::size_t>(k)])];
      back.p[static_cast<std::size_t>(n - 1 - k)] = layer.back(p);
      front.p[static_cast<std::size_t>(k)] = layer.front(p);
    }
  }
  std::array<FaceGeometry, kMaxElementFaces + 2> g{};
  Vec3 estimate{};
  for (int f = 0; f < count; ++f) {
    g[static_cast<std::size_t>(f)] = face_geometry(polygons[static_cast<std::size_t>(f)]);
    estimate += g[static_cast<std::size_t>(f)].centre;
  }
  estimate = estimate / count;
  Vec3 weighted{}, magnitudes{};
  double volume3 = 0.0;
  for (int f = 0; f < count; ++f) {
    const FaceGeometry& face = g[static_cast<std::size_t>(f)];
    const double pyramid3 = dot(face.area, face.centre - estimate);
    weighted += pyramid3 * (0.75 * face.centre + 0.25 * estimate);
    volume3 += pyramid3;
    magnitudes += Vec3{std::abs(face.area.x), std::abs(face.area.y), std::abs(face.area.z)};
    cell.largest_face = std::max(cell.largest_face, norm(face.area));
  }
  cell.centre = std::abs(volume3) > kVSmall ? weighted / volume3 : estimate;
  cell.volume = volume3 / 3.0;
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
  for (int f = sides; f < count; ++f) {
    cell.planes_skewness = std::max(cell.planes_skewness,
                                    boundary_skewness(polygons[static_cast<std::size_t>(f)], g[static_cast<std::size_t>(f)], cell.centre));
  }
  return cell;
}

// The skewness vector `sv` over the distance from the face centre to its edge along sv, at
// least `floor` (OpenFOAM's faceSkewness and boundaryFaceSkewness).
double normalised_skewness(const Polygon& f, const FaceGeometry& g, const Vec3& centre_to_face, const Vec3& d,
                           double floor) {
  const Vec3 sv = centre_to_face - (dot(g.area, centre_to_face) / (dot(g.area, d) + kRootVSmall)) * d;
  const Vec3 direction = sv / (norm(sv) + kRootVSmall);
  double reach = floor + kRootVSmall;
  for (int k = 0; k < f.n; ++k) reach = std::max(reach, std::abs(dot(direction, f.p[static_cast<std::size_t>(k)] - g.centre)));
  return norm(sv) / reach;
}

// A boundary face against the mirror image of its cell.
double boundary_skewness(const Polygon& f, const FaceGeometry& g, const Vec3& cell_centre) {
  const Vec3 to_face = g.centre - cell_centre;
  const Vec3 normal = g.area / (norm(g.area) + kRootVSmall);
  const Vec3 d = dot(normal, to_face) * normal;
  return normalised_skewness(f, g, to_face, d, 0.4 * norm(d));
}

// A face of the mesh: an internal face between `owner` and `neighbour`, or a boundary face
// (neighbour.cell < 0); `owner` is the cell with the lower number.
struct MeshFace {
  CellFace owner;
  CellFace neighbour{-1, 0};
};

std::vector<MeshFace> mesh_faces(const ElementList& cells, std::size_t node_count) {
  const FaceIndex index(cells, node_count);
  std::vector<MeshFace> faces;
  std::vector<bool> paired;
  for (std::size_t n = 0; n < node_count; ++n) {
    const auto bucket = index.bucket(static_cast<NodeId>(n));
    paired.assign(bucket.size(), false);
    for (std::size_t i = 0; i < bucket.size(); ++i) {
      if (paired[i]) continue;
      MeshFace face{bucket[i]};
      const FaceNodes a = face_nodes(cells, bucket[i]);
      for (std::size_t j = i + 1; j < bucket.size(); ++j) {
        if (!paired[j] && same_node_set(a.view(), face_nodes(cells, bucket[j]).view())) {
          face.neighbour = bucket[j];
          paired[j] = true;
          break;
        }
      }
      faces.push_back(face);
    }
  }
  return faces;
}

// One face's measures.
struct FaceMeasures {
  double non_orthogonality = 0.0;  // degrees; internal faces: to the neighbour, boundary: to the face centre
  double cosine = 1.0;             // internal faces
  double skewness = 0.0;
  double volume_ratio = 1.0;  // internal faces
};

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

}  // namespace

SolverQuality solver_quality(const Mesh& mesh, std::span<const Vec3> points, const Extrusion& extrusion) {
  const ElementList& cells = mesh.cells;
  const Layer layer = layer_of(mesh, points, extrusion);
  const auto n_cells = static_cast<std::ptrdiff_t>(cells.size());

  std::vector<CellGeometry> geometry(cells.size());
#pragma omp parallel for schedule(static) if (n_cells >= kParallelCells)
  for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
    geometry[static_cast<std::size_t>(c)] = cell_geometry(cells, static_cast<std::size_t>(c), points, layer);
  }

  const std::vector<MeshFace> faces = mesh_faces(cells, points.size());
  const auto n_faces = static_cast<std::ptrdiff_t>(faces.size());
  std::vector<FaceMeasures> measures(faces.size());
#pragma omp parallel for schedule(static) if (n_faces >= kParallelCells)
  for (std::ptrdiff_t i = 0; i < n_faces; ++i) {
    const MeshFace& face = faces[static_cast<std::size_t>(i)];
    const auto own = static_cast<std::size_t>(face.owner.cell);
    const Polygon polygon = face_polygon(cells, own, face.owner.local, points, layer);
    const FaceGeometry g = face_geometry(polygon);
    const CellGeometry& a = geometry[own];
    FaceMeasures& m = measures[static_cast<std::size_t>(i)];
    const Vec3 to_face = g.centre - a.centre;
    if (face.neighbour.cell < 0) {
      // A face without area (a wedge's side on its axis) has no direction to measure.
      const bool on_axis = layer.planar && side_thickness(polygon) <= kOnTheAxis * a.thickness;
      if (!on_axis && norm(g.area) > kDegenerateFace * a.largest_face) {
        m.non_orthogonality = degrees(dot(g.area, to_face) / (norm(g.area) * norm(to_face) + kRootVSmall));
      }
      m.skewness = boundary_skewness(polygon, g, a.centre);
      continue;
    }
    const CellGeometry& b = geometry[static_cast<std::size_t>(face.neighbour.cell)];
    const Vec3 d = b.centre - a.centre;
    m.cosine = dot(d, g.area) / (norm(d) * norm(g.area) + kRootVSmall);
    m.non_orthogonality = degrees(m.cosine);
    m.skewness = normalised_skewness(polygon, g, to_face, d, 0.2 * norm(d));
    const double small = std::min(std::abs(a.volume), std::abs(b.volume));
    const double large = std::max(std::abs(a.volume), std::abs(b.volume));
    m.volume_ratio = large / (small + kVSmall);
  }

  SolverQuality q;
  q.non_orthogonality.assign(cells.size(), 0.0);
  q.volume_ratio.assign(cells.size(), 1.0);
  q.skewness.resize(cells.size());
  q.aspect_ratio.resize(cells.size());
  Tally all;
  std::array<Tally, kTypes> by_type;
  const auto type_of = [&](CellId c) { return static_cast<std::size_t>(cells.type(static_cast<std::size_t>(c))); };
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
  return q;
}

}  // namespace hotmesh::mesh
