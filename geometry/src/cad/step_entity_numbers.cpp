// hotmesh geometry (internal): repeated STEP entity numbers (see step_entity_numbers.hpp).
#include "cad/step_entity_numbers.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::geometry::detail {

namespace {

/// An instance definition: its number and the line it starts on.
struct Definition {
  std::uint64_t number;
  std::size_t line;
};

/// More digits than this is not a number a CAD system writes: OpenCASCADE's parser judges it.
constexpr int kMaxDigits = 18;

/// The exchange structure's lexical states (ISO 10303-21, clause 5): a statement ends at a
/// ';' outside strings ('...', with '' for a quote) and comments (/* ... */); an instance is
/// defined by a statement that starts with "#N =".
class DefinitionScanner {
 public:
  void feed(char c) {
    if (c == '\n') ++line_;
    switch (state_) {
      case State::string:
        if (c == '\'') state_ = State::string_quote;
        return;
      case State::string_quote:  // '' is a quote inside the string; anything else ended it
        state_ = State::statement;
        if (c == '\'') {
          state_ = State::string;
          return;
        }
        break;
      case State::comment:
        if (c == '*') state_ = State::comment_star;
        return;
      case State::comment_star:
        if (c == '/') state_ = resume_;
        if (c != '*' && c != '/') state_ = State::comment;
        return;
      default:
        break;
    }
    if (slash_) {
      slash_ = false;
      if (c == '*') {
        resume_ = state_;
        state_ = State::comment;
        return;
      }
    }
    if (c == '/') {
      slash_ = true;
      return;
    }
    switch (state_) {
      case State::start:
        if (is_space(c)) return;
        if (c == '#') {
          state_ = State::number;
          number_ = 0;
          digits_ = 0;
          start_line_ = line_;
          return;
        }
        state_ = State::statement;
        break;
      case State::number:
        if (c >= '0' && c <= '9') {
          if (++digits_ > kMaxDigits) state_ = State::statement;
          number_ = number_ * 10 + static_cast<std::uint64_t>(c - '0');
          return;
        }
        state_ = State::after_number;
        [[fallthrough]];
      case State::after_number:
        if (is_space(c)) return;
        if (c == '=' && digits_ > 0) definitions_.push_back({number_, start_line_});
        state_ = State::statement;
        break;
      default:
        break;
    }
    if (c == '\'') state_ = State::string;
    if (c == ';') state_ = State::start;
  }

  std::vector<Definition>& definitions() { return definitions_; }

 private:
  enum class State { start, number, after_number, statement, string, string_quote, comment, comment_star };

  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

  State state_ = State::start;
  State resume_ = State::start;  // the state a comment interrupted
  bool slash_ = false;
  std::uint64_t number_ = 0;
  int digits_ = 0;
  std::size_t line_ = 1;
  std::size_t start_line_ = 1;
  std::vector<Definition> definitions_;
};

}  // namespace

void refuse_repeated_entity_numbers(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError::in(path.string(), "cannot open the CAD file");
  DefinitionScanner scanner;
  std::vector<char> buffer(1 << 20);
  while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0) {
    const auto count = static_cast<std::size_t>(in.gcount());
    for (std::size_t i = 0; i < count; ++i) scanner.feed(buffer[i]);
  }
  std::vector<Definition>& definitions = scanner.definitions();
  // Sorted by number, then line: a repeat is a neighbour; the earliest second definition wins.
  std::stable_sort(definitions.begin(), definitions.end(),
                   [](const Definition& a, const Definition& b) { return a.number < b.number; });
  const Definition* repeat = nullptr;
  const Definition* first = nullptr;
  for (std::size_t i = 1; i < definitions.size(); ++i) {
    if (definitions[i].number != definitions[i - 1].number) continue;
    if (repeat == nullptr || definitions[i].line < repeat->line) {
      repeat = &definitions[i];
      first = &definitions[i - 1];
    }
  }
  if (repeat == nullptr) return;
  throw InputError::at(path.string(), repeat->line,
                       "the STEP file is damaged: entity #" + std::to_string(repeat->number) +
                           " is defined a second time (first on line " + std::to_string(first->line) +
                           "); every entity needs its own number (export the file again from the CAD system)");
}

}  // namespace hotmesh::geometry::detail
