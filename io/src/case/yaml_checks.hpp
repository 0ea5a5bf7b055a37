// hotmesh io (internal): checking YAML values one by one. Problems are collected, not
// thrown, so a whole file can be reported at once; each Entry knows its key path and line.
// yaml-cpp marks are 0-based, ours 1-based.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include "hotmesh/core/enum_names.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/core/text.hpp"
#include "hotmesh/core/vec3.hpp"

namespace hotmesh::io::detail {

/// Concatenates strings (GCC 12 warns wrongly about chains of std::string operator+).
template <class... Parts>
std::string cat(const Parts&... parts) {
  std::string text;
  (text.append(std::string_view(parts)), ...);
  return text;
}

template <class Range>
std::string join(const Range& items) {
  std::string text;
  for (const auto& item : items) text.append(text.empty() ? "" : ", ").append(std::string_view(item));
  return text;
}

/// The allowed key a mistyped ("degre") or abbreviated ("newton_tol") key most likely meant.
inline std::optional<std::string_view> closest_key(std::string_view name, std::span<const std::string_view> allowed) {
  std::optional<std::string_view> best;
  std::size_t best_distance = SIZE_MAX;
  for (const std::string_view candidate : allowed) {
    std::vector<std::size_t> row(candidate.size() + 1);  // Levenshtein distance, one row at a time
    for (std::size_t j = 0; j < row.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= name.size(); ++i) {
      std::size_t diagonal = std::exchange(row[0], i);
      for (std::size_t j = 1; j < row.size(); ++j) {
        const std::size_t change = diagonal + (name[i - 1] == candidate[j - 1] ? 0u : 1u);
        diagonal = std::exchange(row[j], std::min({row[j] + 1, row[j - 1] + 1, change}));
      }
    }
    const std::size_t distance = name.size() >= 3 && candidate.starts_with(name) ? 1 : row.back();
    if (distance < best_distance && distance <= std::max<std::size_t>(2, candidate.size() / 3)) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

/// The problems found so far, each with its line (0: none) and key path.
class Problems {
 public:
  void add(std::size_t line, std::string key, std::string message) {
    list_.push_back({line, std::move(key), std::move(message)});
  }
  bool empty() const { return list_.empty(); }

  /// Throws one InputError with a line per problem, in the order of the file.
  [[noreturn]] void raise(const std::string& file) {
    std::stable_sort(list_.begin(), list_.end(), [](const auto& a, const auto& b) { return a.line < b.line; });
    std::string text;
    for (const Problem& p : list_) {
      text.append(text.empty() ? "" : "\n").append(file);
      if (p.line > 0) text.append(":").append(std::to_string(p.line));
      text.append(": ").append(p.key).append(p.key.empty() ? "" : ": ").append(p.message);
    }
    throw InputError(text);
  }

 private:
  struct Problem {
    std::size_t line;
    std::string key;
    std::string message;
  };
  std::vector<Problem> list_;
};

inline std::size_t line_of(const YAML::Mark& mark) { return mark.line < 0 ? 0 : static_cast<std::size_t>(mark.line) + 1; }
inline std::size_t line_of(const YAML::Node& node) { return line_of(node.Mark()); }

inline bool quoted(const YAML::Node& node) { return node.IsScalar() && node.Tag() == "!"; }

/// What the user wrote, for "expected ..., got <describe>" messages.
inline std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Scalar:
      return quoted(node) ? cat("the text \"", node.Scalar(), "\"") : cat("'", node.Scalar(), "'");
    default: return "nothing";
  }
}

/// A number as YAML writes it (std::from_chars, so no locale), plus a leading '+' and
/// .inf/.nan. Too large reads as infinite (then reported), too small as 0.
template <class T>
std::optional<T> parse(std::string_view text) {
  if constexpr (std::is_floating_point_v<T>) {
    const std::string name = ascii_lower(text);
    if (name == ".inf" || name == "+.inf" || name == "-.inf") return name[0] == '-' ? -HUGE_VAL : HUGE_VAL;
    if (name == ".nan") return std::nan("");
  }
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || end != text.data() + text.size()) return std::nullopt;
  if constexpr (std::is_floating_point_v<T>) {
    if (ec == std::errc::result_out_of_range) {
      const bool tiny = text.find("e-") != std::string_view::npos || text.find("E-") != std::string_view::npos;
      return (text.front() == '-' ? -1.0 : 1.0) * (tiny ? 0.0 : HUGE_VAL);
    }
  }
  return ec == std::errc() ? std::optional<T>(value) : std::nullopt;
}

/// A key of the case file with its value: `path` is the full key path ("solver.increments"),
/// `line` the line of the key (values that are maps or lists may start on a later line).
struct Entry {
  std::string path;
  YAML::Node value;
  std::size_t line = 0;
  std::string name;  ///< the last part of path

  Entry child(const YAML::Node& key, const YAML::Node& child_value) const {
    return {path.empty() ? key.Scalar() : cat(path, ".", key.Scalar()), child_value, line_of(key), key.Scalar()};
  }
  /// Item i of a list value, as "path[i]" on its own line.
  Entry item(std::size_t i) const {
    const YAML::Node node = value[i];
    return {cat(path, "[", std::to_string(i), "]"), node, line_of(node), {}};
  }
  std::string sub(std::string_view key) const { return path.empty() ? std::string(key) : cat(path, ".", key); }
};

/// The keys of one map, in file order.
struct MapEntries {
  std::vector<Entry> entries;

  const Entry* find(std::string_view name) const {
    const auto it = std::find_if(entries.begin(), entries.end(), [&](const Entry& e) { return e.name == name; });
    return it == entries.end() ? nullptr : &*it;
  }
};

/// Type and range checks of single values; each reports its problem and returns nothing.
class Reader {
 public:
  explicit Reader(Problems& problems) : problems_(problems) {}

  void error(const Entry& e, std::string message) { problems_.add(e.line, e.path, std::move(message)); }
  void error(std::size_t line, std::string key, std::string message) {
    problems_.add(line, std::move(key), std::move(message));
  }

  /// True if `e` is a map or empty (an empty value counts as a map without keys).
  bool map_or_empty(const Entry& e, std::string_view expected) {
    if (e.value.IsMap() || e.value.IsNull()) return true;
    error(e, cat("expected ", expected, ", got ", describe(e.value)));
    return false;
  }

  /// The keys of the map `e` (see map_or_empty); reports keys that are repeated, that are not
  /// plain names, or (unless `allowed` is empty) that are not in `allowed`.
  MapEntries keys(const Entry& e, std::span<const std::string_view> allowed) {
    MapEntries map;
    if (!e.value.IsMap()) return map;
    for (const auto pair : e.value) {  // by value: yaml-cpp's iterators hand out temporaries
      if (!pair.first.IsScalar() || pair.first.Scalar().empty()) {
        error(line_of(pair.first), e.path, "keys must be plain names, got " + describe(pair.first));
        continue;
      }
      Entry child = e.child(pair.first, pair.second);
      if (const Entry* first = map.find(child.name)) {
        error(child, cat("given twice (first on line ", std::to_string(first->line), "); keep one"));
      } else if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), child.name) == allowed.end()) {
        const auto guess = closest_key(child.name, allowed);
        error(child, cat("unknown key", guess ? cat(" (did you mean '", *guess, "'?)") : "", "; allowed ",
                         e.path.empty() ? "at the top level" : "in " + e.path, ": ", join(allowed)));
      } else {
        map.entries.push_back(std::move(child));
      }
    }
    return map;
  }

  std::optional<std::string> text(const Entry& e, std::string_view expected) {
    if (e.value.IsScalar() && !e.value.Scalar().empty()) return e.value.Scalar();
    error(e, cat("expected ", expected, ", got ", describe(e.value)));
    return std::nullopt;
  }

  std::optional<double> number(const Entry& e) {
    const std::optional<double> value = scalar_number(e.value);
    if (!value) {
      error(e, "expected a number, got " + describe(e.value));
    } else if (!std::isfinite(*value)) {
      error(e, "must be a finite number, got " + e.value.Scalar());
      return std::nullopt;
    }
    return value;
  }

  /// An integer in [low, high]; `high` = INT_MAX means no upper limit. 3.5 is not an integer.
  std::optional<int> integer_in(const Entry& e, std::int64_t low, std::int64_t high = INT_MAX) {
    const auto value = e.value.IsScalar() && !quoted(e.value) ? parse<std::int64_t>(e.value.Scalar()) : std::nullopt;
    if (!value) {
      const char* expected = scalar_number(e.value) ? "expected a whole number" : "expected an integer";
      error(e, cat(expected, ", got ", describe(e.value)));
      return std::nullopt;
    }
    if (*value < low || *value > high) {
      const std::string range = high == INT_MAX ? cat(">= ", std::to_string(low))
                                                : cat("from ", std::to_string(low), " to ", std::to_string(high));
      error(e, cat("must be an integer ", range, ", got ", e.value.Scalar()));
      return std::nullopt;
    }
    return static_cast<int>(*value);
  }

  /// A finite number for which `valid` holds; `range` says which values are allowed.
  template <class Valid>
  std::optional<double> number_where(const Entry& e, Valid valid, std::string_view range) {
    const auto value = number(e);
    if (value && !valid(*value)) {
      error(e, cat("must be ", range, ", got ", e.value.Scalar()));
      return std::nullopt;
    }
    return value;
  }

  std::optional<bool> boolean(const Entry& e) {
    if (e.value.IsScalar() && !quoted(e.value)) {
      const std::string v = ascii_lower(e.value.Scalar());
      if (v == "true" || v == "yes" || v == "on") return true;
      if (v == "false" || v == "no" || v == "off") return false;
    }
    error(e, "expected true or false, got " + describe(e.value));
    return std::nullopt;
  }

  /// The index of the value among `names`.
  std::optional<std::size_t> choice(const Entry& e, std::span<const std::string_view> names) {
    if (e.value.IsScalar()) {
      const auto it = std::find(names.begin(), names.end(), e.value.Scalar());
      if (it != names.end()) return static_cast<std::size_t>(it - names.begin());
    }
    error(e, cat("expected one of ", join(names), ", got ", describe(e.value)));
    return std::nullopt;
  }

  /// The enum value `e` names, as choice() above reads it.
  template <class E, std::size_t N>
  std::optional<E> choice(const Entry& e, const EnumNames<E, N>& table) {
    const auto names = table.names();
    const auto index = choice(e, names);
    if (!index) return std::nullopt;
    return table.entries[*index].value;
  }

  std::optional<geometry::Vec3> vec3(const Entry& e) {
    if (!e.value.IsSequence() || e.value.size() != 3) {
      const std::string got = e.value.IsSequence() ? "a list of " + std::to_string(e.value.size()) : describe(e.value);
      error(e, "expected a list of 3 numbers [x, y, z], got " + got);
      return std::nullopt;
    }
    geometry::Vec3 v;
    for (int i = 0; i < 3; ++i) {
      const auto value = number(e.item(static_cast<std::size_t>(i)));
      if (!value) return std::nullopt;
      v[i] = *value;
    }
    return v;
  }

 private:
  static std::optional<double> scalar_number(const YAML::Node& node) {
    if (!node.IsScalar() || quoted(node)) return std::nullopt;
    return parse<double>(node.Scalar());
  }

  Problems& problems_;
};

}  // namespace hotmesh::io::detail
