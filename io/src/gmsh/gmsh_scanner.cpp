// hotmesh io (private): the Gmsh scanner's slow paths: section markers and messages.
#include "gmsh/gmsh_scanner.hpp"

#include <algorithm>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::io::gmsh {
namespace {

/// A token for a message: at most 24 characters, control characters shown as '?'.
std::string shown(std::string_view token) {
  std::string text(token.substr(0, 24));
  for (char& c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < ' ' || u >= 127) c = '?';
  }
  if (token.size() > 24) text += "...";
  return text;
}

}  // namespace

void Scanner::fail_at(std::size_t position, std::string_view message) const {
  position = std::min(position, text_.size());
  if (binary_) {
    std::string text = "byte " + std::to_string(position);
    if (!section_.empty()) text.append(" in ").append(section_);
    text.append(": ").append(message);
    throw InputError::in(source_, text);
  }
  const auto newlines = std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(position), '\n');
  throw InputError::at(source_, static_cast<std::size_t>(newlines) + 1, message);
}

std::string_view Scanner::quoted(std::string_view what) {
  while (pos_ < text_.size() && is_line_blank(text_[pos_])) ++pos_;
  if (pos_ >= text_.size()) cut_short(what);
  if (text_[pos_] != '"') fail(std::string("expected ") + std::string(what) + " in double quotes");
  const std::size_t start = pos_ + 1;
  const std::size_t close = text_.find_first_of("\"\n", start);
  if (close == std::string_view::npos || text_[close] != '"') {
    fail(std::string(what) + " has no closing double quote");
  }
  pos_ = close + 1;
  return text_.substr(start, close - start);
}

void Scanner::end_line(std::string_view after_what) {
  while (pos_ < text_.size() && is_line_blank(text_[pos_])) ++pos_;
  if (pos_ >= text_.size()) return;
  if (text_[pos_] == '\n') {
    ++pos_;
    return;
  }
  const char* first = text_.data() + pos_;
  fail("unexpected '" + shown(std::string_view(first, static_cast<std::size_t>(token_end(first) - first))) +
       "' after " + std::string(after_what) + ": the line holds more values than expected");
}

void Scanner::expect_end(std::string_view name) {
  const std::string marker = "$End" + std::string(name);
  skip_blank();
  const std::size_t at = pos_;
  if (at_end()) fail("expected " + marker + ", found the end of the file (the file is cut short)");
  const std::string_view line = next_line();
  if (line != marker) {
    fail_at(at, "expected " + marker + ", found '" + shown(line) +
                    "': the section holds more data than its counts say, or is corrupt");
  }
}

void Scanner::skip_section(std::string_view name) {
  const std::string marker = "\n$End" + std::string(name);
  const std::size_t start = pos_ == 0 ? 0 : pos_ - 1;  // the marker may follow at once
  std::size_t at = text_.find(marker, start);
  while (at != std::string_view::npos) {
    const std::size_t after = at + marker.size();
    if (after >= text_.size() || is_blank(text_[after])) break;  // not "$EndFooBar"
    at = text_.find(marker, after);
  }
  if (at == std::string_view::npos) {
    fail("section $" + std::string(name) + " has no $End" + std::string(name) + " (the file is cut short)");
  }
  pos_ = at + 1;
  next_line();
}

void Scanner::bad_token(const char* first, const char* last, std::string_view what, bool out_of_range) const {
  const std::size_t at = static_cast<std::size_t>(first - text_.data());
  const std::string token = shown(std::string_view(first, static_cast<std::size_t>(last - first)));
  if (out_of_range) fail_at(at, std::string(what) + " '" + token + "' is out of range");
  if (*first == '$') {
    fail_at(at, "found '" + token + "' where " + std::string(what) +
                    " was expected: the section holds fewer entries than its counts say");
  }
  fail_at(at, "expected " + std::string(what) + ", found '" + token + "'");
}

void Scanner::out_of_range(std::size_t at, std::string_view what, std::int64_t value, int low, int high) const {
  fail_at(at, std::string(what) + " " + std::to_string(value) + " is out of range (" + std::to_string(low) + " to " +
                  std::to_string(high) + ")");
}

void Scanner::too_large(std::size_t at, std::string_view what, std::uint64_t value) const {
  fail_at(at, std::string(what) + " " + std::to_string(value) +
                  " is more than the rest of the file can hold (a corrupt count, or the file is cut short)");
}

void Scanner::cut_short(std::string_view what) const {
  fail("the file ends where " + std::string(what) + " was expected (the file is cut short)");
}

void Scanner::line_ends(std::string_view what) const {
  fail("the line ends where " + std::string(what) + " was expected");
}

}  // namespace hotmesh::io::gmsh
