// hotmesh io (private): pieces of the Gmsh reader shared by its files. gmsh_reader.cpp reads
// the sections common to both versions and drives the rest; gmsh_reader_v2.cpp and
// gmsh_reader_v4.cpp read $Nodes / $Elements (and $Entities) of formats 2.2 and 4.1.
// All of them feed a MeshBuilder, which turns nodes, elements and physical groups into a
// mesh::Mesh once the whole file is read (only then is the mesh dimension known).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "gmsh/gmsh_scanner.hpp"
#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::io::gmsh {

/// Node tag -> node index. Tags below a limit proportional to the declared node count go in
/// a vector indexed by tag; larger (sparse) tags go in a hash map.
class NodeTagMap {
 public:
  void prepare(std::size_t expected_nodes);
  /// False if the tag is already taken.
  bool insert(std::int64_t tag, mesh::NodeId index);
  /// -1 if no node has this tag.
  mesh::NodeId find(std::int64_t tag) const {
    if (tag >= 0 && static_cast<std::uint64_t>(tag) < dense_.size()) return dense_[static_cast<std::size_t>(tag)];
    if (sparse_.empty()) return -1;
    const auto it = sparse_.find(tag);
    return it == sparse_.end() ? -1 : it->second;
  }

 private:
  std::uint64_t dense_limit_ = 0;
  std::vector<mesh::NodeId> dense_;
  std::unordered_map<std::int64_t, mesh::NodeId> sparse_;
};

/// Collects what the version readers find and assembles the mesh.
class MeshBuilder {
 public:
  explicit MeshBuilder(Scanner& scanner) : scanner_(scanner) {}

  // ---- physical groups ----
  void add_physical_name(int dimension, int tag, std::string_view name, std::size_t at);
  /// Interned set of physical tags (any order, repeats allowed); 0 is the empty set.
  std::uint32_t membership(std::span<const int> physical_tags);
  /// The set `set` plus `physical_tag`.
  std::uint32_t with_tag(std::uint32_t set, int physical_tag);
  bool contains(std::uint32_t set, int physical_tag) const;

  // ---- nodes ----
  bool has_nodes() const { return nodes_read_; }
  void begin_nodes(std::size_t expected);
  /// The tag of the next node (4.1 lists a block's tags before its coordinates); fails for a
  /// tag < 1 or a tag already used.
  void add_node_tag(std::int64_t tag, std::size_t at);
  /// The coordinates of the next node whose tag was given; fails if one is not finite.
  void add_point(const geometry::Vec3& p, std::size_t at);
  void end_nodes() { nodes_read_ = true; }
  /// Index of the node with `tag`; an element at `at` refers to it.
  mesh::NodeId node(std::int64_t tag, std::size_t at) const {
    const mesh::NodeId index = tags_.find(tag);
    if (index < 0) undefined_node(tag, at);
    return index;
  }

  // ---- elements ----
  void add_element(mesh::ElementType type, std::int64_t tag, std::span<const mesh::NodeId> nodes, std::uint32_t set,
                   std::size_t at);
  /// Gmsh 2.2 writes an element once per physical group it is in, in consecutive lines:
  /// true if `nodes` of `type` repeat the last element of that dimension.
  bool repeats_last(mesh::ElementType type, std::span<const mesh::NodeId> nodes) const;
  std::uint32_t last_membership(int dimension) const;
  void set_last_membership(int dimension, std::uint32_t set, std::size_t at);

  /// The mesh; checks names of physical groups.
  mesh::Mesh finish();

 private:
  struct Elements {
    mesh::ElementList list;
    std::vector<std::int64_t> tags;
    std::vector<std::uint32_t> sets;
    std::vector<std::size_t> first_use;  ///< by set id: where the set was first used
  };
  struct Name {
    std::string name;
    std::size_t at = 0;
  };
  /// Physical tags used by elements of `dimension` (plus named ones), ascending, and for
  /// each set the indices (into that list) of its tags.
  struct Groups {
    std::vector<int> tags;
    std::vector<std::vector<std::size_t>> of_set;
  };

  [[noreturn]] void undefined_node(std::int64_t tag, std::size_t at) const;
  void note_use(Elements& e, std::uint32_t set, std::size_t at);
  Groups groups_of(int dimension) const;
  /// The group's name in $PhysicalNames, or (none, or empty) its tag, with a warning; `kind`
  /// ("patch", "cell group") names what the group becomes.
  std::string name_of(int dimension, int tag, const char* kind) const;

  Scanner& scanner_;
  bool nodes_read_ = false;
  mesh::Mesh mesh_;
  NodeTagMap tags_;
  std::array<Elements, 4> elements_;  ///< by dimension (0 unused)
  std::vector<std::vector<int>> sets_{{}};
  std::map<std::vector<int>, std::uint32_t> set_ids_{{{}, 0u}};
  std::map<std::pair<int, int>, Name> names_;  ///< (dimension, tag)
};

/// Physical groups of the geometric entities of a 4.1 file: (dimension, tag) -> set.
using EntityGroups = std::unordered_map<std::int64_t, std::uint32_t>;
inline std::int64_t entity_key(int dimension, int tag) {
  return static_cast<std::int64_t>(dimension) * (std::int64_t{1} << 32) + tag;
}

/// An element line or record with too few (`found` < `needed`) or too many node tags.
[[noreturn]] void wrong_node_count(const Scanner& s, std::size_t at, std::int64_t tag, int gmsh_type, std::size_t found,
                                   std::size_t needed);

void read_nodes_v2(Scanner& s, MeshBuilder& b);
void read_elements_v2(Scanner& s, MeshBuilder& b);
void read_entities_v4(Scanner& s, MeshBuilder& b, EntityGroups& entities);
void read_nodes_v4(Scanner& s, MeshBuilder& b);
/// `entities` is null if the file has no $Entities section (then no element has groups).
void read_elements_v4(Scanner& s, MeshBuilder& b, const EntityGroups* entities);

}  // namespace hotmesh::io::gmsh
