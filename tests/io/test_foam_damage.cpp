// Tests that a damaged polyMesh folder cannot make the reader allocate what its counts claim
// (issue 46): each count and label is checked against what the other files can need before
// it sizes anything, and a gzipped file is decompressed no further than its count can need.
// The inputs are the issue's, written on the 2x1x1 block of foam_fixtures.hpp. Every
// operator new of this test program records the largest size asked for while armed
// (allocation_watch.hpp; skipped under AddressSanitizer, whose own allocator refuses sizes
// above its limit instead).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <string>

#include "allocation_watch.hpp"
#include "foam_fixtures.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/foam.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "read_error.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using test::foam::block_2x1x1;
using test::foam::Layout;
using test::foam::write_poly_mesh;
using ::testing::HasSubstr;

constexpr std::size_t kMiB = std::size_t{1} << 20;

/// The message read_mesh(folder) is refused with, and the largest allocation it asked for
/// (0 where operator new is the sanitizer's).
struct Refusal {
  std::string message = "no error";
  std::size_t largest = 0;
};

Refusal refusal(const std::filesystem::path& folder) {
  Refusal r;
  ::test::allocations::arm();
  try {
    read_mesh(folder);
  } catch (const InputError& e) {
    r.message = e.what();
  }
  ::test::allocations::armed = false;
  r.largest = ::test::allocations::largest;
  return r;
}

/// The block with `file` replaced by `text` after its header.
std::filesystem::path block_with(const std::filesystem::path& folder, const std::string& file, const std::string& cls,
                                 const std::string& text) {
  write_poly_mesh(folder, block_2x1x1());
  test::write_text(folder / file, test::foam::foam_header(Layout{}, cls, file) + text);
  return folder;
}

// One owner label of 2^31 - 2 made 2^31 - 1 cells: 17 GB for the faces of each cell.
TEST(FoamReaderCounts, AnOwnerLabelBeyondTheCellsTheFacesMakeIsRefusedBeforeSizingAnything) {
  test::TempDir dir;
  auto m = block_2x1x1();
  m.owner[3] = 2147483646;
  write_poly_mesh(dir / "p", m);
  const Refusal r = refusal(dir / "p");
  EXPECT_THAT(r.message, HasSubstr((dir / "p" / "owner").string()));
  EXPECT_THAT(r.message, HasSubstr("face 3 has owner cell 2147483646, but 11 faces (1 of them internal) make at most "
                                   "3 cells (a cell has at least 4 faces)"));
  EXPECT_LT(r.largest, kMiB);
}

// `2147483647{0}`: 17 GB of owner labels for a file of a few bytes.
TEST(FoamReaderCounts, AUniformOwnerListIsBoundedByTheFaces) {
  test::TempDir dir;
  const Refusal r = refusal(block_with(dir / "p", "owner", "labelList", "2147483647{0}\n"));
  EXPECT_THAT(r.message, HasSubstr((dir / "p" / "owner").string() + ":"));
  EXPECT_THAT(r.message, HasSubstr("the list of owner cells has 2147483647 entries, but there are 11 faces (the "
                                   "faces file), one owner each"));
  EXPECT_LT(r.largest, kMiB);
}

// `2147483647{(0 0 0)}`: 51 GB of points.
TEST(FoamReaderCounts, AUniformPointsListIsBoundedByThePointsTheFacesReferTo) {
  test::TempDir dir;
  const Refusal r = refusal(block_with(dir / "p", "points", "vectorField", "2147483647{(0 0 0)}\n"));
  EXPECT_THAT(r.message, HasSubstr((dir / "p" / "points").string() + ":"));
  EXPECT_THAT(r.message, HasSubstr("the list of points has 2147483647 entries, but the faces refer to at most 44 "
                                   "points"));
  EXPECT_LT(r.largest, kMiB);
}

// A face, or the offsets or points of a faceCompactList, as a uniform list: a face's points
// are different points, so such a list is refused before its count allocates anything.
TEST(FoamReaderCounts, UniformFaceListsAreRefusedBeforeTheyAllocate) {
  test::TempDir dir;
  const std::string face_list = "2\n(\n4(0 1 4 3)\n2147483647{0}\n)\n";
  Refusal r = refusal(block_with(dir / "list", "faces", "faceList", face_list));
  EXPECT_THAT(r.message, HasSubstr("the list of points of face 1 is 2147483647 copies of one value (N{value}), but "
                                   "a face's points are different points"));
  EXPECT_LT(r.largest, kMiB);
  r = refusal(block_with(dir / "offsets", "faces", "faceCompactList", "2147483647{0}\n0()\n"));
  EXPECT_THAT(r.message, HasSubstr("the list of face offsets is 2147483647 copies of one value"));
  EXPECT_LT(r.largest, kMiB);
  r = refusal(block_with(dir / "points", "faces", "faceCompactList", "2(0 2147483647)\n2147483647{0}\n"));
  EXPECT_THAT(r.message, HasSubstr("face points is 2147483647 copies of one value (N{value}), but a face's points "
                                   "are different points"));
  EXPECT_LT(r.largest, kMiB);
  r = refusal(block_with(dir / "count", "faces", "faceCompactList", "2(0 3)\n2147483647{0}\n"));
  EXPECT_THAT(r.message, HasSubstr("the list of face points has 2147483647 entries, but the last face offset is 3"));
}

// Every bit from 16 to 31 flipped in turn in every label of the binary owner and neighbour
// files: cell labels up to 2^31 made up to 4 GB of cells. Each is refused, naming the file,
// before any label sizes anything.
TEST(FoamReaderCounts, FlippedBitsInBinaryOwnerAndNeighbourLabelsAreRefused) {
  test::TempDir dir;
  write_poly_mesh(dir / "whole", block_2x1x1(), {.binary = true});
  int refused = 0;
  for (const std::string file : {"owner", "neighbour"}) {
    const std::string text = test::read_text(dir / "whole" / file);
    const std::size_t data = text.find("\n(") + 2;
    const std::size_t labels = file == "owner" ? 11 : 1;
    for (std::size_t label = 0; label < labels; ++label) {
      for (int bit = 16; bit < 32; ++bit) {
        const auto folder = dir / fmt::format("{}-{}-{}", file, label, bit);
        std::filesystem::copy(dir / "whole", folder);
        std::string flipped = text;
        flipped[data + 4 * label + static_cast<std::size_t>(bit / 8)] ^= static_cast<char>(1 << (bit % 8));
        test::write_text(folder / file, flipped);
        const Refusal r = refusal(folder);
        EXPECT_THAT(r.message, HasSubstr((folder / file).string())) << file << " label " << label << " bit " << bit;
        EXPECT_LT(r.largest, kMiB) << file << " label " << label << " bit " << bit;
        refused += r.message != "no error";
      }
    }
  }
  EXPECT_EQ(refused, 12 * 16);
}

/// `text` gzipped, with `blanks` blanks after it, compressed as they come (a gzip bomb when
/// they are many: deflate packs a GiB of them into 1 MB).
std::string gzipped_with_blanks(const std::string& text, std::size_t blanks) {
  z_stream z{};
  deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY);
  std::string out;
  const std::string chunk(kMiB, ' ');
  std::string buffer(2 * kMiB, '\0');
  const auto feed = [&](const std::string& in, int flush) {
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
    z.avail_in = static_cast<uInt>(in.size());
    do {
      z.next_out = reinterpret_cast<Bytef*>(buffer.data());
      z.avail_out = static_cast<uInt>(buffer.size());
      deflate(&z, flush);
      out.append(buffer.data(), buffer.size() - z.avail_out);
    } while (z.avail_out == 0);
  };
  feed(text, Z_NO_FLUSH);
  for (std::size_t done = 0; done < blanks; done += chunk.size()) feed(chunk, Z_NO_FLUSH);
  feed("", Z_FINISH);
  deflateEnd(&z);
  return out;
}

// The 5.2 MB points.gz expanded to 5 GiB: 12 points, then blanks. Here 64 MiB of
// them (65 KB of gzip): refused when the content passes what 12 points can need.
TEST(FoamReaderCounts, AGzipBombIsDecompressedNoFurtherThanItsCountCanNeed) {
  test::TempDir dir;
  write_poly_mesh(dir / "p", block_2x1x1());
  const std::string points = test::read_text(dir / "p" / "points");
  std::filesystem::remove(dir / "p" / "points");
  test::write_text(dir / "p" / "points.gz", gzipped_with_blanks(points, 64 * kMiB));
  const Refusal r = refusal(dir / "p");
  EXPECT_THAT(r.message, HasSubstr((dir / "p" / "points.gz").string() + ": the gzip data expands to more than"));
  EXPECT_THAT(r.message, HasSubstr("more than what 12 points can need"));
  EXPECT_LT(r.largest, kMiB);
}

// A gzipped file whose header and count the reader takes from its first 64 KiB, then the
// rest within the bound: a cube of 20^3 hexahedra, every file gzipped, ASCII and binary.
TEST(FoamReaderCounts, GzippedFilesLargerThanTheirHeadAreReadWhole) {
  test::TempDir dir;
  const mesh::Mesh cube = test::unit_cube(20);
  for (const bool binary : {false, true}) {
    const auto folder = dir / (binary ? "binary" : "ascii") / "polyMesh";
    write_foam(folder, cube, cube.points, {.binary = binary});
    for (const char* name : {"points", "faces", "owner", "neighbour", "boundary"}) {
      test::write_text(folder / (std::string(name) + ".gz"), test::foam::gzipped(test::read_text(folder / name)));
      std::filesystem::remove(folder / name);
    }
    EXPECT_GT(std::filesystem::file_size(folder / "faces.gz"), 64u << 10);  // larger than the head compressed, too
    const LoadedMesh loaded = read_mesh(folder);
    EXPECT_EQ(loaded.mesh.cell_count(), cube.cell_count()) << (binary ? "binary" : "ascii");
    EXPECT_EQ(loaded.mesh.points, cube.points);
  }
}

// OpenFOAM 1.x wrote one neighbour per face, -1 for the boundary faces (Debian's tutorials
// still ship such meshes); OpenFOAM reads the neighbours before the first -1.
TEST(FoamReaderCounts, ANeighbourListPaddedWithMinusOneIsReadAsOpenFoamReadsIt) {
  test::TempDir dir;
  auto m = block_2x1x1();
  m.neighbour.resize(m.faces.size(), -1);
  write_poly_mesh(dir / "padded", m);
  EXPECT_EQ(read_mesh(dir / "padded").mesh.cell_count(), 2u);
  m.neighbour[7] = 0;
  write_poly_mesh(dir / "damaged", m);
  EXPECT_THAT(test_io::read_error(dir / "damaged"),
              HasSubstr("neighbour: face 7 has neighbour cell 0 after the padding of -1 that starts at face 1"));
}

}  // namespace
}  // namespace hotmesh::io
