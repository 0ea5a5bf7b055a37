// hotmesh samples: what every 2D sample generator does around its own geometry — the output
// folder from the command line, its error report, and the deflection table of a lower wall.
#pragma once

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace hotmesh::samples {

/// The main of generator `name`: `write(folder)` writes the sample into argv[1] (default: the
/// current folder, created if missing). An exception is reported as "name: what", exit code 1.
template <class Write>
int run_generator(const char* name, int argc, char** argv, Write write) {
  try {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    std::filesystem::create_directories(folder);
    write(folder);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 1;
  }
}

/// The FEM table of a lower wall y = 0 that deflects along y: `header` (comment lines), then a
/// row x, 0, 0, deflection(x) for each of `xs` in increasing order.
template <class Deflection>
std::string lower_wall_table(const std::string& header, std::vector<double> xs, Deflection deflection) {
  std::sort(xs.begin(), xs.end());
  std::string csv = header + "x,y,dx,dy\n";
  for (const double x : xs) csv += fmt::format("{},0,0,{}\n", x, deflection(x));
  return csv;
}

}  // namespace hotmesh::samples
