// hotmesh io (internal): one OpenFOAM file (points, faces, owner, neighbour, boundary) as
// its FoamFile header and a cursor over its data. ASCII data is read as tokens with C++ and
// C comments skipped; binary data ("format binary") as raw little-endian labels and scalars
// of the sizes the header's `arch` names (label 32 or 64 bit, scalar 32 or 64 bit). Every
// read checks the end of the content: a cut or corrupt file gives an InputError naming the
// file and the line (ASCII) or byte offset (binary), never a read past the end.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "hotmesh/core/vec3.hpp"

namespace hotmesh::io::foam {

struct FoamHeader {
  bool binary = false;
  int label_bytes = 4;   ///< arch "label=32" or "label=64"
  int scalar_bytes = 8;  ///< arch "scalar=64" or "scalar=32"
  std::string class_name;
};

class FoamCursor {
 public:
  /// `content` is the whole (uncompressed) file; `source` names it in messages.
  FoamCursor(std::string_view content, std::string source);

  const std::string& source() const { return source_; }
  std::size_t position() const { return pos_; }
  const FoamHeader& header() const { return header_; }

  /// Reads the FoamFile { ... } dictionary at the start (after comments) and leaves the cursor
  /// behind it. Throws if there is none or it names an unknown format or arch.
  void read_header();

  /// Skips blanks, // and /* */ comments.
  void skip_space();
  /// The next non-blank character ('\0' at the end), not consumed.
  char peek();
  /// True (and consumed) if the next non-blank character is `c`.
  bool accept(char c);
  void expect(char c, std::string_view what);
  /// A word: letters, digits and _ . : < > - + (OpenFOAM words and numbers), or a quoted string.
  std::string_view word(std::string_view what);
  std::int64_t ascii_label(std::string_view what);
  double ascii_scalar(std::string_view what);
  /// A list count (ASCII label) that must be in [0, max].
  std::size_t count(std::string_view what, std::size_t max);

  /// Binary values at the cursor.
  std::int64_t binary_label(std::string_view what);
  double binary_scalar(std::string_view what);
  /// Bytes left from the cursor on.
  std::size_t remaining() const { return text_.size() - pos_; }

  /// "source:line N: message" (ASCII) or "source: byte N: message" (binary data).
  [[noreturn]] void fail(std::string_view message) const;
  [[noreturn]] void fail_at(std::size_t position, std::string_view message) const;

 private:
  std::string_view text_;
  std::string source_;
  std::size_t pos_ = 0;
  std::size_t data_start_ = 0;  ///< where the header ends (binary data is after it)
  FoamHeader header_;
};

/// The largest count a list may have (OpenFOAM's 32-bit labels).
constexpr std::size_t kMaxListSize = std::numeric_limits<std::int32_t>::max();

/// What a list's count may be, checked before anything is allocated for it. A list `N ( ... )`
/// is also bounded by the bytes left in the file; a uniform list `N { value }` (N copies of one
/// value, a few bytes whatever N says) only by this. The bounds come from the files read
/// before (the points the faces can refer to, one owner per face, ...); each `why` says so in
/// messages ("there are 11 faces, one owner each").
struct ListBound {
  std::size_t max_count = kMaxListSize;
  std::string why_count = "OpenFOAM's labels are 32-bit";
  std::size_t max_uniform = kMaxListSize;  ///< also at most max_count
  std::string why_uniform;                 ///< empty: why_count
};

/// An optional `List<...>` type word and a list's count, checked against `bound.max_count`.
std::size_t list_count(FoamCursor& in, std::string_view what, const ListBound& bound);

/// Lists in OpenFOAM's forms: `N ( ... )`, the uniform `N { value }`, and binary
/// `N ( raw bytes )`; an optional `List<...>` type word before the count is skipped. `what`
/// names the entries ("owner cells").
std::vector<std::int64_t> read_label_list(FoamCursor& in, std::string_view what, const ListBound& bound);
std::vector<geometry::Vec3> read_vector_list(FoamCursor& in, std::string_view what, const ListBound& bound);

/// Faces as a flat list: face f has nodes[offsets[f] .. offsets[f+1]).
struct FaceTable {
  std::vector<std::int64_t> offsets{0};
  std::vector<std::int64_t> nodes;
  std::size_t size() const { return offsets.size() - 1; }
};
/// A faceList (`N ( n(a b c ...) ... )`) or faceCompactList (offsets list, then node list),
/// as the header's class says. A face's points are all different, so a face (or the node list
/// of a faceCompactList) is never a uniform list of more than one point, nor the offsets one
/// of more than one offset.
FaceTable read_faces(FoamCursor& in);

struct BoundaryPatch {
  std::string name;
  std::string type;
  std::int64_t start_face = -1;
  std::int64_t face_count = -1;
  std::size_t position = 0;  ///< where its entry starts, for messages
};
/// The polyBoundaryMesh list: `N ( name { type t; nFaces n; startFace s; ... } ... )`.
std::vector<BoundaryPatch> read_boundary(FoamCursor& in);

}  // namespace hotmesh::io::foam
