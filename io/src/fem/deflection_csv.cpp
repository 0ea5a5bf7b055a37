// hotmesh io: reader of FEM deflection tables (CSV). The header names the columns in any
// order: x,y,dx,dy (planar), x,y,z,dx,dy,dz (cartesian) or r,z,dr,dz (meridional), plus an
// optional integer "id". Numbers are parsed with std::from_chars, so the reading does not
// depend on the locale. The first problem found throws an InputError "<source>:<line>: ...".
#include "hotmesh/io/deflection_csv.hpp"

#include "hotmesh/mesh/validate.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <system_error>
#include <unordered_map>
#include <vector>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/core/text.hpp"
#include "hotmesh/io/atomic_file.hpp"

namespace hotmesh::io {
namespace {

using geometry::SampleFrame;
using geometry::Vec3;

constexpr std::string_view kExpectedSets =
    "expected x,y,dx,dy (planar), x,y,z,dx,dy,dz (cartesian) or r,z,dr,dz (meridional), "
    "plus an optional id";

/// The columns a table may have. Coordinates and deflections index Vec3 components.
enum class Column { x, y, z, r, dx, dy, dz, dr, id };

struct ColumnName {
  std::string_view name;
  Column column;
};
constexpr std::array<ColumnName, 9> kColumns{{{"x", Column::x},
                                              {"y", Column::y},
                                              {"z", Column::z},
                                              {"r", Column::r},
                                              {"dx", Column::dx},
                                              {"dy", Column::dy},
                                              {"dz", Column::dz},
                                              {"dr", Column::dr},
                                              {"id", Column::id}}};

std::string_view name_of(Column c) {
  for (const auto& entry : kColumns) {
    if (entry.column == c) return entry.name;
  }
  return "?";
}

/// The columns of each frame, in the order the documentation lists them.
std::vector<Column> columns_of(SampleFrame frame) {
  switch (frame) {
    case SampleFrame::planar: return {Column::x, Column::y, Column::dx, Column::dy};
    case SampleFrame::cartesian:
      return {Column::x, Column::y, Column::z, Column::dx, Column::dy, Column::dz};
    case SampleFrame::meridional: return {Column::r, Column::z, Column::dr, Column::dz};
  }
  return {};
}

std::string join_names(const std::vector<Column>& columns) {
  std::string text;
  for (const Column c : columns) {
    if (!text.empty()) text.push_back(',');
    text.append(name_of(c));
  }
  return text;
}

/// Concatenates strings (GCC 12 warns wrongly about chains of std::string operator+).
template <class... Parts>
std::string cat(const Parts&... parts) {
  std::string text;
  (text.append(std::string_view(parts)), ...);
  return text;
}

/// A number as written in a table: what std::from_chars accepts, plus a leading '+'.
/// Values too small for a double read as 0; values too large as infinity (then rejected).
std::optional<double> parse_double(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || end != text.data() + text.size()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) {
    const std::size_t e = text.find_first_of("eE");
    const bool underflow = e != std::string_view::npos && e + 1 < text.size() && text[e + 1] == '-';
    const double sign = text.front() == '-' ? -1.0 : 1.0;
    return underflow ? sign * 0.0 : sign * HUGE_VAL;
  }
  if (ec != std::errc()) return std::nullopt;
  return value;
}

std::optional<std::int64_t> parse_integer(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

/// The header: which column each field holds and the frame they make up.
struct Header {
  std::vector<Column> fields;
  SampleFrame frame = SampleFrame::cartesian;
};

class TableReader {
 public:
  explicit TableReader(std::string_view source) : source_(source) {}

  [[noreturn]] void fail(std::size_t line, const std::string& message) const {
    throw InputError::at(source_, line, message);
  }

  Header read_header(std::string_view text, std::size_t line) const {
    Header header;
    std::array<bool, kColumns.size()> seen{};
    for (const std::string_view field : split_fields(text)) {
      if (field.empty()) fail(line, "empty column name in the header; " + std::string(kExpectedSets));
      if (parse_double(field)) {
        fail(line, "the first line that is not a comment holds values, not column names; "
                   "add a header line such as x,y,dx,dy (" + std::string(kExpectedSets) + ")");
      }
      const std::string name = ascii_lower(field);
      const ColumnName* known = nullptr;
      for (const auto& entry : kColumns) {
        if (entry.name == name) known = &entry;
      }
      if (known == nullptr) fail(line, "unknown column '" + std::string(field) + "'; " + std::string(kExpectedSets));
      bool& already = seen[static_cast<std::size_t>(known->column)];
      if (already) fail(line, "column '" + name + "' appears twice in the header");
      already = true;
      header.fields.push_back(known->column);
    }
    const auto has = [&](Column c) { return seen[static_cast<std::size_t>(c)]; };

    // The frame follows from the columns that only one set has; z and dz are shared.
    const bool meridional = has(Column::r) || has(Column::dr);
    std::vector<Column> cartesian_only;
    for (const Column c : {Column::x, Column::y, Column::dx, Column::dy}) {
      if (has(c)) cartesian_only.push_back(c);
    }
    if (meridional && !cartesian_only.empty()) {
      const Column m = has(Column::r) ? Column::r : Column::dr;
      fail(line, "the header mixes column sets: '" + std::string(name_of(m)) + "' is meridional (r,z,dr,dz) but '" +
                     std::string(name_of(cartesian_only.front())) +
                     "' is not; use one set: " + std::string(kExpectedSets));
    }
    if (meridional) {
      header.frame = SampleFrame::meridional;
    } else if (!cartesian_only.empty()) {
      header.frame = (has(Column::z) || has(Column::dz)) ? SampleFrame::cartesian : SampleFrame::planar;
    } else {
      fail(line, "the header has no coordinate columns; " + std::string(kExpectedSets));
    }
    const std::vector<Column> expected = columns_of(header.frame);
    std::vector<Column> missing;
    for (const Column c : expected) {
      if (!has(c)) missing.push_back(c);
    }
    if (!missing.empty()) {
      fail(line, std::string(missing.size() == 1 ? "missing column '" : "missing columns '") + join_names(missing) +
                     "': a " + geometry::to_string(header.frame) + " table has columns " + join_names(expected) +
                     " (plus an optional id)");
    }
    return header;
  }

  void read_row(const Header& header, std::string_view text, std::size_t line, geometry::DeflectionSamples& out,
                std::unordered_map<std::int64_t, std::size_t>& id_lines) const {
    const std::vector<std::string_view> fields = split_fields(text);
    if (fields.size() != header.fields.size()) {
      fail(line, "the row has " + std::to_string(fields.size()) + " fields, the header " +
                     std::to_string(header.fields.size()) + " (" + header_names(header) + ")");
    }
    Vec3 point;
    Vec3 deflection;
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const Column column = header.fields[i];
      const std::string_view field = fields[i];
      const std::string_view name = name_of(column);
      if (field.empty()) fail(line, cat("empty value in column '", name, "'"));
      if (column == Column::id) {
        const auto id = parse_integer(field);
        if (!id) fail(line, cat("'", field, "' in column 'id' is not an integer node number"));
        const auto [it, inserted] = id_lines.emplace(*id, line);
        if (!inserted) {
          fail(line, cat("duplicate id ", std::to_string(*id), " (first on line ", std::to_string(it->second), ")"));
        }
        out.ids.push_back(*id);
        continue;
      }
      const auto value = parse_double(field);
      if (!value) fail(line, cat("'", field, "' in column '", name, "' is not a number"));
      if (!std::isfinite(*value)) fail(line, cat("'", field, "' in column '", name, "' is not a finite number"));
      if (std::abs(*value) > mesh::kLargestCoordinate) {
        fail(line, cat("'", field, "' in column '", name, "' is beyond 1e30, the largest coordinate hotmesh moves "
                       "meshes at; is the table in another unit?"));
      }
      if (column == Column::r && *value < 0.0) {
        fail(line, cat("negative radius ", field, " in column 'r'; r is a distance from the axis, r >= 0"));
      }
      place(header.frame, column, *value, point, deflection);
    }
    out.points.push_back(point);
    out.deflections.push_back(deflection);
    out.lines.push_back(line);
  }

 private:
  static std::string header_names(const Header& header) {
    return join_names(header.fields);
  }

  /// Stores a value where its frame keeps it: (x, y, 0), (x, y, z) or (r, z, 0).
  static void place(SampleFrame frame, Column column, double value, Vec3& point, Vec3& deflection) {
    const bool meridional = frame == SampleFrame::meridional;
    switch (column) {
      case Column::x: point.x = value; break;
      case Column::y: point.y = value; break;
      case Column::r: point.x = value; break;
      case Column::z: (meridional ? point.y : point.z) = value; break;
      case Column::dx: deflection.x = value; break;
      case Column::dy: deflection.y = value; break;
      case Column::dr: deflection.x = value; break;
      case Column::dz: (meridional ? deflection.y : deflection.z) = value; break;
      case Column::id: break;
    }
  }

  std::string_view source_;
};

}  // namespace

geometry::DeflectionSamples parse_deflection_csv(std::string_view content, std::string_view source) {
  const TableReader reader(source);
  geometry::DeflectionSamples samples;
  samples.source = std::string(source);

  constexpr std::string_view kBom = "\xEF\xBB\xBF";  // spreadsheets often write one
  if (content.substr(0, kBom.size()) == kBom) content.remove_prefix(kBom.size());

  std::optional<Header> header;
  std::size_t header_line = 0;
  std::unordered_map<std::int64_t, std::size_t> id_lines;
  std::size_t line_number = 0;
  while (!content.empty()) {
    const std::size_t eol = content.find('\n');
    std::string_view line = content.substr(0, eol);
    content.remove_prefix(eol == std::string_view::npos ? content.size() : eol + 1);
    ++line_number;
    line = trim(line.substr(0, line.find('#')));
    if (line.empty()) continue;
    if (!header) {
      header = reader.read_header(line, line_number);
      header_line = line_number;
      continue;
    }
    reader.read_row(*header, line, line_number, samples, id_lines);
  }

  if (!header) {
    throw InputError::in(source, "no header line (the table is empty or only comments); " +
                                     std::string(kExpectedSets));
  }
  if (samples.points.empty()) reader.fail(header_line, "the table has a header but no data rows");
  samples.frame = header->frame;
  return samples;
}

geometry::DeflectionSamples read_deflection_csv(const std::filesystem::path& path) {
  return parse_deflection_csv(read_file(path), path.string());
}

std::string format_deflection_csv(const geometry::DeflectionSamples& samples) {
  const bool ids = samples.ids.size() == samples.size();
  const std::size_t components = samples.frame == SampleFrame::cartesian ? 3 : 2;
  std::string text = ids ? "id," : "";
  text.append(join_names(columns_of(samples.frame))).push_back('\n');
  const auto append = [&text](double v, char after) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);  // shortest text that reads back the same
    text.append(buffer, result.ptr).push_back(after);
  };
  for (std::size_t j = 0; j < samples.size(); ++j) {
    if (ids) text.append(std::to_string(samples.ids[j])).push_back(',');
    for (std::size_t k = 0; k < components; ++k) append(samples.points[j][static_cast<int>(k)], ',');
    for (std::size_t k = 0; k < components; ++k) {
      append(samples.deflections[j][static_cast<int>(k)], k + 1 == components ? '\n' : ',');
    }
  }
  return text;
}

}  // namespace hotmesh::io
