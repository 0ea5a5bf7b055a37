// hotmesh io: $Entities, $Nodes and $Elements of Gmsh format 4.1, ASCII and binary.
// Physical groups belong to geometric entities ($Entities); an element is in the groups of
// the entity its block names, so an entity with several physical tags puts its elements in
// several groups at once. Nodes come in blocks, tags first, then coordinates, followed by
// parametric coordinates (u for curves, u v for surfaces, u v w for volumes) when the block's
// parametric flag is set; those are skipped. In binary files counts and tags are 64-bit
// size_t, entity numbers and element types 32-bit int, coordinates double.
#include <array>
#include <limits>
#include <vector>

#include "gmsh/gmsh_format.hpp"
#include "gmsh/gmsh_reader.hpp"

namespace hotmesh::io::gmsh {
namespace {

constexpr int kMinInt = std::numeric_limits<int>::min();
constexpr int kMaxInt = std::numeric_limits<int>::max();
constexpr std::uint64_t kMaxTag = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());

/// A 64-bit tag of a binary file as int64 (larger ones are corrupt).
std::int64_t binary_tag(Scanner& s, const char* what) {
  const std::size_t at = s.position();
  const auto value = s.binary_value<std::uint64_t>(what);
  if (value > kMaxTag) s.fail_at(at, std::string(what) + " " + std::to_string(value) + " is out of range");
  return static_cast<std::int64_t>(value);
}

std::size_t binary_count(Scanner& s, const char* what, std::size_t min_bytes) {
  const std::size_t at = s.position();
  return s.checked_count(s.binary_value<std::uint64_t>(what), min_bytes, at, what);
}

int binary_int(Scanner& s, const char* what, int low, int high) {
  const std::size_t at = s.position();
  const std::int32_t value = s.binary_value<std::int32_t>(what);
  if (value < low || value > high) {
    s.fail_at(at, std::string(what) + " " + std::to_string(value) + " is out of range (" + std::to_string(low) +
                      " to " + std::to_string(high) + ")");
  }
  return value;
}

/// A physical tag of an entity. Gmsh writes -t for an entity it put in group t with the
/// opposite orientation (`Physical Surface(t) = CombinedBoundary{...}`) and reads the group as t:
/// so does hotmesh. Zero is no group's tag.
int physical_group(Scanner& s, std::size_t at, std::int64_t value) {
  if (value == 0 || value < -kMaxInt || value > kMaxInt) {
    s.fail_at(at, "physical tag " + std::to_string(value) + " is out of range (1 to " + std::to_string(kMaxInt) +
                      ", or its negative)");
  }
  return static_cast<int>(value < 0 ? -value : value);
}

/// One entity of $Entities: its tag and physical tags (bounding box and boundary skipped).
void read_entity(Scanner& s, MeshBuilder& b, EntityGroups& entities, int dimension, std::vector<int>& physical) {
  physical.clear();
  std::size_t at = 0;
  int tag = 0;
  if (s.binary()) {
    at = s.position();
    tag = s.binary_value<std::int32_t>("entity tag");
    double box[6];
    s.binary_values(box, dimension == 0 ? 3 : 6, "entity bounding box");
    const std::size_t n = binary_count(s, "number of physical tags", 4);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t tag_at = s.position();
      physical.push_back(physical_group(s, tag_at, s.binary_value<std::int32_t>("physical tag")));
    }
    if (dimension > 0) {
      const std::size_t bounding = binary_count(s, "number of bounding entities", 4);
      s.need(4 * bounding, "bounding entity tags");
      for (std::size_t k = 0; k < bounding; ++k) s.binary_value<std::int32_t>("bounding entity tag");
    }
  } else {
    s.skip_blank();
    at = s.position();
    tag = s.small_integer("entity tag", kMinInt, kMaxInt);
    for (int k = 0; k < (dimension == 0 ? 3 : 6); ++k) s.real("entity coordinate");
    const std::size_t n = s.count("number of physical tags", 2);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t tag_at = s.position();
      physical.push_back(physical_group(s, tag_at, s.integer("physical tag")));
    }
    if (dimension > 0) {
      const std::size_t bounding = s.count("number of bounding entities", 2);
      for (std::size_t k = 0; k < bounding; ++k) s.integer("bounding entity tag");
    }
    s.end_line("the entity");
  }
  if (!entities.emplace(entity_key(dimension, tag), b.membership(physical)).second) {
    s.fail_at(at, "entity " + std::to_string(tag) + " of dimension " + std::to_string(dimension) + " is defined twice");
  }
}

}  // namespace

void read_entities_v4(Scanner& s, MeshBuilder& b, EntityGroups& entities) {
  std::array<std::size_t, 4> counts{};
  static constexpr const char* kWhat[] = {"number of points", "number of curves", "number of surfaces",
                                          "number of volumes"};
  for (std::size_t dim = 0; dim < 4; ++dim) {
    counts[dim] = s.binary() ? binary_count(s, kWhat[dim], dim == 0 ? 36 : 68) : s.count(kWhat[dim], 8);
  }
  if (!s.binary()) s.end_line("the entity counts");
  std::vector<int> physical;
  for (int dim = 0; dim < 4; ++dim) {
    for (std::size_t i = 0; i < counts[static_cast<std::size_t>(dim)]; ++i) read_entity(s, b, entities, dim, physical);
  }
  s.expect_end("Entities");
}

void read_nodes_v4(Scanner& s, MeshBuilder& b) {
  const bool binary = s.binary();
  std::size_t blocks = 0, total = 0;
  if (binary) {
    blocks = binary_count(s, "number of node blocks", 20);
    total = binary_count(s, "number of nodes", 32);
    binary_tag(s, "smallest node tag");
    binary_tag(s, "largest node tag");
  } else {
    blocks = s.count("number of node blocks", 8);
    total = s.count("number of nodes", 8);
    s.integer("smallest node tag");
    s.integer("largest node tag");
    s.end_line("the node counts");
  }
  b.begin_nodes(total);
  std::size_t done = 0;
  for (std::size_t block = 0; block < blocks; ++block) {
    const std::size_t at = s.position();
    int dimension = 0, parametric = 0;
    std::size_t n = 0;
    if (binary) {
      dimension = binary_int(s, "entity dimension", 0, 3);
      binary_int(s, "entity tag", kMinInt, kMaxInt);
      parametric = binary_int(s, "parametric flag", 0, 1);
      n = binary_count(s, "number of nodes in the block", 32);
    } else {
      s.skip_blank();
      dimension = s.small_integer("entity dimension", 0, 3);
      s.small_integer("entity tag", kMinInt, kMaxInt);
      parametric = s.small_integer("parametric flag", 0, 1);
      n = s.count("number of nodes in the block", 8);
      s.end_line("the node block header");
    }
    if (n > total - done) {
      s.fail_at(at, "node block of " + std::to_string(n) + " nodes, but the section header announces " +
                        std::to_string(total) + " nodes in all and " + std::to_string(done) + " came before");
    }
    const std::size_t values = 3 + static_cast<std::size_t>(parametric != 0 ? dimension : 0);
    if (binary) {
      s.checked_count(n, 8 * (1 + values), at, "number of nodes in the block");
      for (std::size_t j = 0; j < n; ++j) {
        const std::size_t tag_at = s.position();
        b.add_node_tag(binary_tag(s, "node tag"), tag_at);
      }
      double xyz[6];
      for (std::size_t j = 0; j < n; ++j) {
        const std::size_t xyz_at = s.position();
        s.binary_values(xyz, values, "node coordinates");
        b.add_point({xyz[0], xyz[1], xyz[2]}, xyz_at);
      }
    } else {
      for (std::size_t j = 0; j < n; ++j) {
        s.skip_blank();
        const std::size_t tag_at = s.position();
        b.add_node_tag(s.integer("node tag"), tag_at);
      }
      for (std::size_t j = 0; j < n; ++j) {
        s.skip_blank();
        const std::size_t xyz_at = s.position();
        const double x = s.real("x coordinate");
        const double y = s.real("y coordinate");
        const double z = s.real("z coordinate");
        for (std::size_t k = 3; k < values; ++k) s.real("parametric coordinate");
        s.end_line("the node's coordinates");
        b.add_point({x, y, z}, xyz_at);
      }
    }
    done += n;
  }
  if (done != total) {
    s.fail("the $Nodes header announces " + std::to_string(total) + " nodes, its blocks hold " + std::to_string(done));
  }
  b.end_nodes();
  s.expect_end("Nodes");
}

namespace {

/// The header of a block of $Elements: the entity its elements belong to and their type.
struct ElementBlock {
  std::size_t at = 0;  ///< where the header starts, for messages
  int dimension = 0, entity = 0, gmsh_type = 0;
  std::size_t count = 0;
};

ElementBlock read_element_block_header(Scanner& s) {
  ElementBlock block;
  block.at = s.position();
  if (s.binary()) {
    block.dimension = binary_int(s, "entity dimension", 0, 3);
    block.entity = binary_int(s, "entity tag", kMinInt, kMaxInt);
    block.gmsh_type = binary_int(s, "element type", kMinInt, kMaxInt);
    block.count = binary_count(s, "number of elements in the block", 16);
  } else {
    s.skip_blank();
    block.dimension = s.small_integer("entity dimension", 0, 3);
    block.entity = s.small_integer("entity tag", kMinInt, kMaxInt);
    block.gmsh_type = s.small_integer("element type", kMinInt, kMaxInt);
    block.count = s.count("number of elements in the block", 4);
    s.end_line("the element block header");
  }
  return block;
}

/// The physical groups of the block's entity (0 without $Entities).
std::uint32_t entity_set(Scanner& s, const ElementBlock& block, const EntityGroups* entities) {
  if (entities == nullptr) return 0;
  const auto it = entities->find(entity_key(block.dimension, block.entity));
  if (it == entities->end()) {
    s.fail_at(block.at, "element block on entity " + std::to_string(block.entity) + " of dimension " +
                            std::to_string(block.dimension) + ", which $Entities does not define");
  }
  return it->second;
}

/// The block's elements, each with `needed` nodes; added to `b` when they have a `type` (not
/// points).
void read_block_elements(Scanner& s, MeshBuilder& b, const ElementBlock& block, std::optional<mesh::ElementType> type,
                         std::size_t needed, std::uint32_t set) {
  std::array<mesh::NodeId, mesh::kMaxElementNodes> nodes{};
  std::array<std::uint64_t, 1 + mesh::kMaxElementNodes> record{};
  if (s.binary()) s.checked_count(block.count, 8 * (1 + needed), block.at, "number of elements in the block");
  for (std::size_t j = 0; j < block.count; ++j) {
    std::size_t element_at = 0;
    std::int64_t tag = 0;
    if (s.binary()) {
      element_at = s.position();
      s.binary_values(record.data(), 1 + needed, "element");
      for (std::size_t k = 0; k <= needed; ++k) {
        if (record[k] > kMaxTag) s.fail_at(element_at, "element or node tag out of range");
      }
      tag = static_cast<std::int64_t>(record[0]);
      for (std::size_t k = 0; k < needed; ++k) nodes[k] = b.node(static_cast<std::int64_t>(record[k + 1]), element_at);
    } else {
      s.skip_blank();
      element_at = s.position();
      tag = s.integer("element tag");
      for (std::size_t k = 0; k < needed; ++k) {
        if (!s.more_on_line()) wrong_node_count(s, element_at, tag, block.gmsh_type, k, needed);
        nodes[k] = b.node(s.integer("node tag"), element_at);
      }
      if (s.more_on_line()) wrong_node_count(s, element_at, tag, block.gmsh_type, needed + 1, needed);
      s.end_line("the element");
    }
    if (type) b.add_element(*type, tag, std::span(nodes.data(), needed), set, element_at);
  }
}

}  // namespace

void read_elements_v4(Scanner& s, MeshBuilder& b, const EntityGroups* entities) {
  std::size_t blocks = 0, total = 0;
  if (s.binary()) {
    blocks = binary_count(s, "number of element blocks", 20);
    total = binary_count(s, "number of elements", 16);
    binary_tag(s, "smallest element tag");
    binary_tag(s, "largest element tag");
  } else {
    blocks = s.count("number of element blocks", 8);
    total = s.count("number of elements", 4);
    s.integer("smallest element tag");
    s.integer("largest element tag");
    s.end_line("the element counts");
  }
  std::size_t done = 0;
  for (std::size_t i = 0; i < blocks; ++i) {
    const ElementBlock block = read_element_block_header(s);
    if (block.count > total - done) {
      s.fail_at(block.at, "element block of " + std::to_string(block.count) +
                              " elements, but the section header announces " + std::to_string(total) +
                              " elements in all and " + std::to_string(done) + " came before");
    }
    const auto type = element_type(block.gmsh_type);
    if (!type && block.gmsh_type != kPointType) s.fail_at(block.at, unsupported_type_message(block.gmsh_type));
    const std::size_t needed = type ? static_cast<std::size_t>(mesh::node_count(*type)) : 1;
    const std::uint32_t set = type ? entity_set(s, block, entities) : 0;
    read_block_elements(s, b, block, type, needed, set);
    done += block.count;
  }
  if (done != total) {
    s.fail("the $Elements header announces " + std::to_string(total) + " elements, its blocks hold " +
           std::to_string(done));
  }
  s.expect_end("Elements");
}

}  // namespace hotmesh::io::gmsh
