#include "test_support.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "hotmesh/deform/structured_mesh.hpp"

namespace hotmesh::test {

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path() /
          ("hotmesh-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::filesystem::path data_path(std::string_view name) { return std::filesystem::path(HOTMESH_TEST_DATA) / name; }

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const std::filesystem::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

deform::Mesh unit_square(int nx, int ny) {
  const auto xs = deform::uniform_line(0.0, 1.0, nx);
  const auto ys = deform::uniform_line(0.0, 1.0, ny);
  return deform::structured_quads(xs, ys);
}

deform::Mesh unit_cube(int n) {
  const auto line = deform::uniform_line(0.0, 1.0, n);
  return deform::structured_hexes(line, line, line);
}

}  // namespace hotmesh::test
