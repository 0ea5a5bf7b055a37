// hotmesh fuzz: FEM deflection tables (CSV), as case files, `hotmesh curve`, `check` and the
// service read them.
#include "fuzz_support.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/deflection_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr std::string_view kSource = "fuzz.csv";
  try {
    hotmesh::io::parse_deflection_csv(hotmesh::fuzz::as_text(data, size), kSource);
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), kSource);
  }
  return 0;
}
