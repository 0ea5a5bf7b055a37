// hotmesh io: reader of CalculiX .frd results files (the CalculiX GraphiX format), ASCII and
// binary. An .frd file is a sequence of blocks, each opened by a text header line whose
// first five columns hold a key:
//     1C / 1U / 1P   model and parameter headers ("1PSTEP  <block> <increment> <step>")
//     2C             nodes:    numnod in columns 25-36, format in column 74
//     3C             elements: numelem in columns 25-36, format in column 74
//   100C             a nodal result: step time in columns 13-24, numnod in 25-36, format in
//                    74-75; then a " -4  NAME  ncomps" line and one " -5" line per component
//                    (a component whose "iexist" field, columns 34-38, is 1 is computed by
//                    the viewer and not stored)
//   9999             end of file
// Format 0 and 1 are ASCII records (" -1" + node number in 5 or 10 columns + values in 12
// columns each, six to a line, " -2" continuation lines), closed by a " -3" line. Format 2
// is binary with 4-byte floats, 3 binary with 8-byte doubles: numnod records of a 4-byte
// node number and the stored components, little-endian, and no " -3" line. ccx writes ASCII
// for *NODE FILE and binary for *NODE OUTPUT; its binary node block is format 3.
// The numbers hotmesh uses, node coordinates, step times, DISP and NDTEMP values, must be
// finite ("nan" and "inf" read as numbers, and would pass every comparison made with them).
#include "hotmesh/io/calculix.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "fem/calculix_text.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"

namespace hotmesh::io {
namespace {

using detail::field_double;
using detail::field_integer;
using geometry::Vec3;

/// The nodes of each element type of the .frd format (1 he8 ... 12 be3).
constexpr std::array<int, 13> kFrdElementNodes{0, 8, 6, 4, 20, 15, 10, 3, 6, 4, 8, 2, 3};

/// Reads the file line by line, with binary payloads taken by size between the lines.
class FrdScanner {
 public:
  FrdScanner(std::string_view data, std::string_view source) : data_(data), source_(source) {}

  bool at_end() const { return pos_ >= data_.size(); }
  std::size_t line() const { return line_; }

  std::string_view next_line() {
    const std::size_t eol = data_.find('\n', pos_);
    const std::size_t end = eol == std::string_view::npos ? data_.size() : eol;
    std::string_view text = data_.substr(pos_, end - pos_);
    pos_ = eol == std::string_view::npos ? data_.size() : eol + 1;
    ++line_;
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    return text;
  }

  /// The next `count` bytes of a binary block; `what` says what was expected if they are missing.
  std::string_view bytes(std::size_t count, std::string_view what) {
    if (data_.size() - pos_ < count) {
      fail(std::string(what) + ": the file ends " + std::to_string(data_.size() - pos_) + " bytes into the " +
           std::to_string(count) + " it needs; it is truncated (did ccx finish writing it?)");
    }
    const std::string_view out = data_.substr(pos_, count);
    pos_ += count;
    return out;
  }

  /// Throws "<source>:<line>: message"; a problem on a last line cut short says the file is truncated.
  [[noreturn]] void fail(const std::string& message) const {
    const bool cut = at_end() && !data_.empty() && data_.back() != '\n';
    throw InputError::at(source_, line_, message + (cut ? "; the file ends inside this line: it is truncated "
                                                          "(did ccx finish writing it?)"
                                                        : ""));
  }

 private:
  std::string_view data_;
  std::string_view source_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

template <class T>
T load(std::string_view bytes, std::size_t offset) {
  T value{};
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

std::string_view columns(std::string_view line, std::size_t first, std::size_t count) {
  return first >= line.size() ? std::string_view() : line.substr(first, count);
}

/// The format field of a block header (0, 1 ASCII; 2, 3 binary); blank reads as 1.
int block_format(const FrdScanner& in, std::string_view field) {
  field = trim(field);
  if (field.empty()) return 1;
  const auto format = field_integer(field);
  if (!format || *format < 0 || *format > 3) {
    in.fail("unknown block format '" + std::string(field) + "'; expected 0 or 1 (ASCII), 2 or 3 (binary)");
  }
  return static_cast<int>(*format);
}

std::int64_t header_count(const FrdScanner& in, std::string_view line, std::string_view what) {
  const auto count = field_integer(columns(line, 24, 12));
  if (!count || *count < 0) in.fail("the " + std::string(what) + " header has no count in columns 25-36");
  return *count;
}

/// An ASCII record: " -1", the node number (5 or 10 columns), then values of 12 columns; or
/// its continuation " -2", whose node columns are blank, with the values after them.
struct AsciiRecord {
  std::int64_t node = 0;
  std::vector<double> values;
};

enum class RecordKind { first, continuation };

AsciiRecord ascii_record(const FrdScanner& in, std::string_view line, int format, RecordKind kind = RecordKind::first) {
  const std::size_t width = format == 0 ? 5 : 10;
  AsciiRecord record;
  if (kind == RecordKind::first) {
    const auto node = field_integer(columns(line, 3, width));
    if (!node) in.fail("expected a node number in columns 4-" + std::to_string(3 + width) + ", got '" +
                       std::string(columns(line, 3, width)) + "'");
    record.node = *node;
  } else if (!trim(columns(line, 3, width)).empty()) {
    in.fail("a ' -2' continuation record has blank columns 4-" + std::to_string(3 + width) + ", got '" +
            std::string(columns(line, 3, width)) + "'");
  }
  for (std::size_t at = 3 + width; at < line.size(); at += 12) {
    const std::string_view text = columns(line, at, 12);
    if (trim(text).empty()) break;
    const auto value = field_double(text);
    if (!value) in.fail("'" + std::string(trim(text)) + "' is not a number");
    record.values.push_back(*value);
  }
  return record;
}

bool is_end_of_block(std::string_view line) { return line.starts_with(" -3"); }

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string text_of(const Vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", v.x, v.y, v.z);
  return text;
}

/// The result blocks whose values hotmesh uses: they must hold finite numbers.
bool is_used(std::string_view name) { return name == "DISP" || name == "NDTEMP"; }

class FrdParser {
 public:
  FrdParser(std::string_view content, std::string_view source) : in_(content, source) {
    results_.source = std::string(source);
  }

  FrdResults parse() {
    bool ended = false;
    while (!in_.at_end() && !ended) {
      const std::string_view line = in_.next_line();
      if (trim(line).empty()) continue;
      const std::string_view key = trim(columns(line, 0, 5));
      const char code = line.size() > 5 ? line[5] : ' ';
      if (key == "9999") {
        ended = true;
      } else if (key == "1" && columns(line, 5, std::string_view::npos).starts_with("PSTEP")) {
        read_step(line);
      } else if (key == "1") {
        continue;  // model and user headers
      } else if (key == "2" && code == 'C') {
        read_nodes(line);
      } else if (key == "3" && code == 'C') {
        read_elements(line);
      } else if (key == "100" && code == 'C') {
        read_result(line);
      } else {
        in_.fail("unexpected line '" + std::string(line.substr(0, 40)) +
                 "': expected a block header (1C, 1U, 1P, 2C, 3C, 100C) or the end line 9999");
      }
    }
    if (!ended) {
      in_.fail("the file ends before its end line 9999: it is truncated (did ccx finish writing it?)");
    }
    return std::move(results_);
  }

 private:
  /// "    1PSTEP   <block>   <increment>   <step>".
  void read_step(std::string_view line) {
    std::vector<std::int64_t> numbers;
    std::string_view rest = columns(line, 11, std::string_view::npos);
    while (!(rest = trim(rest)).empty()) {
      const std::size_t end = std::min(rest.find(' '), rest.size());
      if (const auto n = field_integer(rest.substr(0, end))) numbers.push_back(*n);
      rest.remove_prefix(end);
    }
    if (numbers.size() < 3) in_.fail("a PSTEP line holds three numbers: block, increment, step");
    increment_ = static_cast<int>(numbers[1]);
    step_ = static_cast<int>(numbers[2]);
  }

  void read_nodes(std::string_view header) {
    const std::int64_t count = header_count(in_, header, "node block");
    const int format = block_format(in_, columns(header, 36, 64));
    if (format >= 2) {
      results_.binary = true;
      const std::size_t size = format == 2 ? 4 + 3 * 4 : 4 + 3 * 8;
      for (std::int64_t i = 0; i < count; ++i) {
        const std::string_view record = in_.bytes(size, "node " + std::to_string(i + 1) + " of the binary node block");
        Vec3 x;
        for (int k = 0; k < 3; ++k) {
          x[k] = format == 2 ? static_cast<double>(load<float>(record, 4 + 4 * static_cast<std::size_t>(k)))
                             : load<double>(record, 4 + 8 * static_cast<std::size_t>(k));
        }
        const std::int32_t node = load<std::int32_t>(record, 0);
        if (!finite(x)) {
          in_.fail("node " + std::to_string(node) + " (record " + std::to_string(i + 1) + " of the binary node block "
                   "after this line) is at " + text_of(x) + ": coordinates must be finite numbers");
        }
        results_.nodes[node] = x;
      }
      return;
    }
    for (std::string_view line = next_record_line("node block"); !is_end_of_block(line);
         line = next_record_line("node block")) {
      const AsciiRecord record = ascii_record(in_, line, format);
      if (record.values.size() < 3) in_.fail("a node record needs three coordinates");
      const Vec3 x{record.values[0], record.values[1], record.values[2]};
      if (!finite(x)) in_.fail("node " + std::to_string(record.node) + " is at " + text_of(x) + ": coordinates must be finite numbers");
      results_.nodes[record.node] = x;
    }
  }

  /// The element block: each element's number and nodes, as the .frd writes them (for beams
  /// and shells, the 3D elements ccx expanded them into).
  void read_elements(std::string_view header) {
    const std::int64_t count = header_count(in_, header, "element block");
    const int format = block_format(in_, columns(header, 36, 64));
    if (format >= 2) {
      read_binary_elements(count);
      return;
    }
    const std::size_t width = format == 0 ? 5 : 10;
    std::int64_t number = 0;
    std::vector<std::int64_t>* nodes = nullptr;
    std::size_t type_nodes = 0;
    const auto require_complete = [&] {
      if (nodes != nullptr && nodes->size() != type_nodes) {
        in_.fail("element " + std::to_string(number) + " has " + std::to_string(nodes->size()) + " nodes, its type " +
                 std::to_string(type_nodes));
      }
    };
    for (std::string_view line = next_record_line("element block"); !is_end_of_block(line);
         line = next_record_line("element block")) {
      if (line.starts_with(" -1")) {
        require_complete();
        const auto element = field_integer(columns(line, 3, width));
        if (!element) in_.fail("expected an element number in columns 4-" + std::to_string(3 + width));
        number = *element;
        type_nodes = element_nodes(field_integer(columns(line, 3 + width, 5)).value_or(0), "element " + std::to_string(number));
        nodes = &results_.elements[number];
        nodes->clear();
      } else if (line.starts_with(" -2") && nodes != nullptr) {
        for (std::size_t at = 3; at < line.size() && !trim(columns(line, at, width)).empty(); at += width) {
          const auto node = field_integer(columns(line, at, width));
          if (!node) in_.fail("'" + std::string(trim(columns(line, at, width))) + "' is not a node number");
          nodes->push_back(*node);
          if (nodes->size() > type_nodes) require_complete();
        }
      } else {
        in_.fail("expected an element's ' -1' line or its ' -2' lines of nodes in the element block");
      }
    }
    require_complete();
  }

  /// The node count of an element of .frd type `type`; `what` names it if the type is unknown.
  std::size_t element_nodes(std::int64_t type, const std::string& what) const {
    if (type < 1 || type >= static_cast<std::int64_t>(kFrdElementNodes.size())) {
      in_.fail(what + " has the unknown element type " + std::to_string(type) + "; the .frd types are 1 to 12");
    }
    return static_cast<std::size_t>(kFrdElementNodes[static_cast<std::size_t>(type)]);
  }

  /// Binary elements: number, type, group, material (4-byte integers), then the nodes.
  void read_binary_elements(std::int64_t count) {
    results_.binary = true;
    for (std::int64_t i = 0; i < count; ++i) {
      const std::string what = "element " + std::to_string(i + 1) + " of the binary element block";
      const std::string_view head = in_.bytes(16, what);
      const std::size_t type_nodes = element_nodes(load<std::int32_t>(head, 4), what);
      const std::string_view nodes = in_.bytes(4 * type_nodes, what);
      std::vector<std::int64_t>& out = results_.elements[load<std::int32_t>(head, 0)];
      out.clear();
      for (std::size_t k = 0; k < type_nodes; ++k) out.push_back(load<std::int32_t>(nodes, 4 * k));
    }
  }

  void read_result(std::string_view header) {
    FrdBlock block;
    block.line = in_.line();
    // The step from the PSTEP line before the block; without one, the header's numstp field.
    block.step = step_ > 0 ? step_ : static_cast<int>(field_integer(columns(header, 58, 5)).value_or(0));
    block.increment = increment_;
    const auto time = field_double(columns(header, 12, 12));
    if (!time) in_.fail("the result header has no step time in columns 13-24");
    if (!std::isfinite(*time)) in_.fail("the step time in columns 13-24 is not a finite number");
    block.time = *time;
    const std::int64_t count = header_count(in_, header, "result block");
    const int format = block_format(in_, columns(header, 73, 2));

    const std::string_view name_line = in_.next_line();
    if (!name_line.starts_with(" -4")) in_.fail("expected the ' -4' line naming the result after its header");
    block.name = std::string(trim(columns(name_line, 5, 8)));
    const auto components = field_integer(columns(name_line, 13, 5));
    if (!components || *components < 1) in_.fail("the ' -4' line gives no component count in columns 14-18");
    int stored = 0;
    for (std::int64_t k = 0; k < *components; ++k) {
      const std::string_view line = in_.next_line();
      if (!line.starts_with(" -5")) in_.fail("expected a ' -5' component line of " + block.name);
      stored += field_integer(columns(line, 33, 5)).value_or(0) == 1 ? 0 : 1;
    }
    if (format >= 2) {
      results_.binary = true;
      read_binary_values(block, count, stored, format);
    } else {
      read_ascii_values(block, stored, format);
    }
    results_.blocks.push_back(std::move(block));
  }

  void read_binary_values(FrdBlock& block, std::int64_t count, int stored, int format) {
    const std::size_t width = format == 2 ? 4 : 8;
    for (std::int64_t i = 0; i < count; ++i) {
      const std::string_view record =
          in_.bytes(4 + width * static_cast<std::size_t>(stored),
                    "node " + std::to_string(i + 1) + " of " + std::to_string(count) + " of the binary " + block.name +
                        " block (line " + std::to_string(block.line) + ")");
      Vec3 v;
      for (int k = 0; k < std::min(stored, 3); ++k) {
        const std::size_t at = 4 + width * static_cast<std::size_t>(k);
        v[k] = format == 2 ? static_cast<double>(load<float>(record, at)) : load<double>(record, at);
      }
      if (is_used(block.name) && !finite(v)) {
        in_.fail("node " + std::to_string(load<std::int32_t>(record, 0)) + " (record " + std::to_string(i + 1) +
                 " of the binary " + block.name + " block after this line) has " + text_of(v) + ": " + block.name +
                 " values must be finite numbers");
      }
      block.nodes.push_back(load<std::int32_t>(record, 0));
      block.values.push_back(v);
    }
  }

  void read_ascii_values(FrdBlock& block, int stored, int format) {
    const std::string what = block.name + " block";
    std::string_view line = next_record_line(what);
    while (!is_end_of_block(line)) {
      if (!line.starts_with(" -1")) in_.fail("expected a ' -1' node record of the " + what);
      AsciiRecord record = ascii_record(in_, line, format);
      require_finite(block.name, record);
      line = next_record_line(what);
      while (line.starts_with(" -2")) {  // more than six components
        AsciiRecord more = ascii_record(in_, line, format, RecordKind::continuation);
        more.node = record.node;
        require_finite(block.name, more);
        record.values.insert(record.values.end(), more.values.begin(), more.values.end());
        line = next_record_line(what);
      }
      if (record.values.size() != static_cast<std::size_t>(stored)) {
        in_.fail("node " + std::to_string(record.node) + " of the " + what + " has " +
                 std::to_string(record.values.size()) + " values, the block " + std::to_string(stored));
      }
      Vec3 v;
      for (std::size_t k = 0; k < std::min<std::size_t>(record.values.size(), 3); ++k) v[static_cast<int>(k)] = record.values[k];
      block.nodes.push_back(record.node);
      block.values.push_back(v);
    }
  }

  /// The values of a record just read, of a block hotmesh uses, are finite numbers.
  void require_finite(const std::string& block, const AsciiRecord& record) const {
    if (!is_used(block)) return;
    for (const double value : record.values) {
      if (!std::isfinite(value)) {
        in_.fail("node " + std::to_string(record.node) + " has the value " + std::to_string(value) + " in the " + block +
                 " block: its values must be finite numbers");
      }
    }
  }

  /// The next line of an ASCII block; the file must not end before the block's " -3".
  std::string_view next_record_line(std::string_view what) {
    if (in_.at_end()) {
      in_.fail("the file ends inside the " + std::string(what) + ", before its ' -3' line: it is truncated "
               "(did ccx finish writing it?)");
    }
    return in_.next_line();
  }

  FrdScanner in_;
  FrdResults results_;
  int step_ = 0;
  int increment_ = 0;
};

std::string step_list(const std::vector<const FrdBlock*>& blocks) {
  std::string text;
  for (const FrdBlock* b : blocks) {
    char time[32];
    std::snprintf(time, sizeof time, "%g", b->time);
    text += (text.empty() ? "" : ", ") + std::string("step ") + std::to_string(b->step) + " increment " +
            std::to_string(b->increment) + " (time " + time + ")";
  }
  return text;
}

}  // namespace

std::vector<const FrdBlock*> FrdResults::displacements() const {
  std::vector<const FrdBlock*> out;
  for (const FrdBlock& b : blocks) {
    if (b.name == "DISP") out.push_back(&b);
  }
  return out;
}

const FrdBlock* FrdResults::companion(const FrdBlock& at, std::string_view name) const {
  for (const FrdBlock& b : blocks) {
    if (b.name == name && b.step == at.step && b.increment == at.increment && b.time == at.time) return &b;
  }
  return nullptr;
}

FrdResults parse_frd(std::string_view content, std::string_view source) {
  return FrdParser(content, source).parse();
}

FrdResults read_frd(const std::filesystem::path& path) { return parse_frd(read_file(path), path.string()); }

const FrdBlock& choose_displacements(const FrdResults& results, const FrdStepChoice& choice) {
  const std::vector<const FrdBlock*> blocks = results.displacements();
  if (blocks.empty()) {
    throw InputError::in(results.source, "no DISP (displacement) block; ask ccx for displacements with "
                                         "`*NODE FILE` (ASCII) or `*NODE OUTPUT` (binary) and the line `U`");
  }
  const FrdBlock* chosen = nullptr;
  for (const FrdBlock* b : blocks) {
    const bool step_ok = !choice.step || b->step == *choice.step;
    const bool time_ok = !choice.time || std::abs(b->time - *choice.time) <= 1e-9 * std::max(1.0, std::abs(*choice.time));
    if (step_ok && time_ok) chosen = b;
  }
  if (chosen == nullptr) {
    std::string wanted = choice.step ? "step " + std::to_string(*choice.step) : std::string();
    if (choice.time) {
      char time[32];
      std::snprintf(time, sizeof time, "%g", *choice.time);
      wanted += (wanted.empty() ? "time " : " at time ") + std::string(time);
    }
    throw InputError::in(results.source, "no displacements at " + wanted + "; its DISP blocks are at " +
                                             step_list(blocks));
  }
  return *chosen;
}

}  // namespace hotmesh::io
