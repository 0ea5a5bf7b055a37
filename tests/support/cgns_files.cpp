// hotmesh tests: the CGNS files of cgns_files.hpp, written with the CGNS library.
#include "cgns_files.hpp"

#include <cgns_io.h>
#include <cgnslib.h>

#include <array>
#include <stdexcept>

namespace hotmesh::test {
namespace {

void ok(int status) {
  if (status != CG_OK) throw std::runtime_error(std::string("CGNS: ") + cg_get_error());
}

class Out {
 public:
  Out(const std::filesystem::path& path, int cell_dim, int phys_dim) {
    ok(cg_set_file_type(CG_FILE_HDF5));
    ok(cg_open(path.c_str(), CG_MODE_WRITE, &fn));
    ok(cg_base_write(fn, "Base", cell_dim, phys_dim, &base));
  }
  ~Out() { cg_close(fn); }
  Out(const Out&) = delete;
  Out& operator=(const Out&) = delete;

  int unstructured(const char* name, cgsize_t nodes, cgsize_t cells) {
    std::array<cgsize_t, 3> size{nodes, cells, 0};
    int z = 0;
    ok(cg_zone_write(fn, base, name, size.data(), CGNS_ENUMV(Unstructured), &z));
    return z;
  }
  int structured(const char* name, std::vector<cgsize_t> vertices) {
    std::vector<cgsize_t> size = vertices;
    for (const cgsize_t v : vertices) size.push_back(v - 1);
    for (std::size_t i = 0; i < vertices.size(); ++i) size.push_back(0);
    int z = 0;
    ok(cg_zone_write(fn, base, name, size.data(), CGNS_ENUMV(Structured), &z));
    return z;
  }
  /// xyz interleaved, 3 per node; writes the first `dims` coordinates.
  void coordinates(int z, const std::vector<double>& xyz, int dims, bool single) {
    const std::array<const char*, 3> names{"CoordinateX", "CoordinateY", "CoordinateZ"};
    for (int a = 0; a < dims; ++a) {
      std::vector<double> d;
      std::vector<float> f;
      for (std::size_t n = 0; n < xyz.size() / 3; ++n) {
        d.push_back(xyz[3 * n + static_cast<std::size_t>(a)]);
        f.push_back(static_cast<float>(d.back()));
      }
      int c = 0;
      ok(cg_coord_write(fn, base, z, single ? CGNS_ENUMV(RealSingle) : CGNS_ENUMV(RealDouble), names[static_cast<std::size_t>(a)],
                        single ? static_cast<const void*>(f.data()) : static_cast<const void*>(d.data()), &c));
    }
  }
  void section(int z, const char* name, CGNS_ENUMT(ElementType_t) type, cgsize_t first, cgsize_t last,
               const std::vector<cgsize_t>& data) {
    int s = 0;
    if (type != CGNS_ENUMV(MIXED)) {
      ok(cg_section_write(fn, base, z, name, type, first, last, 0, data.data(), &s));
      return;
    }
    std::vector<cgsize_t> offsets{0};  // MIXED: where each element (its type code) starts
    for (std::size_t at = 0; at < data.size();) {
      int npe = 0;
      ok(cg_npe(static_cast<CGNS_ENUMT(ElementType_t)>(data[at]), &npe));
      at += 1 + static_cast<std::size_t>(npe);
      offsets.push_back(static_cast<cgsize_t>(at));
    }
    ok(cg_poly_section_write(fn, base, z, name, type, first, last, 0, data.data(), offsets.data(), &s));
  }
  int bc(int z, const char* name, CGNS_ENUMT(PointSetType_t) set, const std::vector<cgsize_t>& points, int index_dim,
         CGNS_ENUMT(GridLocation_t) location = CGNS_ENUMV(Vertex), const char* family = nullptr) {
    int b = 0;
    ok(cg_boco_write(fn, base, z, name, family ? CGNS_ENUMV(FamilySpecified) : CGNS_ENUMV(BCWall), set,
                     static_cast<cgsize_t>(points.size() / static_cast<std::size_t>(index_dim)), points.data(), &b));
    if (location != CGNS_ENUMV(Vertex)) ok(cg_boco_gridlocation_write(fn, base, z, b, location));
    if (family) {
      ok(cg_goto(fn, base, "Zone_t", z, "ZoneBC_t", 1, "BC_t", b, "end"));
      ok(cg_famname_write(family));
    }
    return b;
  }
  void family(const char* name) {
    int f = 0;
    ok(cg_family_write(fn, base, name, &f));
    int b = 0;
    ok(cg_fambc_write(fn, base, f, "bc", CGNS_ENUMV(BCWall), &b));
  }
  void pressure(int z, std::size_t nodes) {
    int s = 0, f = 0;
    ok(cg_sol_write(fn, base, z, "Flow", CGNS_ENUMV(Vertex), &s));
    std::vector<double> p(nodes);
    for (std::size_t n = 0; n < nodes; ++n) p[n] = 101325.0 + 17.25 * static_cast<double>(n);
    ok(cg_field_write(fn, base, z, s, CGNS_ENUMV(RealDouble), "Pressure", p.data(), &f));
  }

  int fn = 0;
  int base = 0;
};

/// Grid nodes (i fastest), interleaved xyz.
std::vector<double> grid(int ni, int nj, int nk, double x0, double h) {
  std::vector<double> xyz;
  for (int k = 0; k < nk; ++k) {
    for (int j = 0; j < nj; ++j) {
      for (int i = 0; i < ni; ++i) {
        xyz.insert(xyz.end(), {x0 + h * i, h * j, nk > 1 ? h * k : 0.0});
      }
    }
  }
  return xyz;
}

/// 1-based node numbers of a grid of ni x nj (x nk) nodes, i fastest.
cgsize_t node(int ni, int nj, int i, int j, int k = 0) { return static_cast<cgsize_t>(i + ni * (j + nj * k) + 1); }

std::vector<cgsize_t> quads_2d(int ni, int nj, bool mixed) {
  std::vector<cgsize_t> data;
  for (int j = 0; j + 1 < nj; ++j) {
    for (int i = 0; i + 1 < ni; ++i) {
      if (mixed) data.push_back(CGNS_ENUMV(QUAD_4));
      data.insert(data.end(), {node(ni, nj, i, j), node(ni, nj, i + 1, j), node(ni, nj, i + 1, j + 1), node(ni, nj, i, j + 1)});
    }
  }
  return data;
}

}  // namespace

void write_unstructured_2d(const std::filesystem::path& path) {
  Out out(path, 2, 2);
  const int z = out.unstructured("Fluid", 12, 6);
  out.coordinates(z, grid(4, 3, 1, 0.0, 1.0), 2, false);
  out.section(z, "Cells", CGNS_ENUMV(MIXED), 1, 6, quads_2d(4, 3, true));
  out.section(z, "Bottom", CGNS_ENUMV(BAR_2), 7, 9, {1, 2, 2, 3, 3, 4});
  out.section(z, "TopEdges", CGNS_ENUMV(BAR_2), 10, 12, {10, 9, 11, 10, 12, 11});
  out.bc(z, "bottom", CGNS_ENUMV(PointRange), {7, 9}, 1, CGNS_ENUMV(EdgeCenter));
  out.bc(z, "left", CGNS_ENUMV(PointList), {1, 5, 9}, 1);
  out.bc(z, "right", CGNS_ENUMV(PointList), {4, 8, 12}, 1);
  out.pressure(z, 12);
}

void write_unstructured_3d(const std::filesystem::path& path) {
  Out out(path, 3, 3);
  const int z = out.unstructured("Block", 27, 8);
  out.coordinates(z, grid(3, 3, 3, 0.0, 1.0), 3, false);
  std::vector<cgsize_t> data;
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 2; ++i) {
        data.push_back(CGNS_ENUMV(HEXA_8));
        for (int dk = 0; dk < 2; ++dk) {
          data.insert(data.end(), {node(3, 3, i, j, k + dk), node(3, 3, i + 1, j, k + dk), node(3, 3, i + 1, j + 1, k + dk),
                                   node(3, 3, i, j + 1, k + dk)});
        }
      }
    }
  }
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      data.push_back(CGNS_ENUMV(QUAD_4));
      data.insert(data.end(), {node(3, 3, i, j), node(3, 3, i, j + 1), node(3, 3, i + 1, j + 1), node(3, 3, i + 1, j)});
    }
  }
  out.section(z, "Elements", CGNS_ENUMV(MIXED), 1, 12, data);
  out.family("Casing");
  out.bc(z, "floor", CGNS_ENUMV(PointList), {9, 10, 11, 12}, 1, CGNS_ENUMV(FaceCenter));
  const auto side = [](auto inside) {
    std::vector<cgsize_t> points;
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
          if (inside(i, j, k)) points.push_back(node(3, 3, i, j, k));
        }
      }
    }
    return points;
  };
  out.bc(z, "xmin", CGNS_ENUMV(PointList), side([](int i, int, int) { return i == 0; }), 1, CGNS_ENUMV(Vertex), "Casing");
  out.bc(z, "xmax", CGNS_ENUMV(PointList), side([](int i, int, int) { return i == 2; }), 1, CGNS_ENUMV(Vertex), "Casing");
  out.bc(z, "ymin", CGNS_ENUMV(PointList), side([](int, int j, int) { return j == 0; }), 1, CGNS_ENUMV(Vertex), "Casing");
  out.bc(z, "ymax", CGNS_ENUMV(PointList), side([](int, int j, int) { return j == 2; }), 1, CGNS_ENUMV(Vertex), "Casing");
  out.bc(z, "top", CGNS_ENUMV(PointList), side([](int, int, int k) { return k == 2; }), 1);
}

void write_structured_2d(const std::filesystem::path& path, bool wrong_interface) {
  Out out(path, 2, 2);
  out.family("Walls");
  const int a = out.structured("A", {4, 3});
  std::vector<double> xyz_a;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 4; ++i) xyz_a.insert(xyz_a.end(), {i / 3.0, j / 2.0, 0.0});
  }
  out.coordinates(a, xyz_a, 2, true);
  const int b = out.structured("B", {3, 4});  // i along y, j along x: left-handed
  std::vector<double> xyz_b;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 3; ++i) xyz_b.insert(xyz_b.end(), {1.0 + j / 3.0, i / 2.0, 0.0});
  }
  out.coordinates(b, xyz_b, 2, true);
  int c = 0;
  std::array<cgsize_t, 4> range_a{4, 1, 4, 3}, range_b{1, 1, 3, 1}, reversed_b{3, 1, 1, 1};
  std::array<int, 2> transform{2, 1}, wrong{2, -1};
  ok(cg_1to1_write(out.fn, out.base, a, "A_to_B", "B", range_a.data(), wrong_interface ? reversed_b.data() : range_b.data(),
                   wrong_interface ? wrong.data() : transform.data(), &c));
  ok(cg_1to1_write(out.fn, out.base, b, "B_to_A", "A", range_b.data(), range_a.data(), transform.data(), &c));
  out.bc(a, "inlet", CGNS_ENUMV(PointRange), {1, 1, 1, 3}, 2);
  out.bc(a, "wall_a", CGNS_ENUMV(PointRange), {1, 1, 4, 1}, 2, CGNS_ENUMV(Vertex), "Walls");
  out.bc(a, "top", CGNS_ENUMV(PointRange), {1, 3, 3, 3}, 2, CGNS_ENUMV(EdgeCenter));
  out.bc(b, "wall_b", CGNS_ENUMV(PointRange), {1, 1, 1, 4}, 2, CGNS_ENUMV(Vertex), "Walls");
  out.bc(b, "top", CGNS_ENUMV(PointRange), {3, 1, 3, 4}, 2);
  out.bc(b, "outlet", CGNS_ENUMV(PointRange), {1, 4, 3, 4}, 2);
  out.pressure(a, 12);
  out.pressure(b, 12);
}

void write_structured_3d(const std::filesystem::path& path) {
  Out out(path, 3, 3);
  const int a = out.structured("A", {3, 3, 3});
  out.coordinates(a, grid(3, 3, 3, 0.0, 0.5), 3, false);
  const int b = out.structured("B", {3, 3, 3});
  out.coordinates(b, grid(3, 3, 3, 1.0, 0.5), 3, false);
  out.bc(a, "xmin", CGNS_ENUMV(PointRange), {1, 1, 1, 1, 3, 3}, 3);
  out.bc(b, "xmax", CGNS_ENUMV(PointRange), {3, 1, 1, 3, 3, 3}, 3);
  for (const int z : {a, b}) {
    out.bc(z, "ymin", CGNS_ENUMV(PointRange), {1, 1, 1, 3, 1, 3}, 3);
    out.bc(z, "ymax", CGNS_ENUMV(PointRange), {1, 3, 1, 3, 3, 3}, 3);
    out.bc(z, "zmin", CGNS_ENUMV(PointRange), {1, 1, 1, 3, 3, 1}, 3);
    out.bc(z, "zmax", CGNS_ENUMV(PointRange), {1, 1, 3, 3, 3, 3}, 3);
  }
}

void write_unstructured_two_zones(const std::filesystem::path& path, bool connectivity) {
  Out out(path, 2, 2);
  out.family("Walls");
  std::vector<double> right = grid(4, 3, 1, 3.0, 1.0);
  if (!connectivity) {
    for (const std::size_t n : {0u, 4u, 8u}) right[3 * n] += 1e-7;
  }
  const std::array<std::vector<double>, 2> xyz{grid(4, 3, 1, 0.0, 1.0), right};
  const std::array<const char*, 2> names{"Left", "Right"};
  const std::array<std::vector<cgsize_t>, 2> interface{std::vector<cgsize_t>{4, 8, 12}, std::vector<cgsize_t>{1, 5, 9}};
  for (std::size_t z = 0; z < 2; ++z) {
    const int zone = out.unstructured(names[z], 12, 6);
    out.coordinates(zone, xyz[z], 2, false);
    out.section(zone, "Cells", CGNS_ENUMV(QUAD_4), 1, 6, quads_2d(4, 3, false));
    out.bc(zone, z == 0 ? "left" : "right", CGNS_ENUMV(PointList), z == 0 ? std::vector<cgsize_t>{1, 5, 9} : std::vector<cgsize_t>{4, 8, 12}, 1);
    out.bc(zone, "bottom", CGNS_ENUMV(PointList), {1, 2, 3, 4}, 1, CGNS_ENUMV(Vertex), "Walls");
    out.bc(zone, "top", CGNS_ENUMV(PointList), {9, 10, 11, 12}, 1, CGNS_ENUMV(Vertex), "Walls");
    if (!connectivity) continue;
    int c = 0;
    ok(cg_conn_write(out.fn, out.base, zone, "interface", CGNS_ENUMV(Vertex), CGNS_ENUMV(Abutting1to1),
                     CGNS_ENUMV(PointList), 3, interface[z].data(), names[1 - z], CGNS_ENUMV(Unstructured),
                     CGNS_ENUMV(PointListDonor), CGNS_ENUMV(Integer), 3, interface[1 - z].data(), &c));
  }
}

void write_structured_periodic_2d(const std::filesystem::path& path) {
  Out out(path, 2, 2);
  const int z = out.structured("Passage", {4, 3});
  std::vector<double> xyz;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 4; ++i) xyz.insert(xyz.end(), {i / 3.0, j / 2.0, 0.0});
  }
  out.coordinates(z, xyz, 2, false);
  std::array<cgsize_t, 4> low{1, 1, 4, 1}, high{1, 3, 4, 3};
  std::array<int, 2> transform{1, 2};
  const std::array<float, 2> center{0, 0}, angle{0, 0}, up{0, 1}, down{0, -1};
  int c = 0;
  ok(cg_1to1_write(out.fn, out.base, z, "per_lo", "Passage", low.data(), high.data(), transform.data(), &c));
  ok(cg_1to1_periodic_write(out.fn, out.base, z, c, center.data(), angle.data(), up.data()));
  ok(cg_1to1_write(out.fn, out.base, z, "per_hi", "Passage", high.data(), low.data(), transform.data(), &c));
  ok(cg_1to1_periodic_write(out.fn, out.base, z, c, center.data(), angle.data(), down.data()));
  out.bc(z, "inlet", CGNS_ENUMV(PointRange), {1, 1, 1, 3}, 2);
  out.bc(z, "outlet", CGNS_ENUMV(PointRange), {4, 1, 4, 3}, 2);
}

void write_with_quadratic_triangles(const std::filesystem::path& path) {
  Out out(path, 2, 2);
  const int z = out.unstructured("Fluid", 9, 2);
  out.coordinates(z, grid(3, 3, 1, 0.0, 0.5), 2, false);
  // Corners 1 3 9 and 1 9 7, then the mid-edge nodes.
  out.section(z, "Tris", CGNS_ENUMV(TRI_6), 1, 2, {1, 3, 9, 2, 6, 5, 1, 9, 7, 5, 8, 4});
}

void write_bc_without_faces(const std::filesystem::path& path) {
  Out out(path, 2, 2);
  const int z = out.unstructured("Fluid", 12, 6);
  out.coordinates(z, grid(4, 3, 1, 0.0, 1.0), 2, false);
  out.section(z, "Cells", CGNS_ENUMV(QUAD_4), 1, 6, quads_2d(4, 3, false));
  out.bc(z, "lonely", CGNS_ENUMV(PointList), {6}, 1);
}

namespace {

void cgio_ok(int status) {
  if (status == CGIO_ERR_NONE) return;
  char message[CGIO_MAX_ERROR_LENGTH + 1] = {};
  cgio_error_message(message);
  throw std::runtime_error(std::string("CGNS I/O: ") + message);
}

/// The children of node `id` of cgio file `cgio`.
std::vector<double> children_of(int cgio, double id) {
  int count = 0;
  cgio_ok(cgio_number_children(cgio, id, &count));
  std::vector<double> ids(static_cast<std::size_t>(count));
  int got = 0;
  if (count > 0) cgio_ok(cgio_children_ids(cgio, id, 1, count, &got, ids.data()));
  ids.resize(static_cast<std::size_t>(got));
  return ids;
}

std::string label_of(int cgio, double id) {
  char label[CGIO_MAX_LABEL_LENGTH + 1] = {};
  cgio_ok(cgio_get_label(cgio, id, label));
  return label;
}

}  // namespace

void make_legacy(const std::filesystem::path& path) {
  int cgio = 0;
  cgio_ok(cgio_open_file(path.c_str(), CGIO_MODE_MODIFY, CGIO_FILE_NONE, &cgio));
  double root = 0, version = 0;
  cgio_ok(cgio_get_root_id(cgio, &root));
  cgio_ok(cgio_get_node_id(cgio, root, "CGNSLibraryVersion", &version));
  const float v31 = 3.1f;
  cgio_ok(cgio_write_all_data(cgio, version, &v31));
  for (double base : children_of(cgio, root)) {
    if (label_of(cgio, base) != "CGNSBase_t") continue;
    for (double zone : children_of(cgio, base)) {
      if (label_of(cgio, zone) != "Zone_t") continue;
      for (double section : children_of(cgio, zone)) {
        if (label_of(cgio, section) != "Elements_t") continue;
        double offsets = 0;
        if (cgio_get_node_id(cgio, section, "ElementStartOffset", &offsets) == CGIO_ERR_NONE) {
          cgio_ok(cgio_delete_node(cgio, section, offsets));
        }
      }
    }
  }
  cgio_ok(cgio_close_file(cgio));
}

void link_node(const std::filesystem::path& path, const std::string& node, const std::filesystem::path& target) {
  int cgio = 0;
  cgio_ok(cgio_open_file(path.c_str(), CGIO_MODE_MODIFY, CGIO_FILE_NONE, &cgio));
  double root = 0, id = 0, parent = 0, link = 0;
  cgio_ok(cgio_get_root_id(cgio, &root));
  cgio_ok(cgio_get_node_id(cgio, root, node.c_str(), &id));
  const std::string parent_path = node.substr(0, node.rfind('/'));
  const std::string name = node.substr(node.rfind('/') + 1);
  cgio_ok(cgio_get_node_id(cgio, root, parent_path.c_str(), &parent));
  cgio_ok(cgio_delete_node(cgio, parent, id));
  cgio_ok(cgio_create_link(cgio, parent, name.c_str(), target.c_str(), node.c_str(), &link));
  cgio_ok(cgio_close_file(cgio));
}

void overwrite_integers(const std::filesystem::path& path, const std::string& node, const std::vector<int>& values,
                        std::vector<long long> dimensions) {
  if (dimensions.empty()) dimensions.push_back(static_cast<long long>(values.size()));
  int cgio = 0;
  cgio_ok(cgio_open_file(path.c_str(), CGIO_MODE_MODIFY, CGIO_FILE_NONE, &cgio));
  double root = 0, id = 0;
  cgio_ok(cgio_get_root_id(cgio, &root));
  cgio_ok(cgio_get_node_id(cgio, root, node.c_str(), &id));
  const std::vector<cgsize_t> dims(dimensions.begin(), dimensions.end());
  cgio_ok(cgio_set_dimensions(cgio, id, "I4", static_cast<int>(dims.size()), dims.data()));
  cgio_ok(cgio_write_all_data(cgio, id, values.data()));
  cgio_ok(cgio_close_file(cgio));
}

std::vector<ZoneCoordinates> read_zone_coordinates(const std::filesystem::path& path) {
  int fn = 0, zones = 0;
  ok(cg_open(path.c_str(), CG_MODE_READ, &fn));
  ok(cg_nzones(fn, 1, &zones));
  std::vector<ZoneCoordinates> out(static_cast<std::size_t>(zones));
  for (int z = 1; z <= zones; ++z) {
    char name[33];
    std::array<cgsize_t, 9> size{};
    ok(cg_zone_read(fn, 1, z, name, size.data()));
    CGNS_ENUMT(ZoneType_t) type{};
    ok(cg_zone_type(fn, 1, z, &type));
    int dims = 1, coords = 0;
    if (type == CGNS_ENUMV(Structured)) ok(cg_index_dim(fn, 1, z, &dims));
    std::array<cgsize_t, 3> lo{1, 1, 1}, hi{1, 1, 1};
    std::size_t n = 1;
    for (int d = 0; d < dims; ++d) {
      hi[static_cast<std::size_t>(d)] = size[static_cast<std::size_t>(d)];
      n *= static_cast<std::size_t>(size[static_cast<std::size_t>(d)]);
    }
    ok(cg_ncoords(fn, 1, z, &coords));
    auto& zone = out[static_cast<std::size_t>(z - 1)];
    zone.xyz.assign(3 * n, 0.0);
    for (int c = 1; c <= coords; ++c) {
      CGNS_ENUMT(DataType_t) data_type{};
      char coordinate[33];
      ok(cg_coord_info(fn, 1, z, c, &data_type, coordinate));
      zone.types.emplace_back(cg_DataTypeName(data_type));
      std::vector<double> v(n);
      ok(cg_coord_read(fn, 1, z, coordinate, CGNS_ENUMV(RealDouble), lo.data(), hi.data(), v.data()));
      const auto axis = static_cast<std::size_t>(coordinate[10] - 'X');
      for (std::size_t i = 0; i < n; ++i) zone.xyz[3 * i + axis] = v[i];
    }
  }
  cg_close(fn);
  return out;
}

std::vector<double> read_field(const std::filesystem::path& path, int zone, int solution, const std::string& field) {
  int fn = 0;
  ok(cg_open(path.c_str(), CG_MODE_READ, &fn));
  char name[33];
  std::array<cgsize_t, 9> size{};
  ok(cg_zone_read(fn, 1, zone, name, size.data()));
  CGNS_ENUMT(ZoneType_t) type{};
  ok(cg_zone_type(fn, 1, zone, &type));
  int dims = 1;
  if (type == CGNS_ENUMV(Structured)) ok(cg_index_dim(fn, 1, zone, &dims));
  std::array<cgsize_t, 3> lo{1, 1, 1}, hi{1, 1, 1};
  std::size_t n = 1;
  for (int d = 0; d < dims; ++d) {
    hi[static_cast<std::size_t>(d)] = size[static_cast<std::size_t>(d)];
    n *= static_cast<std::size_t>(size[static_cast<std::size_t>(d)]);
  }
  std::vector<double> values(n);
  ok(cg_field_read(fn, 1, zone, solution, field.c_str(), CGNS_ENUMV(RealDouble), lo.data(), hi.data(), values.data()));
  cg_close(fn);
  return values;
}

}  // namespace hotmesh::test
