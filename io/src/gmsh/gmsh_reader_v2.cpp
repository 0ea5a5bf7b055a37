// hotmesh io: $Nodes and $Elements of Gmsh format 2.2, ASCII and binary.
// An element's first tag is its physical group (0: none), the second its elementary entity.
// Gmsh 2.2 has no way to put one element in two physical groups: it writes the element once
// per group, in consecutive records with new element tags (checked with gmsh 4.8.4). Such a
// repeat -- same type, same elementary entity and same nodes as the element just before it,
// another physical group -- is read as one element that belongs to both groups, so a cell is
// never duplicated; a face then lands in each of its patches. The element keeps its first tag.
// Further tags (partition numbers of a partitioned mesh) are ignored: the 2.2 file of a
// partitioned mesh still lists every node and element once.
#include <array>
#include <limits>
#include <vector>

#include "gmsh/gmsh_format.hpp"
#include "gmsh/gmsh_reader.hpp"

namespace hotmesh::io::gmsh {
namespace {

constexpr int kMaxInt = std::numeric_limits<int>::max();

/// Adds 2.2 elements to the builder, merging an element's per-group repeats.
class ElementSink {
 public:
  explicit ElementSink(MeshBuilder& b) : b_(b) {}

  void add(const Scanner& s, int gmsh_type, std::int64_t tag, std::int64_t physical, std::int64_t elementary,
           std::span<const std::int64_t> node_tags, std::size_t at) {
    const auto type = element_type(gmsh_type);
    if (!type) {
      if (gmsh_type != kPointType) s.fail_at(at, unsupported_type_message(gmsh_type));
      for (std::int64_t t : node_tags) b_.node(t, at);
      previous_dimension_ = 0;
      return;
    }
    if (physical < 0 || physical > kMaxInt) {
      s.fail_at(at, "element " + std::to_string(tag) + " has physical tag " + std::to_string(physical) +
                        " (must be 0 for none, or positive)");
    }
    std::array<mesh::NodeId, mesh::kMaxElementNodes> nodes{};
    for (std::size_t k = 0; k < node_tags.size(); ++k) nodes[k] = b_.node(node_tags[k], at);
    const std::span<const mesh::NodeId> used(nodes.data(), node_tags.size());
    const int dimension = mesh::dimension(*type);
    const auto group = static_cast<int>(physical);
    const auto d = static_cast<std::size_t>(dimension);
    if (group != 0 && dimension == previous_dimension_ && elementary == previous_elementary_[d] &&
        b_.repeats_last(*type, used)) {
      const std::uint32_t set = b_.last_membership(dimension);
      if (set != 0 && !b_.contains(set, group)) {
        b_.set_last_membership(dimension, b_.with_tag(set, group), at);
        return;
      }
    }
    if (group != cached_group_) {
      cached_group_ = group;
      const int one[] = {group};
      cached_set_ = group == 0 ? 0 : b_.membership(one);
    }
    b_.add_element(*type, tag, used, cached_set_, at);
    previous_dimension_ = dimension;
    previous_elementary_[d] = elementary;
  }

 private:
  MeshBuilder& b_;
  int previous_dimension_ = 0;
  std::array<std::int64_t, 4> previous_elementary_{};
  int cached_group_ = 0;
  std::uint32_t cached_set_ = 0;
};

/// Nodes of an element type (points included), 0 for types the reader rejects.
std::size_t nodes_of(int gmsh_type) {
  if (gmsh_type == kPointType) return 1;
  const auto type = element_type(gmsh_type);
  return type ? static_cast<std::size_t>(mesh::node_count(*type)) : 0;
}

void read_elements_ascii(Scanner& s, MeshBuilder& b, std::size_t n) {
  ElementSink sink(b);
  std::array<std::int64_t, mesh::kMaxElementNodes> node_tags{};
  for (std::size_t i = 0; i < n; ++i) {
    s.skip_blank();
    const std::size_t at = s.position();
    const std::int64_t tag = s.integer("element tag");
    const int type = s.small_integer("element type", std::numeric_limits<int>::min(), kMaxInt);
    const std::size_t needed = nodes_of(type);
    if (needed == 0) s.fail_at(at, unsupported_type_message(type));
    const int tag_count = s.small_integer("number of element tags", 0, kMaxInt);
    std::int64_t physical = 0, elementary = 0;
    for (int k = 0; k < tag_count; ++k) {
      const std::int64_t value = s.integer("element tag list entry");
      if (k == 0) physical = value;
      if (k == 1) elementary = value;
    }
    for (std::size_t k = 0; k < needed; ++k) {
      if (!s.more_on_line()) wrong_node_count(s, at, tag, type, k, needed);
      node_tags[k] = s.integer("node tag");
    }
    if (s.more_on_line()) wrong_node_count(s, at, tag, type, needed + 1, needed);
    s.end_line("the element");
    sink.add(s, type, tag, physical, elementary, std::span(node_tags.data(), needed), at);
  }
}

void read_elements_binary(Scanner& s, MeshBuilder& b, std::size_t n) {
  ElementSink sink(b);
  std::vector<std::int32_t> record;
  std::array<std::int64_t, mesh::kMaxElementNodes> node_tags{};
  std::size_t done = 0;
  while (done < n) {
    const std::size_t header_at = s.position();
    const std::int32_t type = s.binary_value<std::int32_t>("element type");
    const std::int32_t count = s.binary_value<std::int32_t>("number of elements of the block");
    const std::int32_t tag_count = s.binary_value<std::int32_t>("number of element tags");
    if (count < 1 || static_cast<std::size_t>(count) > n - done) {
      s.fail_at(header_at, "element block of " + std::to_string(count) + " elements, but " + std::to_string(n - done) +
                               " remain of the section's count");
    }
    if (tag_count < 0) s.fail_at(header_at, "negative number of element tags " + std::to_string(tag_count));
    const std::size_t needed = nodes_of(type);
    if (needed == 0) s.fail_at(header_at, unsupported_type_message(type));
    const std::size_t ints = 1 + static_cast<std::size_t>(tag_count) + needed;
    s.checked_count(static_cast<std::uint64_t>(count), 4 * ints, header_at, "number of elements of the block");
    record.resize(ints);
    for (std::int32_t j = 0; j < count; ++j) {
      const std::size_t at = s.position();
      s.binary_values(record.data(), ints, "element");
      const std::int64_t physical = tag_count > 0 ? record[1] : 0;
      const std::int64_t elementary = tag_count > 1 ? record[2] : 0;
      const std::size_t first_node = 1 + static_cast<std::size_t>(tag_count);
      for (std::size_t k = 0; k < needed; ++k) node_tags[k] = record[first_node + k];
      sink.add(s, type, record[0], physical, elementary, std::span(node_tags.data(), needed), at);
    }
    done += static_cast<std::size_t>(count);
  }
}

}  // namespace

void read_nodes_v2(Scanner& s, MeshBuilder& b) {
  const bool binary = s.binary();
  const std::size_t n = s.count("number of nodes", binary ? 28 : 8);
  s.end_line("the number of nodes");
  b.begin_nodes(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (binary) {
      const std::size_t at = s.position();
      const std::int32_t tag = s.binary_value<std::int32_t>("node tag");
      b.add_node_tag(tag, at);
      double xyz[3];
      s.binary_values(xyz, 3, "node coordinates");
      b.add_point({xyz[0], xyz[1], xyz[2]}, at);
    } else {
      s.skip_blank();
      const std::size_t at = s.position();
      b.add_node_tag(s.integer("node tag"), at);
      const double x = s.real("x coordinate");
      const double y = s.real("y coordinate");
      const double z = s.real("z coordinate");
      s.end_line("the node's coordinates");
      b.add_point({x, y, z}, at);
    }
  }
  b.end_nodes();
  s.expect_end("Nodes");
}

void read_elements_v2(Scanner& s, MeshBuilder& b) {
  const bool binary = s.binary();
  const std::size_t n = s.count("number of elements", 8);
  s.end_line("the number of elements");
  if (binary) {
    read_elements_binary(s, b, n);
  } else {
    read_elements_ascii(s, b, n);
  }
  s.expect_end("Elements");
}

}  // namespace hotmesh::io::gmsh
