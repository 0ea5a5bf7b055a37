// hotmesh serve: reading the JSON bodies of API requests. Every accessor names the key and
// says what it expected, so a client sees "degree: expected an integer from 1 to 5, got 7"
// rather than a parser's message; unknown keys are refused so typos do not pass unnoticed.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hotmesh/geometry/axis.hpp"

namespace hotmesh::app::serve {

using Json = nlohmann::json;

/// How deep objects and arrays may nest in a request body.
inline constexpr int kMaxJsonDepth = 32;

/// The body as a JSON object. ApiError 400 if it is not valid JSON, not an object, or nests
/// deeper than kMaxJsonDepth.
Json parse_object(std::string_view body);

/// ApiError 400 naming the first key of `object` that is not in `known`.
void refuse_unknown_keys(const Json& object, std::initializer_list<std::string_view> known);

/// A string; `fallback` if the key is absent (nullopt: required).
std::string string_field(const Json& object, const char* key, std::optional<std::string> fallback = std::nullopt);
/// An integer in [lo, hi].
long long integer_field(const Json& object, const char* key, long long lo, long long hi,
                        std::optional<long long> fallback = std::nullopt);
/// A finite number in [lo, hi].
double number_field(const Json& object, const char* key, double lo, double hi,
                    std::optional<double> fallback = std::nullopt);
bool bool_field(const Json& object, const char* key, bool fallback);
/// A non-empty array of positive integers (face ids, or the ids of what `word` names: "edge"),
/// at most `max_count`, without repeats.
std::vector<int> face_list_field(const Json& object, const char* key, std::size_t max_count,
                                 std::string_view word = "face");
/// {"origin": [x, y, z], "direction": [dx, dy, dz]}, or absent/null.
std::optional<geometry::Axis> axis_field(const Json& object, const char* key);

/// [x, y, z] of an axis-like JSON array, naming `what` in messages.
geometry::Vec3 vec3_value(const Json& value, const std::string& what);

}  // namespace hotmesh::app::serve
