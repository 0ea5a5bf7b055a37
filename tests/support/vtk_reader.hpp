// hotmesh tests: what VTK's own XML readers (the ones ParaView uses) find in a .vtu, .vtp or
// every file of a .pvd, through tests/io/check_vtu.py: our VTK files checked against an
// independent implementation.
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace hotmesh::test {

/// The file as VTK reads it: {points, cells, cell_types, point_data, cell_data} (or {error});
/// for a .pvd, {steps: [... with time and file]}.
inline nlohmann::json read_with_vtk(const std::filesystem::path& file) {
  const std::string command = "/usr/bin/python3 " HOTMESH_SOURCE_DIR "/tests/io/check_vtu.py '" + file.string() + "'";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) throw std::runtime_error("cannot run " + command);
  std::string out;
  char buffer[65536];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe.get())) > 0;) out.append(buffer, n);
  return nlohmann::json::parse(out);
}

}  // namespace hotmesh::test
