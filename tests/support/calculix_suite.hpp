// hotmesh tests: CalculiX's own test suite as Debian's calculix-ccx-test installs it
// (/usr/share/doc/calculix-ccx-test/examples/test: decks and the reference .frd results of
// ccx 2.11, many gzipped), read as they are, gzipped or not.
#pragma once

#include <zlib.h>

#include <filesystem>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

#include "test_support.hpp"

namespace hotmesh::test {

inline const std::filesystem::path& ccx_suite() {
  static const std::filesystem::path folder = "/usr/share/doc/calculix-ccx-test/examples/test";
  return folder;
}

inline bool have_ccx_suite() { return std::filesystem::is_directory(ccx_suite()); }

/// The text of a gzipped file, inflated piece by piece.
inline std::string gunzip_file(const std::filesystem::path& path) {
  const std::string data = read_text(path);
  z_stream z{};
  if (inflateInit2(&z, 15 + 32) != Z_OK) throw std::runtime_error("inflateInit2");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  std::string out;
  char buffer[1 << 16];
  int status = Z_OK;
  while (status == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(buffer);
    z.avail_out = sizeof buffer;
    status = inflate(&z, Z_NO_FLUSH);
    out.append(buffer, sizeof buffer - z.avail_out);
  }
  inflateEnd(&z);
  if (status != Z_STREAM_END) throw std::runtime_error(path.string() + ": not a whole gzip stream");
  return out;
}

/// The suite's file `name` (e.g. "shell1.inp"), or `name`.gz inflated; none if neither is there.
inline std::optional<std::string> ccx_suite_text(const std::string& name) {
  const std::filesystem::path plain = ccx_suite() / name;
  if (std::filesystem::exists(plain)) return read_text(plain);
  const std::filesystem::path gz = ccx_suite() / (name + ".gz");
  if (std::filesystem::exists(gz)) return gunzip_file(gz);
  return std::nullopt;
}

/// The suite's deck `job`.inp written, inflated, into `folder`; its path.
inline std::filesystem::path ccx_suite_deck(const std::filesystem::path& folder, const std::string& job) {
  const std::optional<std::string> text = ccx_suite_text(job + ".inp");
  if (!text) throw std::runtime_error("the CalculiX test suite has no deck " + job + ".inp");
  write_text(folder / (job + ".inp"), *text);
  return folder / (job + ".inp");
}

/// The jobs of the suite's reference results: <job>.frd.ref(.gz), and twobeam.frd.gz, the
/// global model of submodeltwobeam (its deck is not in the suite).
inline std::set<std::string> ccx_suite_results() {
  std::set<std::string> jobs;
  for (const auto& entry : std::filesystem::directory_iterator(ccx_suite())) {
    std::string name = entry.path().filename().string();
    for (const char* suffix : {".frd.ref.gz", ".frd.ref", ".frd.gz"}) {
      if (name.ends_with(suffix)) {
        jobs.insert(name.substr(0, name.size() - std::string(suffix).size()));
        break;
      }
    }
  }
  return jobs;
}

/// The text of a job's reference results.
inline std::string ccx_suite_results_text(const std::string& job) {
  for (const std::string& name : {job + ".frd.ref", job + ".frd"}) {
    if (const auto text = ccx_suite_text(name)) return *text;
  }
  throw std::runtime_error("the CalculiX test suite has no results of " + job);
}

}  // namespace hotmesh::test
