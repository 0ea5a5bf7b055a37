// hotmesh io: the FoamFile cursor and OpenFOAM's list forms (see foam_file.hpp).
#include "foam/foam_file.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::io::foam {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
bool ends_word(char c) {
  return is_space(c) || c == ';' || c == '{' || c == '}' || c == '(' || c == ')' || c == '[' || c == ']' || c == '"';
}

/// "label=32" in an arch string: 32, or 0 if the key is missing.
int arch_bits(std::string_view arch, std::string_view key) {
  const std::size_t at = arch.find(key);
  if (at == std::string_view::npos) return 0;
  int bits = 0;
  const char* begin = arch.data() + at + key.size();
  std::from_chars(begin, arch.data() + arch.size(), bits);
  return bits;
}

}  // namespace

FoamCursor::FoamCursor(std::string_view content, std::string source) : text_(content), source_(std::move(source)) {}

void FoamCursor::fail(std::string_view message) const { fail_at(pos_, message); }

void FoamCursor::fail_at(std::size_t position, std::string_view message) const {
  position = std::min(position, text_.size());
  if (header_.binary && position >= data_start_) {
    throw InputError::in(source_, fmt::format("byte {}: {}", position, message));
  }
  const auto line =
      static_cast<std::size_t>(std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(position), '\n'));
  throw InputError::at(source_, line + 1, message);
}

void FoamCursor::skip_space() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (is_space(c)) {
      ++pos_;
    } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/') {
      const std::size_t end = text_.find('\n', pos_);
      pos_ = end == std::string_view::npos ? text_.size() : end + 1;
    } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') {
      const std::size_t end = text_.find("*/", pos_ + 2);
      if (end == std::string_view::npos) fail("a /* comment is not closed");
      pos_ = end + 2;
    } else {
      return;
    }
  }
}

char FoamCursor::peek() {
  skip_space();
  return pos_ < text_.size() ? text_[pos_] : '\0';
}

bool FoamCursor::accept(char c) {
  skip_space();
  if (pos_ < text_.size() && text_[pos_] == c) {
    ++pos_;
    return true;
  }
  return false;
}

void FoamCursor::expect(char c, std::string_view what) {
  if (accept(c)) return;
  if (pos_ >= text_.size()) fail(fmt::format("the file ends where '{}' was expected ({}): is it truncated?", c, what));
  fail(fmt::format("expected '{}' ({}), found '{}'", c, what, text_[pos_]));
}

std::string_view FoamCursor::word(std::string_view what) {
  skip_space();
  if (pos_ >= text_.size()) fail(fmt::format("the file ends where {} was expected: is it truncated?", what));
  if (text_[pos_] == '"') {
    const std::size_t end = text_.find('"', pos_ + 1);
    if (end == std::string_view::npos) fail(fmt::format("a quoted string ({}) is not closed", what));
    const std::string_view quoted = text_.substr(pos_ + 1, end - pos_ - 1);
    pos_ = end + 1;
    return quoted;
  }
  const std::size_t start = pos_;
  while (pos_ < text_.size() && !ends_word(text_[pos_])) ++pos_;
  if (pos_ == start) fail(fmt::format("expected {}, found '{}'", what, text_[pos_]));
  return text_.substr(start, pos_ - start);
}

std::int64_t FoamCursor::ascii_label(std::string_view what) {
  const std::size_t at = (skip_space(), pos_);
  const std::string_view w = word(what);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), value);
  if (ec != std::errc() || end != w.data() + w.size()) {
    fail_at(at, fmt::format("expected {} (an integer), found '{}'", what, w));
  }
  return value;
}

double FoamCursor::ascii_scalar(std::string_view what) {
  const std::size_t at = (skip_space(), pos_);
  const std::string_view w = word(what);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), value);
  if (ec != std::errc() || end != w.data() + w.size()) {
    fail_at(at, fmt::format("expected {} (a number), found '{}'", what, w));
  }
  return value;
}

std::size_t FoamCursor::count(std::string_view what, std::size_t max) {
  const std::size_t at = (skip_space(), pos_);
  const std::int64_t n = ascii_label(what);
  if (n < 0) fail_at(at, fmt::format("negative {}: {}", what, n));
  if (static_cast<std::uint64_t>(n) > max) {
    fail_at(at, fmt::format("{} {} is more than the rest of the file can hold: is it truncated?", what, n));
  }
  return static_cast<std::size_t>(n);
}

std::int64_t FoamCursor::binary_label(std::string_view what) {
  const auto size = static_cast<std::size_t>(header_.label_bytes);
  if (remaining() < size) fail(fmt::format("the file ends inside {}: is it truncated?", what));
  std::int64_t value = 0;
  if (size == 4) {
    std::int32_t v = 0;
    std::memcpy(&v, text_.data() + pos_, 4);
    value = v;
  } else {
    std::memcpy(&value, text_.data() + pos_, 8);
  }
  pos_ += size;
  return value;
}

double FoamCursor::binary_scalar(std::string_view what) {
  const auto size = static_cast<std::size_t>(header_.scalar_bytes);
  if (remaining() < size) fail(fmt::format("the file ends inside {}: is it truncated?", what));
  double value = 0.0;
  if (size == 4) {
    float v = 0.0f;
    std::memcpy(&v, text_.data() + pos_, 4);
    value = static_cast<double>(v);
  } else {
    std::memcpy(&value, text_.data() + pos_, 8);
  }
  pos_ += size;
  return value;
}

namespace {

/// Skips the value of a dictionary entry: tokens up to the ';' that ends it, or a { } block.
/// Returns the first word of the value (empty for a block).
std::string skip_entry_value(FoamCursor& in, std::string_view key) {
  const std::string what = fmt::format("the value of '{}'", key);
  if (in.accept('{')) {
    for (int depth = 1; depth > 0;) {
      if (in.accept('{')) {
        ++depth;
      } else if (in.accept('}')) {
        --depth;
      } else if (!in.accept(';') && !in.accept('(') && !in.accept(')') && !in.accept('[') && !in.accept(']')) {
        in.word(what);
      }
    }
    return {};
  }
  std::string first;
  for (int depth = 0;;) {
    if (in.accept(';')) {
      if (depth == 0) return first;
    } else if (in.accept('(') || in.accept('[')) {
      ++depth;
    } else if (in.accept(')') || in.accept(']')) {
      --depth;
    } else {
      const std::string_view w = in.word(what);
      if (first.empty()) first = w;
    }
  }
}

}  // namespace

void FoamCursor::read_header() {
  skip_space();
  const std::size_t at = pos_;
  if (word("the FoamFile header") != "FoamFile") fail_at(at, "expected the FoamFile { ... } header");
  expect('{', "the FoamFile header");
  std::map<std::string, std::string, std::less<>> entries;
  while (!accept('}')) {
    const std::string key(word("a FoamFile header entry"));
    entries[key] = skip_entry_value(*this, key);
  }
  data_start_ = pos_;
  const auto format = entries.find("format");
  if (format == entries.end() || (format->second != "ascii" && format->second != "binary")) {
    fail_at(at, "the FoamFile header needs `format ascii;` or `format binary;`");
  }
  header_.binary = format->second == "binary";
  if (const auto c = entries.find("class"); c != entries.end()) header_.class_name = c->second;
  if (const auto arch = entries.find("arch"); arch != entries.end()) {
    if (arch->second.find("MSB") != std::string::npos) {
      fail_at(at, "big-endian (arch \"MSB...\") binary files are not supported: convert them with foamFormatConvert");
    }
    const int label = arch_bits(arch->second, "label=");
    const int scalar = arch_bits(arch->second, "scalar=");
    if (label != 0 && label != 32 && label != 64) {
      fail_at(at, fmt::format("arch: label size {} (expected 32 or 64)", label));
    }
    if (scalar != 0 && scalar != 32 && scalar != 64) {
      fail_at(at, fmt::format("arch: scalar size {} (expected 32 or 64)", scalar));
    }
    if (label != 0) header_.label_bytes = label / 8;
    if (scalar != 0) header_.scalar_bytes = scalar / 8;
  }
}

namespace {

/// Skips a `List<label>` style type word before a list's count.
void skip_list_type(FoamCursor& in) {
  const char c = in.peek();
  if (c >= '0' && c <= '9') return;
  const std::size_t at = in.position();
  const std::string_view w = in.word("a list count");
  if (!w.starts_with("List<")) in.fail_at(at, fmt::format("expected a list count, found '{}'", w));
}

std::int64_t label_value(FoamCursor& in, std::string_view what) {
  return in.header().binary ? in.binary_label(what) : in.ascii_label(what);
}

geometry::Vec3 vector_value(FoamCursor& in, std::string_view what) {
  if (in.header().binary) {
    const double x = in.binary_scalar(what), y = in.binary_scalar(what), z = in.binary_scalar(what);
    return {x, y, z};
  }
  in.expect('(', what);
  const double x = in.ascii_scalar(what), y = in.ascii_scalar(what), z = in.ascii_scalar(what);
  in.expect(')', what);
  return {x, y, z};
}

}  // namespace

std::size_t list_count(FoamCursor& in, std::string_view what, const ListBound& bound) {
  skip_list_type(in);
  const std::size_t at = (in.skip_space(), in.position());
  const std::size_t n = in.count(fmt::format("the number of {}", what), kMaxListSize);
  if (n > bound.max_count) {
    in.fail_at(at, fmt::format("the list of {} has {} entries, but {}", what, n, bound.why_count));
  }
  return n;
}

namespace {

/// The shape shared by every list form: count, then `(` elements `)` or `{` one value `}`.
/// `min_size` is the fewest bytes an element takes, to check the count before allocating.
template <class T, class ReadOne>
std::vector<T> read_list(FoamCursor& in, std::string_view what, const ListBound& bound, std::size_t min_size,
                         ReadOne read_one) {
  const std::size_t at = (in.skip_space(), in.position());
  const std::size_t n = list_count(in, what, bound);
  std::vector<T> values;
  if (in.accept('{')) {  // uniform: N{value}
    if (n > bound.max_uniform) {
      in.fail_at(at, fmt::format("the list of {} is {} copies of one value (N{{value}}), but {}", what, n,
                                 bound.why_uniform.empty() ? bound.why_count : bound.why_uniform));
    }
    const T value = read_one(in);
    in.expect('}', fmt::format("the end of the uniform list of {}", what));
    values.assign(n, value);
    return values;
  }
  in.expect('(', fmt::format("the start of the list of {}", what));
  if (n > in.remaining() / min_size) {
    in.fail_at(at, fmt::format("the list of {} should hold {} entries, but only {} bytes are left in the file: is it "
                               "truncated?",
                               what, n, in.remaining()));
  }
  values.reserve(n);
  for (std::size_t i = 0; i < n; ++i) values.push_back(read_one(in));
  in.expect(')', fmt::format("the end of the list of {} ({} read, as its count says)", what, n));
  return values;
}

}  // namespace

std::vector<std::int64_t> read_label_list(FoamCursor& in, std::string_view what, const ListBound& bound) {
  const std::size_t size = in.header().binary ? static_cast<std::size_t>(in.header().label_bytes) : 2;  // "0 "
  return read_list<std::int64_t>(in, what, bound, size, [&](FoamCursor& c) { return label_value(c, what); });
}

std::vector<geometry::Vec3> read_vector_list(FoamCursor& in, std::string_view what, const ListBound& bound) {
  const std::size_t size =
      in.header().binary ? 3 * static_cast<std::size_t>(in.header().scalar_bytes) : 8;  // "(0 0 0) "
  return read_list<geometry::Vec3>(in, what, bound, size, [&](FoamCursor& c) { return vector_value(c, what); });
}

namespace {

/// A face's points are different points: a uniform list of them holds at most one.
constexpr std::string_view kFacePointsDiffer = "a face's points are different points";

FaceTable read_compact_faces(FoamCursor& in) {
  const std::size_t at = (in.skip_space(), in.position());
  FaceTable faces;
  faces.offsets = read_label_list(
      in, "face offsets",
      {.max_uniform = 1, .why_uniform = "a face has points, so the offsets of successive faces differ"});
  if (faces.offsets.empty() || faces.offsets.front() != 0) in.fail_at(at, "the face offsets must start with 0");
  for (std::size_t f = 0; f + 1 < faces.offsets.size(); ++f) {
    if (faces.offsets[f + 1] < faces.offsets[f]) {
      in.fail_at(at, fmt::format("the face offsets decrease at face {} ({} after {})", f, faces.offsets[f + 1],
                                 faces.offsets[f]));
    }
  }
  const auto last = static_cast<std::size_t>(faces.offsets.back());
  faces.nodes = read_label_list(in, "face points",
                                {.max_count = last,
                                 .why_count = fmt::format("the last face offset is {}", last),
                                 .max_uniform = 1,
                                 .why_uniform = std::string(kFacePointsDiffer)});
  if (faces.nodes.size() != last) {
    in.fail_at(at, fmt::format("the last face offset is {} but there are {} face points", last, faces.nodes.size()));
  }
  return faces;
}

FaceTable read_face_list(FoamCursor& in) {
  FaceTable faces;
  skip_list_type(in);
  const std::size_t n = in.count("the number of faces", in.remaining() / 4);  // "0()" and a blank
  in.expect('(', "the start of the list of faces");
  faces.offsets.reserve(n + 1);
  faces.nodes.reserve(4 * n);
  const ListBound bound{.max_uniform = 1, .why_uniform = std::string(kFacePointsDiffer)};
  for (std::size_t f = 0; f < n; ++f) {
    const std::vector<std::int64_t> face = read_label_list(in, fmt::format("points of face {}", f), bound);
    faces.nodes.insert(faces.nodes.end(), face.begin(), face.end());
    faces.offsets.push_back(static_cast<std::int64_t>(faces.nodes.size()));
  }
  in.expect(')', fmt::format("the end of the list of faces ({} read, as its count says)", n));
  return faces;
}

}  // namespace

FaceTable read_faces(FoamCursor& in) {
  return in.header().class_name == "faceCompactList" ? read_compact_faces(in) : read_face_list(in);
}

std::vector<BoundaryPatch> read_boundary(FoamCursor& in) {
  skip_list_type(in);
  const std::size_t n = in.count("the number of patches", in.remaining() / 8);  // "a{}" and blanks at least
  in.expect('(', "the start of the list of patches");
  std::vector<BoundaryPatch> patches;
  for (std::size_t k = 0; k < n; ++k) {
    BoundaryPatch& p = patches.emplace_back();
    p.position = (in.skip_space(), in.position());
    p.name = in.word("a patch name");
    in.expect('{', fmt::format("the dictionary of patch '{}'", p.name));
    while (!in.accept('}')) {
      const std::size_t at = (in.skip_space(), in.position());
      const std::string key(in.word(fmt::format("an entry of patch '{}'", p.name)));
      if (key == "type") {
        p.type = skip_entry_value(in, key);
      } else if (key == "nFaces" || key == "startFace") {
        const std::int64_t value = in.ascii_label(fmt::format("{} of patch '{}'", key, p.name));
        if (value < 0) in.fail_at(at, fmt::format("patch '{}': negative {} {}", p.name, key, value));
        (key == "nFaces" ? p.face_count : p.start_face) = value;
        in.expect(';', fmt::format("the end of {} of patch '{}'", key, p.name));
      } else {
        skip_entry_value(in, key);
      }
    }
    if (p.type.empty() || p.face_count < 0 || p.start_face < 0) {
      in.fail_at(p.position, fmt::format("patch '{}' needs type, nFaces and startFace", p.name));
    }
  }
  in.expect(')', fmt::format("the end of the list of patches ({} read, as its count says)", n));
  return patches;
}

}  // namespace hotmesh::io::foam
