// hotmesh tests: what `hotmesh deform` leaves in its output folder, read and compared.
// Header-only: the test programs that use it link hotmesh::io and GoogleTest's gmock.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "hotmesh/io/checkpoint_file.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "test_support.hpp"

namespace hotmesh::test {

inline nlohmann::json read_json(const std::filesystem::path& p) { return nlohmann::json::parse(read_text(p)); }

/// A checkpoint file's parts: its JSON header, and the bytes after it.
struct CheckpointParts {
  nlohmann::json header;
  std::string arrays;
};

inline CheckpointParts checkpoint_parts(const std::filesystem::path& path) {
  const std::string bytes = read_text(path);
  const std::string magic = "HOTMESH-CHECKPOINT\n";
  EXPECT_EQ(bytes.compare(0, magic.size(), magic), 0) << path;
  std::uint64_t length = 0;
  std::memcpy(&length, bytes.data() + magic.size(), sizeof length);
  const std::size_t header_at = magic.size() + sizeof length;
  return {nlohmann::json::parse(bytes.substr(header_at, static_cast<std::size_t>(length))),
          bytes.substr(header_at + static_cast<std::size_t>(length))};
}

/// Rewrites a checkpoint (format 4) in place as hotmesh wrote it in format 1, before issue 18:
/// `remaining` listed every step left, the pieces of a split increment and then each whole
/// increment to N, and the header carried the run's maxima (since derived from the records);
/// the hints' s and face, which format 3 appends to the arrays (two counts, 12 bytes per hint
/// and a checksum), and the previous points, which format 4 appends (a count, the points and a
/// checksum), were not there.
inline void rewrite_as_checkpoint_format_1(const std::filesystem::path& path) {
  auto [header, arrays] = checkpoint_parts(path);
  ASSERT_EQ(header["format_version"], 4);
  const std::size_t previous = header["previous_nodes"].get<std::size_t>();
  arrays.resize(arrays.size() - (2 * sizeof(std::uint64_t) + previous * 3 * sizeof(double)));
  header.erase("previous_nodes");
  header.erase("previous_lambda");
  const std::size_t hints = 3 * header["sliding_nodes"].get<std::size_t>();
  arrays.resize(arrays.size() - (3 * sizeof(std::uint64_t) + hints * (sizeof(double) + sizeof(std::int32_t))));
  const int n = header["increments"], done = header["finished_increments"];
  nlohmann::json remaining = header["split_pieces"];
  for (int k = done + (remaining.empty() ? 1 : 2); k <= n; ++k) {
    remaining.push_back({k, double(k - 1) / n, double(k) / n, 0});
  }
  header.erase("split_pieces");
  header["remaining"] = remaining;
  header["format_version"] = 1;
  header["max_normal_slip"] = 0.0;
  header["max_sliding_projection_distance"] = 0.0;
  const std::string text = header.dump();
  const std::uint64_t length = text.size();
  std::string out = "HOTMESH-CHECKPOINT\n";
  out.append(reinterpret_cast<const char*>(&length), sizeof length);
  out += text;
  out += arrays;
  write_text(path, out);
}

/// The largest distance between the nodes of the deformed meshes in two output folders, over
/// the first one's bounding-box diagonal.
inline double largest_relative_distance(const std::filesystem::path& a, const std::filesystem::path& b) {
  const auto ma = io::read_mesh(a / "deformed.msh").mesh, mb = io::read_mesh(b / "deformed.msh").mesh;
  EXPECT_EQ(ma.points.size(), mb.points.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < std::min(ma.points.size(), mb.points.size()); ++i) {
    largest = std::max(largest, distance(ma.points[i], mb.points[i]));
  }
  return largest / mesh::bounding_diagonal(ma.points);
}

/// Two output folders of runs that must end alike (a resumed run and the uninterrupted one):
/// the meshes and the restart file byte for byte, every increment's iterations and residuals in
/// report.json (not the times), and no checkpoint or temporary file left in `b`.
inline void expect_same_outputs(const std::filesystem::path& a, const std::filesystem::path& b) {
  for (const char* name : {"deformed.msh", "deformed.vtu", "restart.hmr"}) {
    ASSERT_TRUE(std::filesystem::exists(b / name)) << name;
    EXPECT_TRUE(read_text(a / name) == read_text(b / name)) << name << " differs";
  }
  const auto ra = read_json(a / "report.json"), rb = read_json(b / "report.json");
  EXPECT_EQ(rb["status"], "success");
  ASSERT_EQ(ra["increments"].size(), rb["increments"].size());
  for (std::size_t i = 0; i < ra["increments"].size(); ++i) {
    for (const char* key : {"increment", "stage", "split_depth", "accepted", "newton_iterations", "pcg_iterations",
                            "linear_tolerances", "linear_norms", "residuals", "min_scaled_jacobian", "inverted_cells",
                            "max_projection_distance", "max_projection_distance_relative", "max_normal_slip",
                            "max_normal_slip_relative"}) {
      EXPECT_EQ(ra["increments"][i][key], rb["increments"][i][key]) << "increment record " << i << ", " << key;
    }
  }
  for (const char* key : {"newton_iterations", "pcg_iterations", "min_scaled_jacobian", "sliding_nodes", "length_scale",
                          "max_normal_slip", "max_normal_slip_relative", "max_projection_distance",
                          "max_projection_distance_relative", "final_projection_distance",
                          "final_projection_distance_relative", "max_periodic_mismatch",
                          "max_periodic_mismatch_relative", "max_sliding_projection_distance",
                          "periodic_max_mismatch"}) {
    ASSERT_TRUE(ra.contains(key)) << key;
    EXPECT_EQ(ra[key], rb[key]) << key;
  }
  EXPECT_FALSE(std::filesystem::exists(b / io::kCheckpointName)) << "the checkpoint outlived the run";
  for (const auto& entry : std::filesystem::directory_iterator(b)) {
    EXPECT_THAT(entry.path().filename().string(), ::testing::Not(::testing::HasSubstr(".tmp-")));
  }
}

}  // namespace hotmesh::test
