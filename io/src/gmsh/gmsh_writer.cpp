// hotmesh io: the Gmsh .msh writer, format 4.1, ASCII or binary.
// Layout, chosen so that parse_gmsh gives back an equal mesh and gmsh itself opens the file:
//   $PhysicalNames  patches (dimension d-1), then cell groups (dimension d)
//   $Entities       one entity of dimension d-1 per patch (its physical tag), and one entity of
//                   dimension d per distinct set of cell groups a cell belongs to (numbered in
//                   order of first appearance; cells in no group get one without physical tag)
//   $Nodes          one block, on the first cell entity, all nodes in mesh order with their ids
//   $Elements       the cells in mesh order, as blocks of consecutive cells with the same entity
//                   and type, then each patch's faces (blocks by type) with element tags above the
//                   largest cell id
// Numbers are written with std::to_chars (shortest form that reads back to the same double).
#include <algorithm>
#include <array>
#include <charconv>
#include <cstring>
#include <limits>
#include <map>
#include <ostream>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "gmsh/gmsh_format.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/gmsh.hpp"

namespace hotmesh::io {
namespace {

using mesh::ElementList;
using mesh::ElementType;
using mesh::Mesh;

/// Buffered output of 4.1 records: in ASCII each field is text followed by a blank and
/// end_record() ends the line; in binary each field is its raw bytes.
class Out {
 public:
  Out(std::ostream& out, bool binary) : out_(out), binary_(binary) { buffer_.reserve(kChunk + 4096); }

  bool binary() const { return binary_; }
  void text(std::string_view s) {
    buffer_.append(s);
    spill();
  }
  void size(std::uint64_t v) { binary_ ? raw(v) : ascii(v); }
  void int32(int v) { binary_ ? raw(static_cast<std::int32_t>(v)) : ascii(v); }
  void real(double v) { binary_ ? raw(v) : ascii(v); }
  void end_record() {
    if (!binary_ && !buffer_.empty() && buffer_.back() == ' ') buffer_.back() = '\n';
    spill();
  }
  void begin_section(std::string_view name) {
    buffer_.push_back('$');
    buffer_.append(name);
    text("\n");
  }
  void end_section(std::string_view name) {
    buffer_.append(binary_ ? "\n$End" : "$End");
    buffer_.append(name);
    text("\n");
  }
  void flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }

 private:
  static constexpr std::size_t kChunk = std::size_t{1} << 20;

  template <class T>
  void ascii(T v) {
    char digits[32];
    const auto result = std::to_chars(digits, digits + sizeof digits, v);
    buffer_.append(digits, result.ptr);
    buffer_.push_back(' ');
  }
  template <class T>
  void raw(T v) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    buffer_.append(bytes, sizeof(T));
  }
  void spill() {
    if (buffer_.size() >= kChunk) flush();
  }

  std::ostream& out_;
  bool binary_;
  std::string buffer_;
};

[[noreturn]] void misuse(const std::string& what) { throw std::invalid_argument("write_gmsh: " + what); }

/// Physical tags to write: positive unique tags are kept, the others (0 = unset, repeats)
/// get new numbers above the largest.
template <class Group>
std::vector<int> physical_tags(const std::vector<Group>& groups) {
  std::vector<int> tags(groups.size(), 0);
  std::set<int> used;
  int top = 0;
  for (std::size_t i = 0; i < groups.size(); ++i) {
    if (groups[i].tag > 0 && used.insert(groups[i].tag).second) {
      tags[i] = groups[i].tag;
      top = std::max(top, groups[i].tag);
    }
  }
  for (int& tag : tags) {
    if (tag == 0) tag = ++top;
  }
  return tags;
}

void check_name(const std::string& name) {
  if (name.find_first_of("\"\n\r") != std::string::npos) {
    misuse("group name '" + name + "' holds a double quote or line break, which .msh cannot store");
  }
}

void check_elements(const ElementList& list, int dimension, std::size_t nodes, const std::string& what) {
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (mesh::dimension(list.type(i)) != dimension) {
      misuse(what + " " + std::to_string(i) + " is a " + std::string(mesh::name(list.type(i))) +
             ", not of dimension " + std::to_string(dimension));
    }
  }
  for (mesh::NodeId n : list.all_nodes()) {
    if (n < 0 || static_cast<std::size_t>(n) >= nodes)
      misuse(what + " refers to missing node index " + std::to_string(n));
  }
}

void check_mesh(const Mesh& mesh) {
  if (mesh.dimension != 2 && mesh.dimension != 3) misuse("mesh dimension must be 2 or 3");
  if (!mesh.node_ids.empty() && mesh.node_ids.size() != mesh.points.size())
    misuse("node_ids and points differ in size");
  if (!mesh.cell_ids.empty() && mesh.cell_ids.size() != mesh.cells.size()) misuse("cell_ids and cells differ in size");
  check_elements(mesh.cells, mesh.dimension, mesh.points.size(), "cell");
  for (const mesh::Patch& patch : mesh.patches) {
    check_name(patch.name);
    check_elements(patch.faces, mesh.dimension - 1, mesh.points.size(), "patch '" + patch.name + "' face");
  }
  for (const mesh::CellGroup& group : mesh.cell_groups) {
    check_name(group.name);
    for (mesh::CellId c : group.cells) {
      if (c < 0 || static_cast<std::size_t>(c) >= mesh.cells.size()) {
        misuse("cell group '" + group.name + "' refers to missing cell index " + std::to_string(c));
      }
    }
  }
}

struct Box {
  std::array<double, 3> low{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                            std::numeric_limits<double>::max()};
  std::array<double, 3> high{std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest(),
                             std::numeric_limits<double>::lowest()};
  void add(const geometry::Vec3& p) {
    for (int i = 0; i < 3; ++i) {
      low[static_cast<std::size_t>(i)] = std::min(low[static_cast<std::size_t>(i)], p[i]);
      high[static_cast<std::size_t>(i)] = std::max(high[static_cast<std::size_t>(i)], p[i]);
    }
  }
  bool empty() const { return low[0] > high[0]; }
};

/// Which cell groups each cell is in, as ids of distinct sets of group indices (0: none).
struct CellSets {
  std::vector<std::uint32_t> of_cell;
  std::vector<std::vector<std::size_t>> sets{{}};
};

CellSets cell_sets(const Mesh& mesh) {
  CellSets result;
  result.of_cell.assign(mesh.cells.size(), 0);
  std::map<std::pair<std::uint32_t, std::size_t>, std::uint32_t> next;  // (set, group) -> set + group
  for (std::size_t g = 0; g < mesh.cell_groups.size(); ++g) {
    for (mesh::CellId c : mesh.cell_groups[g].cells) {
      std::uint32_t& set = result.of_cell[static_cast<std::size_t>(c)];
      if (!result.sets[set].empty() && result.sets[set].back() == g) continue;  // listed twice
      const auto [it, added] = next.try_emplace({set, g}, static_cast<std::uint32_t>(result.sets.size()));
      if (added) {
        std::vector<std::size_t> grown = result.sets[set];
        grown.push_back(g);
        result.sets.push_back(std::move(grown));
      }
      set = it->second;
    }
  }
  return result;
}

/// Writes one entity record of $Entities.
void write_entity(Out& out, int tag, const Box& box, std::span<const int> physical) {
  out.int32(tag);
  for (std::size_t i = 0; i < 3; ++i) out.real(box.empty() ? 0.0 : box.low[i]);
  for (std::size_t i = 0; i < 3; ++i) out.real(box.empty() ? 0.0 : box.high[i]);
  out.size(physical.size());
  for (int p : physical) out.int32(p);
  out.size(0);  // no bounding entities
  out.end_record();
}

/// Writes the elements of `list` in [begin, end) (all of one type) as one block.
void write_block(Out& out, const Mesh& mesh, int dimension, int entity, const ElementList& list, std::size_t begin,
                 std::size_t end, const std::vector<std::int64_t>* tags, std::int64_t first_tag) {
  out.int32(dimension);
  out.int32(entity);
  out.int32(gmsh::gmsh_type(list.type(begin)));
  out.size(end - begin);
  out.end_record();
  for (std::size_t i = begin; i < end; ++i) {
    const std::int64_t tag = tags ? (*tags)[i] : first_tag + static_cast<std::int64_t>(i - begin);
    out.size(static_cast<std::uint64_t>(tag));
    for (mesh::NodeId n : list.nodes(i)) out.size(static_cast<std::uint64_t>(mesh.node_id(n)));
    out.end_record();
  }
}

/// Cell entities: one per set of groups, numbered in order of first appearance, each with the
/// bounding box of its cells.
struct CellEntities {
  std::vector<int> of_set;             ///< per set of groups: its entity tag, 0 if no cell has it
  std::vector<std::uint32_t> sets;     ///< per entity (tag - 1): its set of groups
  std::vector<Box> boxes;              ///< per entity
};

CellEntities cell_entities(const Mesh& mesh, const CellSets& sets) {
  CellEntities e;
  e.of_set.assign(sets.sets.size(), 0);
  for (std::uint32_t set : sets.of_cell) {
    if (e.of_set[set] == 0) {
      e.sets.push_back(set);
      e.of_set[set] = static_cast<int>(e.sets.size());
    }
  }
  if (e.sets.empty()) e.sets.push_back(0);  // the nodes need an entity to sit on
  e.boxes.resize(e.sets.size());
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    Box& box = e.boxes[static_cast<std::size_t>(e.of_set[sets.of_cell[c]] - 1)];
    for (mesh::NodeId n : mesh.cells.nodes(c)) box.add(mesh.points[static_cast<std::size_t>(n)]);
  }
  return e;
}

void write_format(Out& out, bool binary) {
  out.text(binary ? "$MeshFormat\n4.1 1 8\n" : "$MeshFormat\n4.1 0 8\n");
  if (binary) {
    out.int32(1);
    out.text("\n");
  }
  out.text("$EndMeshFormat\n");
}

void write_physical_names(Out& out, const Mesh& mesh, std::span<const int> patch_tags, std::span<const int> group_tags) {
  if (mesh.patches.empty() && mesh.cell_groups.empty()) return;
  const int d = mesh.dimension;
  out.text("$PhysicalNames\n" + std::to_string(mesh.patches.size() + mesh.cell_groups.size()) + "\n");
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    out.text(std::to_string(d - 1) + " " + std::to_string(patch_tags[p]) + " \"" + mesh.patches[p].name + "\"\n");
  }
  for (std::size_t g = 0; g < mesh.cell_groups.size(); ++g) {
    out.text(std::to_string(d) + " " + std::to_string(group_tags[g]) + " \"" + mesh.cell_groups[g].name + "\"\n");
  }
  out.text("$EndPhysicalNames\n");
}

/// $Entities: one per patch (its physical tag), then the cell entities.
void write_entities(Out& out, const Mesh& mesh, std::span<const int> patch_tags, std::span<const int> group_tags,
                    const CellSets& sets, const CellEntities& entities) {
  const int d = mesh.dimension;
  out.begin_section("Entities");
  const std::size_t patch_entities = mesh.patches.size();
  out.size(0);  // points
  out.size(d == 3 ? 0 : patch_entities);
  out.size(d == 3 ? patch_entities : entities.sets.size());
  out.size(d == 3 ? entities.sets.size() : 0);
  out.end_record();
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    Box box;
    for (mesh::NodeId n : mesh.patches[p].faces.all_nodes()) box.add(mesh.points[static_cast<std::size_t>(n)]);
    const int tag[] = {patch_tags[p]};
    write_entity(out, static_cast<int>(p) + 1, box, tag);
  }
  for (std::size_t e = 0; e < entities.sets.size(); ++e) {
    std::vector<int> physical;
    for (std::size_t g : sets.sets[entities.sets[e]]) physical.push_back(group_tags[g]);
    write_entity(out, static_cast<int>(e) + 1, entities.boxes[e], physical);
  }
  out.end_section("Entities");
}

/// $Nodes: one block, on the first cell entity.
void write_nodes(Out& out, const Mesh& mesh) {
  const std::size_t n = mesh.points.size();
  std::int64_t min_node = 0, max_node = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t id = mesh.node_id(static_cast<mesh::NodeId>(i));
    min_node = i == 0 ? id : std::min(min_node, id);
    max_node = i == 0 ? id : std::max(max_node, id);
  }
  out.begin_section("Nodes");
  out.size(n > 0 ? 1 : 0);
  out.size(n);
  out.size(static_cast<std::uint64_t>(min_node));
  out.size(static_cast<std::uint64_t>(max_node));
  out.end_record();
  if (n > 0) {
    out.int32(mesh.dimension);
    out.int32(1);
    out.int32(0);  // no parametric coordinates
    out.size(n);
    out.end_record();
    for (std::size_t i = 0; i < n; ++i) {
      out.size(static_cast<std::uint64_t>(mesh.node_id(static_cast<mesh::NodeId>(i))));
      out.end_record();
    }
    for (const geometry::Vec3& p : mesh.points) {
      out.real(p.x);
      out.real(p.y);
      out.real(p.z);
      out.end_record();
    }
  }
  out.end_section("Nodes");
}

/// $Elements: blocks of runs of consecutive cells with one entity and type, then the faces by
/// patch and type, numbered after the cells.
void write_elements(Out& out, const Mesh& mesh, const CellSets& sets, const CellEntities& entities) {
  const int d = mesh.dimension;
  struct Run {
    std::size_t begin, end;
  };
  std::vector<Run> cell_runs;
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    if (c == 0 || mesh.cells.type(c) != mesh.cells.type(c - 1) || sets.of_cell[c] != sets.of_cell[c - 1]) {
      cell_runs.push_back({c, c});
    }
    cell_runs.back().end = c + 1;
  }
  std::vector<std::vector<Run>> face_runs(mesh.patches.size());
  std::size_t blocks = cell_runs.size(), faces = 0;
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    const ElementList& list = mesh.patches[p].faces;
    for (std::size_t f = 0; f < list.size(); ++f) {
      if (f == 0 || list.type(f) != list.type(f - 1)) face_runs[p].push_back({f, f});
      face_runs[p].back().end = f + 1;
    }
    blocks += face_runs[p].size();
    faces += list.size();
  }
  std::int64_t min_cell = 0, max_cell = 0;
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    const std::int64_t id = mesh.cell_id(static_cast<mesh::CellId>(c));
    min_cell = c == 0 ? id : std::min(min_cell, id);
    max_cell = c == 0 ? id : std::max(max_cell, id);
  }
  const std::int64_t first_face = max_cell + 1;
  const std::size_t elements = mesh.cells.size() + faces;
  out.begin_section("Elements");
  out.size(blocks);
  out.size(elements);
  out.size(static_cast<std::uint64_t>(mesh.cells.empty() ? (faces > 0 ? first_face : 0) : min_cell));
  out.size(static_cast<std::uint64_t>(faces > 0 ? first_face + static_cast<std::int64_t>(faces) - 1 : max_cell));
  out.end_record();
  for (const Run& run : cell_runs) {
    const int entity = entities.of_set[sets.of_cell[run.begin]];
    const std::vector<std::int64_t>* ids = mesh.cell_ids.empty() ? nullptr : &mesh.cell_ids;
    write_block(out, mesh, d, entity, mesh.cells, run.begin, run.end, ids, static_cast<std::int64_t>(run.begin) + 1);
  }
  std::int64_t next_face = first_face;
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    for (const Run& run : face_runs[p]) {
      write_block(out, mesh, d - 1, static_cast<int>(p) + 1, mesh.patches[p].faces, run.begin, run.end, nullptr,
                  next_face);
      next_face += static_cast<std::int64_t>(run.end - run.begin);
    }
  }
  out.end_section("Elements");
}

}  // namespace

void write_gmsh(std::ostream& stream, const Mesh& mesh, const GmshWriteOptions& options) {
  check_mesh(mesh);
  const std::vector<int> patch_tags = physical_tags(mesh.patches);
  const std::vector<int> group_tags = physical_tags(mesh.cell_groups);
  const CellSets sets = cell_sets(mesh);
  const CellEntities entities = cell_entities(mesh, sets);
  Out out(stream, options.binary);
  write_format(out, options.binary);
  write_physical_names(out, mesh, patch_tags, group_tags);
  write_entities(out, mesh, patch_tags, group_tags, sets, entities);
  write_nodes(out, mesh);
  write_elements(out, mesh, sets, entities);
  out.flush();
}

void write_gmsh(const std::filesystem::path& path, const Mesh& mesh, const GmshWriteOptions& options) {
  AtomicFile file(path);
  write_gmsh(file.stream(), mesh, options);
  file.commit();
}

}  // namespace hotmesh::io
