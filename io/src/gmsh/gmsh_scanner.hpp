// hotmesh io (private): the cursor the Gmsh reader walks a .msh file with. The whole file is
// in memory; ASCII tokens are cut at blanks and converted with std::from_chars, binary values
// are copied out with bounds checks. Nothing is counted while scanning: the line of a problem
// is found only when a message is made (ASCII files), binary files name the byte offset and
// section instead. Every read checks the end of the content, so a cut or corrupt file gives
// an InputError, never a read past the end; counts are checked against the bytes that remain
// before anything is allocated for them.
#pragma once

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace hotmesh::io::gmsh {

class Scanner {
 public:
  Scanner(std::string_view content, std::string_view source) : text_(content), source_(source) {}

  std::string_view source() const { return source_; }
  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return text_.size() - pos_; }
  bool at_end() const { return pos_ >= text_.size(); }

  /// Binary files: messages name byte offsets instead of lines.
  void set_binary(bool binary) { binary_ = binary; }
  bool binary() const { return binary_; }
  /// The section being read, e.g. "$Nodes", for messages.
  void set_section(std::string_view section) { section_ = section; }
  std::string_view section() const { return section_; }

  // ---- ASCII ----------------------------------------------------------------------------

  /// Skips blanks and line ends (blank lines, the CR of CRLF).
  void skip_blank() {
    while (pos_ < text_.size() && is_blank(text_[pos_])) ++pos_;
  }

  /// The next non-blank line without surrounding blanks; the cursor moves past its end.
  /// Empty at the end of the content.
  std::string_view next_line() {
    skip_blank();
    const std::size_t start = pos_;
    std::size_t end = text_.find('\n', start);
    if (end == std::string_view::npos) end = text_.size();
    pos_ = end < text_.size() ? end + 1 : end;
    while (end > start && is_blank(text_[end - 1])) --end;
    return text_.substr(start, end - start);
  }

  /// True if another token follows on the current line.
  bool more_on_line() {
    while (pos_ < text_.size() && is_line_blank(text_[pos_])) ++pos_;
    return pos_ < text_.size() && text_[pos_] != '\n';
  }

  /// The next token on the current line as it is written.
  std::string_view word(std::string_view what) {
    const char* first = token(what);
    const char* last = token_end(first);
    pos_ = static_cast<std::size_t>(last - text_.data());
    return {first, static_cast<std::size_t>(last - first)};
  }

  /// An integer token on the current line; `what` names it in messages.
  std::int64_t integer(std::string_view what) {
    const char* first = token(what);
    const char* last = token_end(first);
    const char* digits = (*first == '+' && last - first > 1) ? first + 1 : first;
    std::int64_t value = 0;
    const auto [ptr, ec] = std::from_chars(digits, last, value);
    if (ec != std::errc{} || ptr != last) bad_token(first, last, what, ec == std::errc::result_out_of_range);
    pos_ = static_cast<std::size_t>(last - text_.data());
    return value;
  }

  /// An integer token that must lie in [low, high].
  int small_integer(std::string_view what, int low, int high) {
    const std::size_t at = pos_;
    const std::int64_t value = integer(what);
    if (value < low || value > high) out_of_range(at, what, value, low, high);
    return static_cast<int>(value);
  }

  /// A floating-point token on the current line ("nan" and "inf" are returned as such).
  double real(std::string_view what) {
    const char* first = token(what);
    const char* last = token_end(first);
    const char* digits = (*first == '+' && last - first > 1) ? first + 1 : first;
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(digits, last, value);
    if (ec != std::errc{} || ptr != last) bad_token(first, last, what, ec == std::errc::result_out_of_range);
    pos_ = static_cast<std::size_t>(last - text_.data());
    return value;
  }

  /// A count of items on the current line, each needing at least `min_bytes` of the rest of
  /// the file: a larger count is reported as corrupt before anything is allocated for it.
  std::size_t count(std::string_view what, std::size_t min_bytes) {
    const std::size_t at = pos_;
    const std::int64_t value = integer(what);
    if (value < 0) fail_at(at, std::string(what) + " is negative (" + std::to_string(value) + ")");
    return checked_count(static_cast<std::uint64_t>(value), min_bytes, at, what);
  }

  /// The text between double quotes on the current line.
  std::string_view quoted(std::string_view what);

  /// Only blanks may remain on the current line; moves to the start of the next one.
  void end_line(std::string_view after_what);

  /// Expects the line "$End<name>" (blank lines before it are skipped).
  void expect_end(std::string_view name);

  /// Moves past the line "$End<name>" without reading what comes before it.
  void skip_section(std::string_view name);

  // ---- binary ---------------------------------------------------------------------------

  /// Ensures `bytes` more bytes exist.
  void need(std::size_t bytes, std::string_view what) {
    if (bytes > remaining()) cut_short(what);
  }

  template <class T>
  T binary_value(std::string_view what) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T), what);
    T value;
    std::memcpy(&value, text_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }

  /// Copies `n` values of T (the bytes were checked with need()).
  template <class T>
  void binary_values(T* out, std::size_t n, std::string_view what) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (n > remaining() / sizeof(T)) cut_short(what);
    std::memcpy(out, text_.data() + pos_, n * sizeof(T));
    pos_ += n * sizeof(T);
  }

  /// A binary count read at `at`, each item needing at least `min_bytes`.
  std::size_t checked_count(std::uint64_t value, std::size_t min_bytes, std::size_t at, std::string_view what) const {
    if (min_bytes > 0 && value > remaining() / min_bytes) too_large(at, what, value);
    return static_cast<std::size_t>(value);
  }

  // ---- messages -------------------------------------------------------------------------

  /// Throws InputError "<source>:<line>: <message>" (ASCII) or
  /// "<source>: byte <offset> in <section>: <message>" (binary).
  [[noreturn]] void fail_at(std::size_t position, std::string_view message) const;
  [[noreturn]] void fail(std::string_view message) const { fail_at(pos_, message); }

 private:
  static bool is_blank(char c) { return static_cast<unsigned char>(c) <= ' '; }
  static bool is_line_blank(char c) { return c != '\n' && static_cast<unsigned char>(c) <= ' '; }

  /// Start of the next token on the current line; fails at the line's end.
  const char* token(std::string_view what) {
    while (pos_ < text_.size() && is_line_blank(text_[pos_])) ++pos_;
    if (pos_ >= text_.size()) cut_short(what);
    if (text_[pos_] == '\n') line_ends(what);
    return text_.data() + pos_;
  }
  const char* token_end(const char* p) const {
    const char* end = text_.data() + text_.size();
    while (p < end && !is_blank(*p)) ++p;
    return p;
  }

  [[noreturn]] void bad_token(const char* first, const char* last, std::string_view what, bool out_of_range) const;
  [[noreturn]] void out_of_range(std::size_t at, std::string_view what, std::int64_t value, int low, int high) const;
  [[noreturn]] void too_large(std::size_t at, std::string_view what, std::uint64_t value) const;
  [[noreturn]] void cut_short(std::string_view what) const;
  [[noreturn]] void line_ends(std::string_view what) const;

  std::string_view text_;
  std::string_view source_;
  std::size_t pos_ = 0;
  bool binary_ = false;
  std::string_view section_;
};

}  // namespace hotmesh::io::gmsh
