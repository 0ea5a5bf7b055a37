#include "cli/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace hotmesh::app {

void configure_logging(int verbosity) {
  auto logger = spdlog::stderr_color_mt("hotmesh");
  logger->set_pattern("%^%l%$ %v");
  spdlog::level::level_enum level = spdlog::level::info;
  if (verbosity < 0) level = spdlog::level::warn;
  if (verbosity == 1) level = spdlog::level::debug;
  if (verbosity >= 2) level = spdlog::level::trace;
  logger->set_level(level);
  spdlog::set_default_logger(logger);
}

void quiet_other_ranks(int rank) {
  auto logger = spdlog::default_logger();
  logger->set_pattern(fmt::format("[rank {}] %^%l%$ %v", rank));
  logger->set_level(spdlog::level::err);
}

}  // namespace hotmesh::app
