// hotmesh core: the small text helpers of every reader of user files (tables, case files,
// CalculiX decks, CAD headers): trimming, ASCII case, comma-separated fields. ASCII only and
// no locale, so a file reads the same on every machine.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace hotmesh {

/// What the table and deck readers take as blank around a field: space, tab, CR, FF, VT (not
/// the newline, which ends their lines).
inline constexpr std::string_view kBlanks = " \t\r\f\v";
/// Blanks and the newline: what std::isspace is in the "C" locale.
inline constexpr std::string_view kWhiteSpace = " \t\n\r\f\v";

/// `text` without the characters of `strip` at either end.
constexpr std::string_view trim(std::string_view text, std::string_view strip = kBlanks) {
  const std::size_t first = text.find_first_not_of(strip);
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(strip) - first + 1);
}

/// `text` with A-Z as a-z; other bytes as they are.
inline std::string ascii_lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

/// `text` with a-z as A-Z; other bytes as they are.
inline std::string ascii_upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  }
  return out;
}

/// The fields of a line between `separator`s, each trimmed of blanks; an empty line is one
/// empty field, and "a," is "a" and "" (callers decide what a trailing separator means).
inline std::vector<std::string_view> split_fields(std::string_view line, char separator = ',') {
  std::vector<std::string_view> fields;
  while (true) {
    const std::size_t end = line.find(separator);
    fields.push_back(trim(line.substr(0, end)));
    if (end == std::string_view::npos) break;
    line.remove_prefix(end + 1);
  }
  return fields;
}

}  // namespace hotmesh
