// hotmesh serve: reading the JSON bodies of API requests (see json_fields.hpp).
#include "service/json_fields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "service/api_error.hpp"

namespace hotmesh::app::serve {

namespace {

std::string type_name(const Json& value) { return value.type_name(); }

/// The value as JSON text, cut to a length that fits a message.
std::string shown(const Json& value) {
  std::string text = value.dump();
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

const Json* find(const Json& object, const char* key) {
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) return nullptr;
  return &*it;
}

[[noreturn]] void missing(const char* key) { throw ApiError::bad_request(fmt::format("{}: required", key)); }

}  // namespace

Json parse_object(std::string_view body) {
  // Writing a value (dump(), as messages and answers do) recurses once per level: a body of
  // "[[[[...": a few hundred kilobytes nested 100 000 deep overflowed the stack of the
  // thread serving it. The API's bodies nest 3 levels ({"axis": {"origin": [...]}}).
  const auto shallow = [](int depth, Json::parse_event_t event, const Json&) {
    const bool opens = event == Json::parse_event_t::object_start || event == Json::parse_event_t::array_start;
    if (opens && depth >= kMaxJsonDepth) {
      throw ApiError::bad_request(fmt::format("the body nests objects and arrays deeper than {} levels", kMaxJsonDepth));
    }
    return true;
  };
  Json value;
  try {
    value = Json::parse(body.begin(), body.end(), shallow);
  } catch (const Json::exception& e) {
    // e.what() reads "[json.exception.parse_error.101] parse error at line 1, column 5: ..." (or
    // out_of_range.406 for a number too large for a double)
    std::string what = e.what();
    const auto at = what.find("] ");
    if (at != std::string::npos) what = what.substr(at + 2);
    throw ApiError::bad_request("the body is not valid JSON: " + what);
  }
  if (!value.is_object()) {
    throw ApiError::bad_request("the body must be a JSON object ({...}), got " + type_name(value));
  }
  return value;
}

void refuse_unknown_keys(const Json& object, std::initializer_list<std::string_view> known) {
  for (const auto& item : object.items()) {
    if (std::find(known.begin(), known.end(), item.key()) == known.end()) {
      throw ApiError::bad_request(
          fmt::format("unknown key \"{}\" (known keys: {})", item.key(), fmt::join(known, ", ")));
    }
  }
}

std::string string_field(const Json& object, const char* key, std::optional<std::string> fallback) {
  const Json* value = find(object, key);
  if (!value) {
    if (!fallback) missing(key);
    return *fallback;
  }
  if (!value->is_string()) throw ApiError::bad_request(fmt::format("{}: expected a string, got {}", key, type_name(*value)));
  return value->get<std::string>();
}

long long integer_field(const Json& object, const char* key, long long lo, long long hi,
                        std::optional<long long> fallback) {
  const Json* value = find(object, key);
  if (!value) {
    if (!fallback) missing(key);
    return *fallback;
  }
  const std::string expected = fmt::format("{}: expected an integer from {} to {}", key, lo, hi);
  if (!value->is_number_integer()) throw ApiError::bad_request(expected + ", got " + shown(*value));
  const long long n = value->is_number_unsigned() && value->get<unsigned long long>() > static_cast<unsigned long long>(hi)
                          ? hi + 1
                          : value->get<long long>();
  if (n < lo || n > hi) throw ApiError::bad_request(expected + ", got " + shown(*value));
  return n;
}

double number_field(const Json& object, const char* key, double lo, double hi, std::optional<double> fallback) {
  const Json* value = find(object, key);
  if (!value) {
    if (!fallback) missing(key);
    return *fallback;
  }
  const std::string expected = fmt::format("{}: expected a number from {:g} to {:g}", key, lo, hi);
  if (!value->is_number()) throw ApiError::bad_request(expected + ", got " + shown(*value));
  const double x = value->get<double>();
  if (!std::isfinite(x) || x < lo || x > hi) throw ApiError::bad_request(expected + ", got " + shown(*value));
  return x;
}

bool bool_field(const Json& object, const char* key, bool fallback) {
  const Json* value = find(object, key);
  if (!value) return fallback;
  if (!value->is_boolean()) throw ApiError::bad_request(fmt::format("{}: expected true or false, got {}", key, shown(*value)));
  return value->get<bool>();
}

std::vector<int> face_list_field(const Json& object, const char* key, std::size_t max_count, std::string_view word) {
  const Json* value = find(object, key);
  if (!value) {
    throw ApiError::bad_request(fmt::format("{}: required: the ids of the boundary's {}s, e.g. [1, 2]", key, word));
  }
  const std::string expected = fmt::format("{}: expected an array of {} ids (integers from 1), e.g. [1, 2]", key, word);
  if (!value->is_array() || value->empty()) throw ApiError::bad_request(expected + ", got " + shown(*value));
  if (value->size() > max_count) {
    throw ApiError::bad_request(fmt::format("{}: at most {} {}s, got {}", key, max_count, word, value->size()));
  }
  std::vector<int> ids;
  std::set<int> seen;
  for (const Json& item : *value) {
    if (!item.is_number_integer() || item.get<long long>() < 1 || item.get<long long>() > 1'000'000'000) {
      throw ApiError::bad_request(expected + ", got " + shown(item) + " in it");
    }
    const int id = item.get<int>();
    if (!seen.insert(id).second) throw ApiError::bad_request(fmt::format("{}: {} {} is listed twice", key, word, id));
    ids.push_back(id);
  }
  return ids;
}

geometry::Vec3 vec3_value(const Json& value, const std::string& what) {
  if (!value.is_array() || value.size() != 3 ||
      !std::all_of(value.begin(), value.end(), [](const Json& x) { return x.is_number(); })) {
    throw ApiError::bad_request(fmt::format("{}: expected three numbers [x, y, z], got {}", what, shown(value)));
  }
  const geometry::Vec3 v{value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
    throw ApiError::bad_request(fmt::format("{}: the numbers must be finite", what));
  }
  return v;
}

std::optional<geometry::Axis> axis_field(const Json& object, const char* key) {
  const Json* value = find(object, key);
  if (!value) return std::nullopt;
  if (!value->is_object() || !value->contains("origin") || !value->contains("direction") || value->size() != 2) {
    throw ApiError::bad_request(fmt::format(
        "{}: expected {{\"origin\": [x, y, z], \"direction\": [dx, dy, dz]}}, got {}", key, shown(*value)));
  }
  const geometry::Vec3 origin = vec3_value((*value)["origin"], std::string(key) + ".origin");
  const geometry::Vec3 direction = vec3_value((*value)["direction"], std::string(key) + ".direction");
  try {
    return geometry::Axis(origin, direction);
  } catch (const std::invalid_argument& e) {
    throw ApiError::bad_request(fmt::format("{}: {}", key, e.what()));
  }
}

}  // namespace hotmesh::app::serve
