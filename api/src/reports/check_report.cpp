// hotmesh api: the report of `hotmesh check` as text, JSON and JUnit XML (see check_report.hpp).
#include "hotmesh/api/check_report.hpp"
#include "hotmesh/api/mesh_summary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

namespace hotmesh::api {

namespace {

std::string point_text(const geometry::Vec3& p) { return fmt::format("({:.9g}, {:.9g}, {:.9g})", p.x, p.y, p.z); }

std::string verdict(const DistanceCheck& p, double tolerance) {
  return fmt::format("max distance {:.3e} at node {} {} {} the tolerance {:.3e}; mean {:.3e} over {} nodes",
                     p.max_distance, p.worst_node, point_text(p.worst_point),
                     p.max_distance <= tolerance ? "within" : "ABOVE", tolerance, p.mean_distance, p.nodes);
}

/// The faces' two-sided distance, and how it compares with the wall tolerance if there is one.
std::string wall_verdict(const DistanceCheck& p, const std::optional<double>& wall_tolerance) {
  if (!p.wall.measured()) return "faces: " + wall_text(p.wall);
  const std::string against = wall_tolerance ? fmt::format(", {} the wall tolerance {:.3e}",
                                                           p.wall.passed ? "within" : "ABOVE", *wall_tolerance)
                                             : std::string(" (no --wall-tol: reported only)");
  return "faces: " + wall_text(p.wall) + against;
}

/// Text escaped for XML attributes and content.
std::string xml(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // Control characters other than tab and line ends are not allowed in XML 1.0.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') {
          out += '?';
        } else {
          out += c;
        }
    }
  }
  return out;
}

/// The verdicts of the parts of a patch, one line each, indented.
std::string part_lines(const PatchCheck& p, const CheckResult& result, const std::string& indent) {
  std::string text;
  for (std::size_t k = 0; k < p.parts.size(); ++k) {
    const DistanceCheck& part = p.parts[k];
    text += fmt::format("{}part {} {}: {}\n{}    {}\n{}    against {}\n", indent, k + 1, part.passed ? "pass" : "FAIL",
                        verdict(part, result.tolerance), indent, wall_verdict(part, result.wall_tolerance), indent,
                        part.reference);
  }
  return text;
}

nlohmann::json wall_check_json(const DistanceCheck& p) {
  nlohmann::json wall = wall_json(p.wall);
  wall["passed"] = p.wall.passed;
  return wall;
}

nlohmann::json distances_json(const DistanceCheck& p) {
  return {{"reference", p.reference},
          {"nodes", p.nodes},
          {"max_distance", p.max_distance},
          {"mean_distance", p.mean_distance},
          {"worst_node", {{"id", p.worst_node}, {"point", {p.worst_point.x, p.worst_point.y, p.worst_point.z}}}},
          {"wall", wall_check_json(p)},
          {"passed", p.passed}};
}

double total_seconds(const CheckResult& result) {
  double seconds = 0.0;
  for (const PatchCheck& p : result.patches) seconds += p.seconds;
  return seconds;
}

std::size_t failures(const CheckResult& result) {
  return static_cast<std::size_t>(
      std::count_if(result.patches.begin(), result.patches.end(), [](const PatchCheck& p) { return !p.passed; }));
}

}  // namespace

bool CheckResult::passed() const { return failures(*this) == 0; }

std::string check_text(const CheckResult& result) {
  std::string text = fmt::format("hotmesh check: {}{}{}, tolerance {:.3e} {}{}\n", result.mesh,
                                 result.case_file.empty() ? "" : " against the case " + result.case_file,
                                 result.cad.empty() ? "" : " and " + result.cad, result.tolerance, result.unit,
                                 result.wall_tolerance ? fmt::format(", wall tolerance {:.3e}", *result.wall_tolerance)
                                                       : std::string());
  for (const PatchCheck& p : result.patches) {
    text += fmt::format("  {} {}: {}\n      {}\n      against {}\n", p.passed ? "pass" : "FAIL", p.patch,
                        verdict(p, result.tolerance), wall_verdict(p, result.wall_tolerance), p.reference);
    text += part_lines(p, result, "      ");
  }
  text += fmt::format("{} of {} patches within the tolerance\n", result.patches.size() - failures(result),
                      result.patches.size());
  if (!result.quality.is_null()) text += "cells of the mesh:\n  " + quality_text(result.quality, "  ");
  return text;
}

std::string check_json(const CheckResult& result) {
  nlohmann::json patches = nlohmann::json::array();
  const auto optional_text = [](const std::string& text) {
    return text.empty() ? nlohmann::json(nullptr) : nlohmann::json(text);
  };
  for (const PatchCheck& p : result.patches) {
    nlohmann::json patch = {{"patch", p.patch}};
    patch.update(distances_json(p));
    patch["seconds"] = p.seconds;
    if (!p.parts.empty()) {
      patch["parts"] = nlohmann::json::array();
      for (const DistanceCheck& part : p.parts) patch["parts"].push_back(distances_json(part));
    }
    patches.push_back(std::move(patch));
  }
  const nlohmann::json json = {{"mesh", result.mesh},
                               {"case", optional_text(result.case_file)},
                               {"cad", optional_text(result.cad)},
                               {"tolerance", result.tolerance},
                               {"wall_tolerance", result.wall_tolerance ? nlohmann::json(*result.wall_tolerance)
                                                                        : nlohmann::json(nullptr)},
                               {"unit", result.unit},
                               {"passed", result.passed()},
                               {"patches", patches},
                               {"quality", result.quality}};
  return json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string check_junit(const CheckResult& result) {
  const std::string suite = "hotmesh check " + std::filesystem::path(result.mesh).filename().string();
  const std::string classname = "hotmesh.check." + std::filesystem::path(result.mesh).stem().string();
  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  x += fmt::format("<testsuites name=\"hotmesh check\" tests=\"{}\" failures=\"{}\" errors=\"0\" time=\"{:.3f}\">\n",
                   result.patches.size(), failures(result), total_seconds(result));
  x += fmt::format("  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"0\" skipped=\"0\" time=\"{:.3f}\">\n",
                   xml(suite), result.patches.size(), failures(result), total_seconds(result));
  x += "    <properties>\n";
  x += fmt::format("      <property name=\"mesh\" value=\"{}\"/>\n", xml(result.mesh));
  if (!result.case_file.empty()) {
    x += fmt::format("      <property name=\"case\" value=\"{}\"/>\n", xml(result.case_file));
  }
  if (!result.cad.empty()) x += fmt::format("      <property name=\"cad\" value=\"{}\"/>\n", xml(result.cad));
  x += fmt::format("      <property name=\"tolerance\" value=\"{:.6e}\"/>\n", result.tolerance);
  if (result.wall_tolerance) {
    x += fmt::format("      <property name=\"wall_tolerance\" value=\"{:.6e}\"/>\n", *result.wall_tolerance);
  }
  x += fmt::format("      <property name=\"unit\" value=\"{}\"/>\n", xml(result.unit));
  x += "    </properties>\n";
  for (const PatchCheck& p : result.patches) {
    x += fmt::format("    <testcase classname=\"{}\" name=\"{}\" time=\"{:.3f}\">\n", xml(classname), xml(p.patch), p.seconds);
    const std::string details = xml(verdict(p, result.tolerance) + "; " + wall_verdict(p, result.wall_tolerance) +
                                    "; against " + p.reference + "\n" + part_lines(p, result, ""));
    if (!(p.max_distance <= result.tolerance)) {
      x += fmt::format("      <failure type=\"tolerance\" message=\"node {} is {:.3e} from the reference shape, above the "
                       "tolerance {:.3e}\">{}</failure>\n",
                       p.worst_node, p.max_distance, result.tolerance, details);
    } else if (!p.passed) {
      const WallSide& w = p.wall.worst_side();
      x += fmt::format("      <failure type=\"wall tolerance\" message=\"the faces are {:.3e} from the reference shape at {} "
                       "({}, {}), above the wall tolerance {:.3e}\">{}</failure>\n",
                       p.wall.hausdorff, point_text(w.point), p.wall.worst, xml(mesh_location(w)),
                       result.wall_tolerance.value_or(0.0), details);
    }
    x += fmt::format("      <system-out>{}</system-out>\n", details);
    x += "    </testcase>\n";
  }
  x += "  </testsuite>\n</testsuites>\n";
  return x;
}

std::string check_junit_error(const std::string& subject, const std::string& type, const std::string& message) {
  const std::string suite = "hotmesh check " + std::filesystem::path(subject).filename().string();
  const std::string classname = "hotmesh.check." + std::filesystem::path(subject).stem().string();
  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  x += "<testsuites name=\"hotmesh check\" tests=\"1\" failures=\"0\" errors=\"1\" time=\"0.000\">\n";
  x += fmt::format("  <testsuite name=\"{}\" tests=\"1\" failures=\"0\" errors=\"1\" skipped=\"0\" time=\"0.000\">\n",
                   xml(suite));
  x += fmt::format("    <testcase classname=\"{}\" name=\"input\" time=\"0.000\">\n", xml(classname));
  x += fmt::format("      <error type=\"{}\" message=\"{}\">{}</error>\n", xml(type), xml(message), xml(message));
  x += "    </testcase>\n  </testsuite>\n</testsuites>\n";
  return x;
}

}  // namespace hotmesh::api
