// hotmesh sample stator_well: the sector in the formats of engine CFD codes.
//
// CGNS, structured multi-block: one zone per block of the meridional section, its index i
// along the block's first side, j along its fourth and k along theta (right-handed, as the
// hexes of sector_mesh). Blocks sharing a side are joined by GridConnectivity1to1: the side's
// points of one zone are the donor's under the transform T, whose column for k is +3, for the
// side's direction +-(donor's side direction) (- if the donor runs the side the other way),
// and for the normal direction +-(donor's normal), + when leaving one zone across its side
// enters the donor in its increasing direction. Patches are BCs with vertex point ranges: the
// periodic sides k = 1 and k = K of every zone, and runs of a block side's segments on one
// patch; each BC's FamilyName is its patch (a patch may need two BCs in one zone).
//
// OpenFOAM: the sector's hex mesh through hotmesh's polyMesh writer, in a case folder with
// the system/ files checkMesh reads.
#include <cgnslib.h>

#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/foam.hpp"
#include "stator_well.hpp"

namespace hotmesh::samples::stator_well {
namespace {

namespace fs = std::filesystem;
using Index3 = std::array<cgsize_t, 3>;

/// A new CGNS file, closed by the destructor.
class CgnsOutput {
 public:
  explicit CgnsOutput(const fs::path& path) : path_(path.string()) {
    check(cg_set_file_type(CG_FILE_HDF5), "choosing HDF5");
    check(cg_open(path_.c_str(), CG_MODE_WRITE, &fn_), "opening");
  }
  ~CgnsOutput() {
    if (fn_ >= 0) cg_close(fn_);
  }
  CgnsOutput(const CgnsOutput&) = delete;
  CgnsOutput& operator=(const CgnsOutput&) = delete;

  int fn() const { return fn_; }
  void check(int status, std::string_view what) const {
    if (status != CG_OK) throw std::runtime_error(fmt::format("{}: {}: {}", path_, what, cg_get_error()));
  }
  void close() {
    const int fn = fn_;
    fn_ = -1;
    check(cg_close(fn), "closing");
  }

 private:
  std::string path_;
  int fn_ = -1;
};

/// Side s of a block: 0 j = 1, 1 i = ni, 2 j = nj, 3 i = 1 (CGNS indices, from 1).
struct BlockSide {
  const QuadMesh::Block* block = nullptr;
  int side = 0;

  int along() const { return side % 2 == 0 ? 0 : 1; }  ///< the index running along the side
  int normal() const { return 1 - along(); }
  bool at_max() const { return side == 1 || side == 2; }
  std::size_t size() const { return along() == 0 ? block->ni : block->nj; }
  /// The (i, j) of the side's t-th node (t from 0).
  std::array<cgsize_t, 2> index(std::size_t t) const {
    std::array<cgsize_t, 2> ij{};
    ij[static_cast<std::size_t>(along())] = static_cast<cgsize_t>(t) + 1;
    ij[static_cast<std::size_t>(normal())] =
        at_max() ? static_cast<cgsize_t>(normal() == 0 ? block->ni : block->nj) : 1;
    return ij;
  }
  std::int32_t node(std::size_t t) const {
    const auto [i, j] = index(t);
    return block->nodes[static_cast<std::size_t>(j - 1) * block->ni + static_cast<std::size_t>(i - 1)];
  }
};

/// The 3D point range of nodes t0..t1 of a side, all layers k = 1..K.
std::array<cgsize_t, 6> side_range(const BlockSide& s, std::size_t t0, std::size_t t1, cgsize_t layers) {
  const auto a = s.index(t0), b = s.index(t1);
  return {a[0], a[1], 1, b[0], b[1], layers};
}

std::pair<std::int32_t, std::int32_t> segment_key(std::int32_t a, std::int32_t b) {
  return {std::min(a, b), std::max(a, b)};
}

struct Zones {
  const QuadMesh& section;
  const mesh::Mesh& sector;
  std::map<std::pair<std::int32_t, std::int32_t>, Patch> segment_patch;
  std::map<std::pair<std::int32_t, std::int32_t>, std::vector<BlockSide>> sides_by_corners;
  cgsize_t layers = 0;
};

std::string zone_name(std::size_t b) { return fmt::format("block_{:02}", b + 1); }

void write_zone_grid(const CgnsOutput& out, int base, std::size_t b, const Zones& z, int& zone) {
  const QuadMesh::Block& block = z.section.blocks[b];
  const auto ni = static_cast<cgsize_t>(block.ni), nj = static_cast<cgsize_t>(block.nj);
  const cgsize_t size[9] = {ni, nj, z.layers, ni - 1, nj - 1, z.layers - 1, 0, 0, 0};
  out.check(cg_zone_write(out.fn(), base, zone_name(b).c_str(), size, CGNS_ENUMV(Structured), &zone), "writing a zone");
  const std::size_t layer_nodes = z.section.nodes.size();
  std::array<std::vector<double>, 3> xyz;
  for (auto& c : xyz) c.reserve(block.nodes.size() * static_cast<std::size_t>(z.layers));
  for (cgsize_t k = 0; k < z.layers; ++k) {
    for (const std::int32_t m : block.nodes) {
      const geometry::Vec3& p = z.sector.points[static_cast<std::size_t>(k) * layer_nodes + static_cast<std::size_t>(m)];
      xyz[0].push_back(p.x);
      xyz[1].push_back(p.y);
      xyz[2].push_back(p.z);
    }
  }
  const char* names[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
  for (int a = 0; a < 3; ++a) {
    int c = 0;
    out.check(cg_coord_write(out.fn(), base, zone, CGNS_ENUMV(RealDouble), names[a], xyz[static_cast<std::size_t>(a)].data(), &c),
              "writing coordinates");
  }
}

/// The 1-to-1 connection of side `s` of zone `zone` to `donor`, the same nodes (maybe reversed).
void write_connection(const CgnsOutput& out, int base, int zone, const BlockSide& s, const BlockSide& donor,
                      std::size_t donor_block, cgsize_t layers) {
  const std::size_t n = s.size();
  const bool same_way = s.node(0) == donor.node(0);
  const auto range = side_range(s, 0, n - 1, layers);
  const auto donor_range = same_way ? side_range(donor, 0, n - 1, layers) : side_range(donor, n - 1, 0, layers);
  int transform[3] = {0, 0, 3};
  transform[s.along()] = (same_way ? 1 : -1) * (donor.along() + 1);
  const int leave = s.at_max() ? 1 : -1, enter = donor.at_max() ? -1 : 1;
  transform[s.normal()] = leave * enter * (donor.normal() + 1);
  const std::string name = fmt::format("side{}_to_{}", s.side + 1, zone_name(donor_block));
  int index = 0;
  out.check(cg_1to1_write(out.fn(), base, zone, name.c_str(), zone_name(donor_block).c_str(), range.data(),
                          donor_range.data(), transform, &index),
            "writing a 1-to-1 connection");
}

void write_bc(const CgnsOutput& out, int base, int zone, std::map<std::string, int>& used, Patch patch,
              const std::array<cgsize_t, 6>& range) {
  const std::string family(name(patch));
  const int count = ++used[family];
  const std::string bc_name = count == 1 ? family : fmt::format("{}_{}", family, count);
  const CGNS_ENUMT(BCType_t) type = patch == Patch::inlet    ? CGNS_ENUMV(BCInflow)
                                    : patch == Patch::outlet ? CGNS_ENUMV(BCOutflow)
                                    : patch == Patch::per_lo || patch == Patch::per_hi ? CGNS_ENUMV(BCGeneral)
                                                                                        : CGNS_ENUMV(BCWall);
  int bc = 0;
  out.check(cg_boco_write(out.fn(), base, zone, bc_name.c_str(), type, CGNS_ENUMV(PointRange), 2, range.data(), &bc),
            "writing a BC");
  out.check(cg_goto(out.fn(), base, "Zone_t", zone, "ZoneBC_t", 1, "BC_t", bc, "end"), "reaching a BC");
  out.check(cg_famname_write(family.c_str()), "writing a BC's family");
}

/// BCs of a block side on the loop: one per run of segments on one patch.
void write_loop_side_bcs(const CgnsOutput& out, int base, int zone, const BlockSide& s, const Zones& z,
                         std::map<std::string, int>& used) {
  const auto patch_of = [&](std::size_t t) { return z.segment_patch.at(segment_key(s.node(t), s.node(t + 1))); };
  std::size_t start = 0;
  for (std::size_t t = 1; t < s.size(); ++t) {
    if (t == s.size() - 1 || patch_of(t) != patch_of(start)) {
      write_bc(out, base, zone, used, patch_of(start), side_range(s, start, t, z.layers));
      start = t;
    }
  }
}

void write_zone_topology(const CgnsOutput& out, int base, int zone, std::size_t b, const Zones& z) {
  const QuadMesh::Block& block = z.section.blocks[b];
  std::map<std::string, int> used;
  for (int side = 0; side < 4; ++side) {
    const BlockSide s{&block, side};
    const auto& sharing = z.sides_by_corners.at(segment_key(s.node(0), s.node(s.size() - 1)));
    const BlockSide* donor = nullptr;
    for (const BlockSide& other : sharing) {
      if (other.block != &block || other.side != side) donor = &other;
    }
    if (donor) {
      write_connection(out, base, zone, s, *donor, static_cast<std::size_t>(donor->block - z.section.blocks.data()),
                       z.layers);
    } else {
      write_loop_side_bcs(out, base, zone, s, z, used);
    }
  }
  const auto ni = static_cast<cgsize_t>(block.ni), nj = static_cast<cgsize_t>(block.nj);
  write_bc(out, base, zone, used, Patch::per_lo, {1, 1, 1, ni, nj, 1});
  write_bc(out, base, zone, used, Patch::per_hi, {1, 1, z.layers, ni, nj, z.layers});
}

Zones zones_of(const QuadMesh& section, const mesh::Mesh& sector, const std::vector<ProfileCurve>& loop, int theta_cells) {
  Zones z{section, sector, {}, {}, static_cast<cgsize_t>(theta_cells) + 1};
  for (const auto& segment : section.boundary) {
    z.segment_patch[segment_key(segment.a, segment.b)] = loop[static_cast<std::size_t>(segment.curve)].patch;
  }
  for (const QuadMesh::Block& block : section.blocks) {
    for (int side = 0; side < 4; ++side) {
      const BlockSide s{&block, side};
      z.sides_by_corners[segment_key(s.node(0), s.node(s.size() - 1))].push_back(s);
    }
  }
  for (const auto& [corners, sides] : z.sides_by_corners) {
    if (sides.size() > 2) throw std::logic_error("a block side shared by more than two blocks");
  }
  return z;
}

}  // namespace

void write_sector_cgns(const fs::path& path, const QuadMesh& section, const mesh::Mesh& sector,
                       const std::vector<ProfileCurve>& loop, int theta_cells) {
  const Zones z = zones_of(section, sector, loop, theta_cells);
  const fs::path partial = path.string() + ".partial";
  {
    CgnsOutput out(partial);
    int base = 0;
    out.check(cg_base_write(out.fn(), "stator_well", 3, 3, &base), "writing the base");
    out.check(cg_goto(out.fn(), base, "end"), "reaching the base");
    out.check(cg_dataclass_write(CGNS_ENUMV(Dimensional)), "writing the data class");
    out.check(cg_units_write(CGNS_ENUMV(Kilogram), CGNS_ENUMV(Meter), CGNS_ENUMV(Second), CGNS_ENUMV(Kelvin),
                             CGNS_ENUMV(Degree)),
              "writing the units (metres)");
    for (int p = 0; p < kPatchCount; ++p) {
      int family = 0;
      out.check(cg_family_write(out.fn(), base, std::string(name(static_cast<Patch>(p))).c_str(), &family),
                "writing a family");
    }
    for (std::size_t b = 0; b < section.blocks.size(); ++b) {
      int zone = 0;
      write_zone_grid(out, base, b, z, zone);
      write_zone_topology(out, base, zone, b, z);
    }
    out.close();
  }
  fs::rename(partial, path);
}

void write_sector_foam(const fs::path& folder, const mesh::Mesh& sector, bool binary) {
  const auto dictionary = [&](const std::string& object, const std::string& body) {
    io::write_file_atomically(folder / "system" / object,
                              "FoamFile { version 2.0; format ascii; class dictionary; object " + object + "; }\n" + body);
  };
  fs::create_directories(folder / "system");
  dictionary("controlDict",
             "application checkMesh; startFrom startTime; startTime 0; stopAt endTime; endTime 1;\n"
             "deltaT 1; writeControl timeStep; writeInterval 1; writeFormat " +
                 std::string(binary ? "binary" : "ascii") +
                 ";\nwritePrecision 17; writeCompression off; timeFormat general; timePrecision 6;\n");
  dictionary("fvSchemes",
             "ddtSchemes { default Euler; } gradSchemes { default Gauss linear; } divSchemes { default none; }\n"
             "laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default linear; }\n"
             "snGradSchemes { default corrected; }\n");
  dictionary("fvSolution", "solvers { }\n");
  io::write_foam(folder, sector, sector.points, {.binary = binary});
}

}  // namespace hotmesh::samples::stator_well
