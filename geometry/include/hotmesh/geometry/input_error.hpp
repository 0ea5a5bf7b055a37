// hotmesh: the one exception type for problems in what the user gave us (files, case keys,
// command-line values). Its text names the file, line or key and says what is wrong, so the
// user can act on it; the command line turns it into exit code 2. It lives in the bottom
// module because every module reports such problems.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace hotmesh {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& text) : std::runtime_error(text) {}

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

}  // namespace hotmesh
