// hotmesh core: the names of an enum's values in one table. to_string, the parsers of the
// case file, restart files and the service's requests all read the table, so a name cannot
// drift from its value and no value is tied to a name by its position in a list.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace hotmesh {

template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

template <class E, std::size_t N>
struct EnumNames {
  std::array<EnumName<E>, N> entries;

  /// The name of `value`; "?" for a value outside the enum (a damaged or cast value).
  constexpr std::string_view name(E value) const {
    for (const EnumName<E>& e : entries) {
      if (e.value == value) return e.name;
    }
    return "?";
  }

  /// The value named `text`, if any.
  constexpr std::optional<E> parse(std::string_view text) const {
    for (const EnumName<E>& e : entries) {
      if (e.name == text) return e.value;
    }
    return std::nullopt;
  }

  /// Every name, in the table's order (for "expected one of ..." messages).
  constexpr std::array<std::string_view, N> names() const {
    std::array<std::string_view, N> result{};
    for (std::size_t i = 0; i < N; ++i) result[i] = entries[i].name;
    return result;
  }
};

}  // namespace hotmesh
