// hotmesh io (internal): integers of the JSON headers of the state files (restart.hmr,
// checkpoint.hmc). nlohmann's get<int>() converts a floating-point value with a plain cast,
// which is undefined for a value beyond the integer's range (a damaged file's 5.8e19, found
// by fuzzing): these take only JSON integers within the range and throw otherwise, which the
// readers report as a damaged header.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace hotmesh::io::detail {

/// `value` as a T. Throws std::out_of_range for an integer T cannot hold, std::domain_error
/// for anything but an integer (a fraction, 1e3, a string, ...).
template <class T>
T integer_value(const nlohmann::json& value) {
  static_assert(std::is_integral_v<T> && !std::is_same_v<T, bool>);
  if (value.is_number_unsigned()) {
    const auto v = value.get<std::uint64_t>();
    if (std::in_range<T>(v)) return static_cast<T>(v);
  } else if (value.is_number_integer()) {
    const auto v = value.get<std::int64_t>();
    if (std::in_range<T>(v)) return static_cast<T>(v);
  } else {
    const std::string got = value.is_number() ? value.dump() : value.type_name();
    throw std::domain_error("expected an integer, got " + got);
  }
  throw std::out_of_range(value.dump() + " is out of range");
}

/// Every element of the array `value`, as integer_value<T> reads it.
template <class T>
std::vector<T> integer_values(const nlohmann::json& value) {
  if (!value.is_array()) throw std::domain_error(std::string("expected an array, got ") + value.type_name());
  std::vector<T> result;
  result.reserve(value.size());
  for (const nlohmann::json& item : value) result.push_back(integer_value<T>(item));
  return result;
}

}  // namespace hotmesh::io::detail
