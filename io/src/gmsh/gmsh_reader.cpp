// hotmesh io: the Gmsh .msh reader's entry points. Reads $MeshFormat and $PhysicalNames,
// hands $Entities / $Nodes / $Elements to the reader of the file's version (2.2 or 4.1),
// skips sections it does not need, and assembles the mesh (MeshBuilder): cells are the
// elements of the highest dimension d, physical groups of dimension d become cell groups and
// those of dimension d-1 patches, named by $PhysicalNames (an unnamed group by its tag).
#include "gmsh/gmsh_reader.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <set>

#include "gmsh/gmsh_format.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/gmsh.hpp"

namespace hotmesh::io {
namespace gmsh {
namespace {

constexpr std::size_t kUnused = std::numeric_limits<std::size_t>::max();
constexpr auto kMaxIndex = static_cast<std::size_t>(std::numeric_limits<mesh::NodeId>::max());

std::string number_text(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

}  // namespace

// ---- NodeTagMap -------------------------------------------------------------------------

void NodeTagMap::prepare(std::size_t expected_nodes) {
  // Tags up to a few times the node count (Gmsh numbers nodes 1..n, sometimes with gaps) go
  // in a vector; a file with far larger tags does not make us allocate for them.
  dense_limit_ = 4 * static_cast<std::uint64_t>(expected_nodes) + 1024;
  dense_.clear();
  sparse_.clear();
}

bool NodeTagMap::insert(std::int64_t tag, mesh::NodeId index) {
  const auto t = static_cast<std::uint64_t>(tag);
  if (tag >= 0 && t < dense_limit_) {
    if (t >= dense_.size()) {
      const std::uint64_t grown =
          std::max<std::uint64_t>(t + 1, std::min<std::uint64_t>(2 * dense_.size(), dense_limit_));
      dense_.resize(static_cast<std::size_t>(grown), -1);
    }
    mesh::NodeId& slot = dense_[static_cast<std::size_t>(t)];
    if (slot >= 0) return false;
    slot = index;
    return true;
  }
  return sparse_.emplace(tag, index).second;
}

// ---- MeshBuilder ------------------------------------------------------------------------

void MeshBuilder::add_physical_name(int dimension, int tag, std::string_view name, std::size_t at) {
  const auto [it, added] = names_.try_emplace({dimension, tag}, Name{std::string(name), at});
  if (!added) {
    scanner_.fail_at(at, "physical group " + std::to_string(tag) + " (dimension " + std::to_string(dimension) +
                             ") is named twice ('" + it->second.name + "' and '" + std::string(name) + "')");
  }
}

std::uint32_t MeshBuilder::membership(std::span<const int> physical_tags) {
  std::vector<int> key(physical_tags.begin(), physical_tags.end());
  std::sort(key.begin(), key.end());
  key.erase(std::unique(key.begin(), key.end()), key.end());
  const auto it = set_ids_.find(key);
  if (it != set_ids_.end()) return it->second;
  const auto id = static_cast<std::uint32_t>(sets_.size());
  sets_.push_back(key);
  set_ids_.emplace(std::move(key), id);
  return id;
}

std::uint32_t MeshBuilder::with_tag(std::uint32_t set, int physical_tag) {
  std::vector<int> tags = sets_[set];
  tags.push_back(physical_tag);
  return membership(tags);
}

bool MeshBuilder::contains(std::uint32_t set, int physical_tag) const {
  const std::vector<int>& tags = sets_[set];
  return std::binary_search(tags.begin(), tags.end(), physical_tag);
}

void MeshBuilder::begin_nodes(std::size_t expected) {
  tags_.prepare(expected);
  mesh_.points.reserve(expected);
  mesh_.node_ids.reserve(expected);
}

void MeshBuilder::add_node_tag(std::int64_t tag, std::size_t at) {
  if (tag < 1) scanner_.fail_at(at, "node tag " + std::to_string(tag) + " is not positive");
  if (mesh_.node_ids.size() >= kMaxIndex) scanner_.fail_at(at, "more nodes than hotmesh can index (2^31 - 1)");
  if (!tags_.insert(tag, static_cast<mesh::NodeId>(mesh_.node_ids.size()))) {
    scanner_.fail_at(at, "node tag " + std::to_string(tag) + " is defined twice");
  }
  mesh_.node_ids.push_back(tag);
}

void MeshBuilder::add_point(const geometry::Vec3& p, std::size_t at) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
    scanner_.fail_at(at, "node " + std::to_string(mesh_.node_ids[mesh_.points.size()]) +
                             " has a coordinate that is not a finite number (" + number_text(p.x) + ", " +
                             number_text(p.y) + ", " + number_text(p.z) + ")");
  }
  mesh_.points.push_back(p);
}

void MeshBuilder::undefined_node(std::int64_t tag, std::size_t at) const {
  scanner_.fail_at(at, "element refers to node " + std::to_string(tag) + ", which $Nodes does not define");
}

void MeshBuilder::note_use(Elements& e, std::uint32_t set, std::size_t at) {
  if (set >= e.first_use.size()) e.first_use.resize(sets_.size(), kUnused);
  if (e.first_use[set] == kUnused) e.first_use[set] = at;
}

void MeshBuilder::add_element(mesh::ElementType type, std::int64_t tag, std::span<const mesh::NodeId> nodes,
                              std::uint32_t set, std::size_t at) {
  Elements& e = elements_[static_cast<std::size_t>(mesh::dimension(type))];
  if (e.tags.size() >= kMaxIndex) scanner_.fail_at(at, "more elements than hotmesh can index (2^31 - 1)");
  e.list.add(type, nodes);
  e.tags.push_back(tag);
  e.sets.push_back(set);
  note_use(e, set, at);
}

bool MeshBuilder::repeats_last(mesh::ElementType type, std::span<const mesh::NodeId> nodes) const {
  const Elements& e = elements_[static_cast<std::size_t>(mesh::dimension(type))];
  if (e.tags.empty()) return false;
  const std::size_t last = e.tags.size() - 1;
  if (e.list.type(last) != type) return false;
  const auto previous = e.list.nodes(last);
  return std::equal(previous.begin(), previous.end(), nodes.begin(), nodes.end());
}

std::uint32_t MeshBuilder::last_membership(int dimension) const {
  return elements_[static_cast<std::size_t>(dimension)].sets.back();
}

void MeshBuilder::set_last_membership(int dimension, std::uint32_t set, std::size_t at) {
  Elements& e = elements_[static_cast<std::size_t>(dimension)];
  e.sets.back() = set;
  note_use(e, set, at);
}

MeshBuilder::Groups MeshBuilder::groups_of(int dimension) const {
  const Elements& e = elements_[static_cast<std::size_t>(dimension)];
  std::set<int> tags;  // used by elements of this dimension, or named
  for (std::size_t set = 0; set < e.first_use.size(); ++set) {
    if (e.first_use[set] != kUnused) tags.insert(sets_[set].begin(), sets_[set].end());
  }
  for (auto it = names_.lower_bound({dimension, std::numeric_limits<int>::min()});
       it != names_.end() && it->first.first == dimension; ++it) {
    tags.insert(it->first.second);
  }
  Groups groups;
  groups.tags.assign(tags.begin(), tags.end());
  groups.of_set.resize(sets_.size());
  for (std::size_t set = 0; set < e.first_use.size(); ++set) {
    if (e.first_use[set] == kUnused) continue;
    for (int tag : sets_[set]) {
      const auto at = std::lower_bound(groups.tags.begin(), groups.tags.end(), tag);
      groups.of_set[set].push_back(static_cast<std::size_t>(at - groups.tags.begin()));
    }
  }
  return groups;
}

std::string MeshBuilder::name_of(int dimension, int tag, const char* kind) const {
  const auto it = names_.find({dimension, tag});
  if (it != names_.end() && !it->second.name.empty()) return it->second.name;
  // Gmsh leaves a group unnamed unless told (`Physical Volume(101) = {...}`), or names it ""; its
  // tag is how its own tools refer to it, and how the case file may.
  std::string name = std::to_string(tag);
  spdlog::warn("{}: physical group {} (dimension {}) has {} in $PhysicalNames: its {} is named '{}'",
               scanner_.source(), tag, dimension, it == names_.end() ? "no name" : "an empty name", kind, name);
  return name;
}

mesh::Mesh MeshBuilder::finish() {
  const int d = !elements_[3].tags.empty() ? 3 : (!elements_[2].tags.empty() ? 2 : 0);
  if (d == 0) {
    throw InputError::in(scanner_.source(), elements_[1].tags.empty()
                                                ? "the file holds no 2D or 3D elements: nothing to use as cells"
                                                : "the file holds only lines and points: hotmesh needs 2D or 3D cells");
  }
  mesh_.dimension = d;
  scanner_.set_section("$Elements");

  Elements& cells = elements_[static_cast<std::size_t>(d)];
  const Groups cell_groups = groups_of(d);
  mesh_.cell_groups.resize(cell_groups.tags.size());
  for (std::size_t g = 0; g < cell_groups.tags.size(); ++g) {
    mesh::CellGroup& group = mesh_.cell_groups[g];
    group.tag = cell_groups.tags[g];
    group.name = name_of(d, group.tag, "cell group");
  }
  for (std::size_t c = 0; c < cells.sets.size(); ++c) {
    for (std::size_t g : cell_groups.of_set[cells.sets[c]]) {
      mesh_.cell_groups[g].cells.push_back(static_cast<mesh::CellId>(c));
    }
  }

  const Elements& faces = elements_[static_cast<std::size_t>(d - 1)];
  const Groups patch_groups = groups_of(d - 1);
  mesh_.patches.resize(patch_groups.tags.size());
  for (std::size_t p = 0; p < patch_groups.tags.size(); ++p) {
    mesh::Patch& patch = mesh_.patches[p];
    patch.tag = patch_groups.tags[p];
    patch.name = name_of(d - 1, patch.tag, "patch");
  }
  for (std::size_t f = 0; f < faces.sets.size(); ++f) {
    for (std::size_t p : patch_groups.of_set[faces.sets[f]]) {
      mesh_.patches[p].faces.add(faces.list.type(f), faces.list.nodes(f));
    }
  }

  scanner_.set_section("$PhysicalNames");
  std::map<std::string_view, int> tag_of_name;
  for (const mesh::Patch& patch : mesh_.patches) {
    const auto [it, added] = tag_of_name.try_emplace(patch.name, patch.tag);
    if (!added) {
      const std::string message = "physical groups " + std::to_string(it->second) + " and " +
                                  std::to_string(patch.tag) + " (dimension " + std::to_string(d - 1) +
                                  ") are both named '" + patch.name + "'; patch names must be unique";
      // One of the two has its name in $PhysicalNames (a tag names the other, or both are named).
      const auto named = names_.find({d - 1, patch.tag});
      scanner_.fail_at(named != names_.end() ? named->second.at : names_.at({d - 1, it->second}).at, message);
    }
  }

  mesh_.cells = std::move(cells.list);
  mesh_.cells.shrink_to_fit();  // grown element by element: a third of it was spare on the stator well
  mesh_.cell_ids = std::move(cells.tags);
  mesh_.cell_ids.shrink_to_fit();
  mesh_.derive_node_sets();
  return std::move(mesh_);
}

void wrong_node_count(const Scanner& s, std::size_t at, std::int64_t tag, int gmsh_type, std::size_t found,
                      std::size_t needed) {
  const auto type = element_type(gmsh_type);
  std::string text = "element " + std::to_string(tag) + " of type " + std::to_string(gmsh_type);
  if (type) text.append(" (").append(mesh::name(*type)).append(")");
  text += found < needed ? " has " + std::to_string(found) + " node tags, needs " + std::to_string(needed)
                         : " has more than " + std::to_string(needed) + " node tags";
  s.fail_at(at, text);
}

namespace {

enum class Version { v2, v4 };

Version read_format(Scanner& s) {
  s.set_section("$MeshFormat");
  s.skip_blank();
  if (s.at_end()) throw InputError::in(s.source(), "the file is empty, not a Gmsh .msh file");
  const std::size_t start = s.position();
  const std::string_view first = s.next_line();
  if (first == "$NOD" || first == "$NOE") {
    s.fail_at(start, "format 1.0 is not supported; save as 4.1 or 2.2");
  }
  if (first != "$MeshFormat") s.fail_at(start, "not a Gmsh .msh file: it does not start with $MeshFormat");
  s.skip_blank();
  const std::size_t version_at = s.position();
  const std::string_view version_text = s.word("the format version");
  if (version_text != "2.2" && version_text != "4.1") {
    s.fail_at(version_at, "format " + std::string(version_text) + " is not supported; save as 4.1 or 2.2");
  }
  const Version version = version_text == "2.2" ? Version::v2 : Version::v4;
  const int file_type = s.small_integer("file type", 0, 1);
  const std::size_t size_at = s.position();
  const std::int64_t data_size = s.integer("data size");
  s.end_line("the data size");
  if (file_type == 1) {
    if (data_size != 8) {
      s.fail_at(size_at, "binary files must have data size 8 (64-bit size_t), not " + std::to_string(data_size));
    }
    s.set_binary(true);
    const std::size_t marker_at = s.position();
    const auto one = s.binary_value<std::int32_t>("the binary byte-order marker");
    if (one == 0x01000000) {
      s.fail_at(marker_at,
                "the binary file has the other byte order (written on a big-endian machine); "
                "save it as ASCII");
    }
    if (one != 1) s.fail_at(marker_at, "bad binary byte-order marker " + std::to_string(one) + " (expected 1)");
  }
  s.expect_end("MeshFormat");
  return version;
}

void read_physical_names(Scanner& s, MeshBuilder& b) {
  const std::size_t n = s.count("number of physical names", 7);
  s.end_line("the number of physical names");
  for (std::size_t i = 0; i < n; ++i) {
    s.skip_blank();
    const std::size_t at = s.position();
    const int dimension = s.small_integer("physical group dimension", 0, 3);
    const int tag = s.small_integer("physical tag", 1, std::numeric_limits<int>::max());
    const std::string_view name = s.quoted("physical name");
    s.end_line("the physical name");
    b.add_physical_name(dimension, tag, name, at);
  }
  s.expect_end("PhysicalNames");
}

}  // namespace
}  // namespace gmsh

mesh::Mesh parse_gmsh(std::string_view content, std::string_view source) {
  using namespace gmsh;
  Scanner s(content, source);
  const Version version = read_format(s);
  MeshBuilder builder(s);
  EntityGroups entities;
  bool have_entities = false;
  bool have_elements = false;
  for (;;) {
    s.set_section("");
    s.skip_blank();
    if (s.at_end()) break;
    const std::size_t at = s.position();
    const std::string_view line = s.next_line();
    if (line.size() < 2 || line[0] != '$' || line.substr(1, 3) == "End") {
      s.fail_at(at, "expected a section such as $Nodes, found '" + std::string(line.substr(0, 40)) + "'");
    }
    const std::string_view name = line.substr(1);
    s.set_section(line);
    if (name == "MeshFormat") {
      s.fail_at(at, "a second $MeshFormat section");
    } else if (name == "PhysicalNames") {
      read_physical_names(s, builder);
    } else if (name == "PartitionedEntities") {
      s.fail_at(at,
                "partitioned meshes are not supported: save the mesh without partitions "
                "(Mesh.NbPartitions = 0, no -part)");
    } else if (name == "Entities" && version == Version::v4) {
      if (have_entities || builder.has_nodes()) s.fail_at(at, "$Entities must come once, before $Nodes");
      read_entities_v4(s, builder, entities);
      have_entities = true;
    } else if (name == "Nodes") {
      if (builder.has_nodes()) s.fail_at(at, "a second $Nodes section");
      if (version == Version::v2) {
        read_nodes_v2(s, builder);
      } else {
        read_nodes_v4(s, builder);
      }
    } else if (name == "Elements") {
      if (!builder.has_nodes()) s.fail_at(at, "$Elements comes before $Nodes");
      if (have_elements) s.fail_at(at, "a second $Elements section");
      if (version == Version::v2) {
        read_elements_v2(s, builder);
      } else {
        read_elements_v4(s, builder, have_entities ? &entities : nullptr);
      }
      have_elements = true;
    } else {
      s.skip_section(name);
    }
  }
  if (!builder.has_nodes()) s.fail("the file has no $Nodes section (is it cut short?)");
  if (!have_elements) s.fail("the file has no $Elements section (is it cut short?)");
  return builder.finish();
}

mesh::Mesh read_gmsh(const std::filesystem::path& path) { return parse_gmsh(read_file(path), path.string()); }

}  // namespace hotmesh::io
