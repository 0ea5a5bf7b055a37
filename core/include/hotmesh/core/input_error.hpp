// hotmesh: the one exception type for problems in what the user gave us (files, case keys,
// command-line values). Its text names the file, line or key and says what is wrong, so the
// user can act on it; the command line turns it into exit code 2. It lives in the bottom
// module because every module reports such problems.
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace hotmesh {

class InputError : public std::runtime_error {
 public:
  /// The text as a terminal or a log can show it: control characters, NUL bytes and bytes
  /// that are not UTF-8 written as \xNN; lines cut at kMaxLine characters and the text at
  /// kMaxLines lines (a user's value may be megabytes of binary).
  explicit InputError(const std::string& text) : std::runtime_error(printable(text)) {}

  static constexpr std::size_t kMaxLine = 1000;
  static constexpr std::size_t kMaxLines = 200;
  static std::string printable(std::string_view text);

  /// "file:line: message" (line is 1-based; 0 omits it).
  static InputError at(std::string_view file, std::size_t line, std::string_view message) {
    std::string text(file);
    if (line > 0) {
      text.push_back(':');
      text.append(std::to_string(line));
    }
    text.append(": ").append(message);
    return InputError(text);
  }

  /// "file: message".
  static InputError in(std::string_view file, std::string_view message) {
    return at(file, 0, message);
  }
};

/// What keeps `path` from being read as an input file, or an empty string if nothing does:
/// "no such file", "is a folder, ...", "is a named pipe (FIFO), ..." (reading a FIFO, socket
/// or device would block or never end).
std::string input_file_problem(const std::filesystem::path& path);

/// Throws InputError naming `path` if input_file_problem() finds something.
void require_input_file(const std::filesystem::path& path);

}  // namespace hotmesh
