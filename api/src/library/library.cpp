// hotmesh api: the public library's free functions: version, verbosity and check (hotmesh/hotmesh.hpp).
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include <mutex>

#include "hotmesh/api/case_check.hpp"
#include "library_state.hpp"

namespace hotmesh {
namespace {

std::once_flag g_logger_installed;

void install_logger() {
  std::call_once(g_logger_installed, [] {
    auto logger = spdlog::stderr_logger_mt("hotmesh");
    logger->set_pattern("hotmesh: %^%l%$: %v");
    logger->set_level(spdlog::level::warn);
    spdlog::set_default_logger(std::move(logger));
  });
}

}  // namespace

void start_library_logging() { install_logger(); }

std::string version() { return HOTMESH_VERSION; }

void set_verbosity(Verbosity verbosity) {
  install_logger();
  static constexpr spdlog::level::level_enum kLevels[] = {spdlog::level::err, spdlog::level::warn, spdlog::level::info,
                                                          spdlog::level::debug};
  spdlog::set_level(kLevels[static_cast<int>(verbosity)]);
}

CheckResult check(const std::filesystem::path& mesh, const std::filesystem::path& case_file, double tolerance,
                  double wall_tolerance) {
  install_logger();
  if (!(tolerance >= 0.0) || !(wall_tolerance >= 0.0)) {
    throw InputError(fmt::format("check: tolerance {} and wall_tolerance {} must be numbers >= 0 (0: the default)",
                                 tolerance, wall_tolerance));
  }
  api::CaseCheckOptions options;
  options.case_file = case_file;
  options.mesh = mesh;
  options.tolerance = tolerance;
  if (wall_tolerance > 0.0) options.wall_tolerance = wall_tolerance;
  std::vector<std::filesystem::path> inputs{case_file};
  bool inputs_known = false;
  const api::CheckResult checked = api::check_with_case(options, inputs, inputs_known);
  CheckResult result;
  result.passed = checked.passed();
  result.tolerance = checked.tolerance;
  for (const api::PatchCheck& p : checked.patches) {
    result.patches.push_back({p.patch, p.nodes, p.max_distance, p.mean_distance, p.worst_node,
                              p.wall.measured() ? p.wall.hausdorff : -1.0, p.passed});
  }
  result.text = api::check_text(checked);
  result.json = api::check_json(checked);
  return result;
}

}  // namespace hotmesh
