// hotmesh fuzz: CalculiX results files (.frd, ASCII and binary), as `hotmesh fem` and a case's
// `calculix: {frd: ...}` read them: parse_frd, then the table of the coupled_disc sample's
// surface DISC_BASE from the last DISP block (the check that the results belong to the deck,
// the displacements of the set's nodes, their temperatures).
#include "fuzz_support.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/calculix.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr std::string_view kSource = "fuzz.frd";
  static const hotmesh::io::InpDeck deck =
      hotmesh::io::read_inp(hotmesh::fuzz::source_file("samples/coupled_disc/disc_1.inp"));
  try {
    const hotmesh::io::FrdResults results = hotmesh::io::parse_frd(hotmesh::fuzz::as_text(data, size), kSource);
    hotmesh::io::calculix_table(results, deck, {std::string(kSource), deck.file, "DISC_BASE", {}});
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), kSource);
  }
  return 0;
}
