// hotmesh io (internal): small text helpers of the CalculiX readers (frd_reader.cpp,
// inp_reader.cpp): trimming, upper case, numbers read with std::from_chars (no locale).
#pragma once

#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace hotmesh::io::detail {

inline std::string_view trim_blanks(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

inline std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  }
  return out;
}

/// A whole field as a number: "1.5", "-2.3E-04", "+7", ".5"; Fortran's "1.5D+03" too.
inline std::optional<double> field_double(std::string_view text) {
  text = trim_blanks(text);
  if (text.size() > 1 && text.front() == '+') text.remove_prefix(1);
  std::string buffer;
  if (text.find_first_of("dD") != std::string_view::npos) {
    buffer = std::string(text);
    for (char& c : buffer) {
      if (c == 'd' || c == 'D') c = 'E';
    }
    text = buffer;
  }
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || end != text.data() + text.size()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) {  // too small reads as 0, too large is no number
    const bool tiny = text.find("E-") != std::string_view::npos || text.find("e-") != std::string_view::npos;
    return tiny ? std::optional<double>(0.0) : std::nullopt;
  }
  if (ec != std::errc()) return std::nullopt;
  return value;
}

inline std::optional<std::int64_t> field_integer(std::string_view text) {
  text = trim_blanks(text);
  if (text.size() > 1 && text.front() == '+') text.remove_prefix(1);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace hotmesh::io::detail
