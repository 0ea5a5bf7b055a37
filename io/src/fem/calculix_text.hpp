// hotmesh io (internal): small text helpers of the CalculiX readers (frd_reader.cpp,
// inp_reader.cpp): numbers read with std::from_chars (no locale).
#pragma once

#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

#include "hotmesh/core/text.hpp"

namespace hotmesh::io::detail {

/// A whole field as a number: "1.5", "-2.3E-04", "+7", ".5"; Fortran's "1.5D+03" too.
inline std::optional<double> field_double(std::string_view text) {
  text = trim(text);
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
  text = trim(text);
  if (text.size() > 1 && text.front() == '+') text.remove_prefix(1);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace hotmesh::io::detail
