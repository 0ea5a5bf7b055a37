// hotmesh tests: the 2D channel with a forward-facing step of tests/data/gmsh/channel_step.geo,
// made as a user makes it: gmsh draws it with its OpenCASCADE kernel, writes the CAD to STEP
// and meshes it (a node on every CAD vertex), in a temporary folder; the lower wall's CAD edges
// are found in `hotmesh cad --json`'s list, and the FEM table of the lower wall is written
// here. The wall's exact shape (lines and the fillet's circle, StepWall below) is what the
// tests measure against.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "deform_cases.hpp"
#include "hotmesh/core/vec2.hpp"

namespace hotmesh::test {

/// The lower wall, mm: the floor y = 0 to the step's foot at x = 10, the step's face up to
/// y = 3, the fillet (radius 2 about (12, 3)) to (12, 5), the top y = 5 to x = 25.
struct StepWall {
  static constexpr double kRadius = 2.0;
  static geometry::Vec2 centre() { return {12.0, 3.0}; }
  static std::vector<geometry::Vec2> vertices() { return {{0, 0}, {10, 0}, {10, 3}, {12, 5}, {25, 5}}; }

  /// The point at arc length s along the wall from (0, 0).
  static geometry::Vec2 at(double s) {
    if (s <= 10.0) return {s, 0.0};
    if (s <= 13.0) return {10.0, s - 10.0};
    const double arc = 0.5 * std::numbers::pi * kRadius;
    if (s <= 13.0 + arc) {
      const double a = std::numbers::pi - (s - 13.0) / kRadius;  // from 180 degrees down to 90
      return centre() + kRadius * geometry::Vec2{std::cos(a), std::sin(a)};
    }
    return {12.0 + (s - 13.0 - arc), 5.0};
  }

  /// Distance of p from the fillet's circle moved by `shift`.
  static double off_fillet(const geometry::Vec2& p, const geometry::Vec2& shift = {0, 0}) {
    return std::abs(distance(p, centre() + shift) - kRadius);
  }
  /// Distance of p from the whole wall moved by `shift`: its lines and the fillet's arc.
  static double off_wall(const geometry::Vec2& p, const geometry::Vec2& shift = {0, 0}) {
    const geometry::Vec2 q = p - shift;
    const auto segment = [&](geometry::Vec2 a, geometry::Vec2 b) {
      const geometry::Vec2 d = b - a;
      const double t = std::clamp(dot(q - a, d) / dot(d, d), 0.0, 1.0);
      return distance(q, a + t * d);
    };
    double best = std::min({segment({0, 0}, {10, 0}), segment({10, 0}, {10, 3}), segment({12, 5}, {25, 5})});
    const geometry::Vec2 r = q - centre();
    if (r.x <= 0.0 && r.y >= 0.0) best = std::min(best, std::abs(norm(r) - kRadius));
    return best;
  }
};

/// channel.msh and channel.step made by gmsh in a temporary folder, with the lower wall's edge
/// ids as `hotmesh cad` lists them.
class ChannelStep {
 public:
  ChannelStep() {
    const std::string geo = shell_quote(data_path("gmsh/channel_step.geo").string());
    const auto meshed = run_command("gmsh -2 -nt 1 " + geo + " -format msh41 -o " + shell_quote(path("channel.msh")));
    EXPECT_EQ(meshed.exit_code, 0) << "gmsh is a required test dependency (scripts/install-deps.sh):\n" << meshed.output;
    const auto cad = run_command("gmsh -0 " + geo + " -o " + shell_quote(path("channel.step")));
    EXPECT_EQ(cad.exit_code, 0) << cad.output;
    wall_edges_ = edges_along_wall("channel.step");
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  const std::filesystem::path& dir() const { return dir_.path(); }
  /// The wall's edges, in the order of `hotmesh cad`'s list.
  const std::vector<int>& wall_edges() const { return wall_edges_; }
  std::string wall_edge_list() const { return fmt::format("{}", fmt::join(wall_edges_, ", ")); }

  /// The CAD with the fillet and its ends 0.5 out of the plane z = 0 (edges only, no face).
  void write_lifted_cad(const std::string& name) const {
    const std::string geo = shell_quote(data_path("gmsh/channel_step.geo").string());
    const auto cad = run_command("gmsh -0 -setnumber lift 0.5 " + geo + " -o " + shell_quote(path(name)));
    EXPECT_EQ(cad.exit_code, 0) << cad.output;
  }

  /// The edges of a CAD file whose ends are two of the wall's vertices (the others reach the top
  /// y = 10 or run up the outlet x = 25 from the wall's end), from `hotmesh cad --json`.
  std::vector<int> edges_along_wall(const std::string& cad_name) const {
    const auto listing = hotmesh("-q cad --json --unit mm " + shell_quote(path(cad_name)));
    EXPECT_EQ(listing.exit_code, 0) << listing.output;
    const auto json = nlohmann::json::parse(listing.output.substr(listing.output.find('{')));
    const auto ends_on_wall = [](const nlohmann::json& p) {
      const std::vector<geometry::Vec2> v = StepWall::vertices();
      return std::any_of(v.begin(), v.end(), [&](const geometry::Vec2& q) {
        return std::hypot(p[0].get<double>() - q.x, p[1].get<double>() - q.y) < 1e-9;
      });
    };
    std::vector<int> ids;
    for (const auto& edge : json["edges"]) {
      const bool outlet = std::abs(edge["start"][0].get<double>() - 25.0) < 1e-9 &&
                          std::abs(edge["end"][0].get<double>() - 25.0) < 1e-9;
      if (ends_on_wall(edge["start"]) && ends_on_wall(edge["end"]) && !outlet) ids.push_back(edge["id"].get<int>());
    }
    return ids;
  }

  /// An FEM table of the lower wall (x,y,dx,dy), all nodes moved by `shift`: as an FEM mesh of
  /// the part has them, a node on each CAD vertex and nodes evenly along each edge, at most
  /// 0.8 mm apart (4 on the fillet's quarter circle: the wall turns by 22.5 degrees at each).
  void write_table(const std::string& name, geometry::Vec2 shift) const {
    const double arc = 0.5 * std::numbers::pi * StepWall::kRadius;
    std::string table = "x,y,dx,dy\n";
    double start = 0.0;
    for (const double length : {10.0, 3.0, arc, 13.0}) {
      const int n = static_cast<int>(std::ceil(length / 0.8));
      for (int k = 0; k < n; ++k) {
        const geometry::Vec2 p = StepWall::at(start + length * k / n);
        table += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}\n", p.x, p.y, shift.x, shift.y);
      }
      start += length;
    }
    table += fmt::format("25,5,{:.17g},{:.17g}\n", shift.x, shift.y);
    write_text(dir_ / name, table);
  }

  /// case.yaml: the lower wall `bottom` as `bottom` says (its map, e.g. "{role: sliding, ...}"),
  /// the top fixed, inlet and outlet slipping.
  std::string write_case(const std::string& bottom, const std::string& top = "cad: channel.step\n") const {
    write_text(dir_ / "case.yaml", fmt::format("mesh: channel.msh\n{}length_unit: mm\npatches:\n  bottom: {}\n"
                                               "  top: {{role: fixed}}\n  inlet: {{role: slip}}\n"
                                               "  outlet: {{role: slip}}\n",
                                               top, bottom));
    return shell_quote(path("case.yaml"));
  }

 private:
  TempDir dir_;
  std::vector<int> wall_edges_;
};

}  // namespace hotmesh::test
