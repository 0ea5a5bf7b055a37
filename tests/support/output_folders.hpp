// hotmesh tests: what `hotmesh deform` leaves in its output folder, read and compared.
// Header-only: the test programs that use it link hotmesh::io and GoogleTest's gmock.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "hotmesh/io/checkpoint_file.hpp"
#include "test_support.hpp"

namespace hotmesh::test {

inline nlohmann::json read_json(const std::filesystem::path& p) { return nlohmann::json::parse(read_text(p)); }

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
                            "linear_tolerances", "linear_norms", "residuals", "min_scaled_jacobian",
                            "max_projection_distance"}) {
      EXPECT_EQ(ra["increments"][i][key], rb["increments"][i][key]) << "increment record " << i << ", " << key;
    }
  }
  for (const char* key : {"newton_iterations", "pcg_iterations", "min_scaled_jacobian", "max_normal_slip",
                          "max_sliding_projection_distance", "sliding_nodes"}) {
    EXPECT_EQ(ra[key], rb[key]) << key;
  }
  EXPECT_FALSE(std::filesystem::exists(b / io::kCheckpointName)) << "the checkpoint outlived the run";
  for (const auto& entry : std::filesystem::directory_iterator(b)) {
    EXPECT_THAT(entry.path().filename().string(), ::testing::Not(::testing::HasSubstr(".tmp-")));
  }
}

}  // namespace hotmesh::test
