// hotmesh: user errors shown safely, and what makes a path unreadable as an input file.
#include "hotmesh/core/input_error.hpp"

#include <algorithm>
#include <system_error>

namespace hotmesh {

namespace {

/// Length of the UTF-8 sequence that starts at text[i], or 0 if none does.
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  const std::size_t n = lead >= 0xf0 && lead <= 0xf4 ? 4 : lead >= 0xe0 ? 3 : lead >= 0xc2 && lead < 0xe0 ? 2 : 0;
  if (n == 0 || i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
  }
  return n;
}

}  // namespace

std::string InputError::printable(std::string_view text) {
  std::string out;
  out.reserve(std::min(text.size(), std::size_t{1} << 16));
  std::size_t line_length = 0;
  std::size_t lines = 1;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      if (++lines > kMaxLines) {
        const auto rest = static_cast<std::size_t>(std::count(text.begin() + static_cast<std::ptrdiff_t>(i) + 1, text.end(), '\n')) +
                          (text.back() == '\n' ? 0 : 1);
        out += "\n... (" + std::to_string(rest) + " more lines)";
        break;
      }
      out.push_back('\n');
      line_length = 0;
      ++i;
      continue;
    }
    if (line_length >= kMaxLine) {  // the rest of this line is left out
      std::size_t end = text.find('\n', i);
      if (end == std::string_view::npos) end = text.size();
      out += " ... (" + std::to_string(end - i) + " more bytes)";
      i = end;
      continue;
    }
    const std::size_t n = c >= 0x80 ? utf8_length(text, i) : 1;
    const bool control = (c < 0x20 && c != '\t') || c == 0x7f;
    if (n == 0 || control) {
      constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out.push_back(kHex[c >> 4]);
      out.push_back(kHex[c & 0xf]);
    } else {
      out.append(text.substr(i, n));
    }
    i += std::max<std::size_t>(n, 1);
    ++line_length;
  }
  return out;
}

std::string input_file_problem(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  switch (status.type()) {
    case fs::file_type::regular: return {};
    case fs::file_type::not_found: return "no such file";
    case fs::file_type::directory: return "is a folder, expected a file";
    case fs::file_type::fifo: return "is a named pipe (FIFO), not a regular file: hotmesh reads its inputs from files";
    case fs::file_type::socket: return "is a socket, not a regular file: hotmesh reads its inputs from files";
    case fs::file_type::character:
    case fs::file_type::block: return "is a device, not a regular file: hotmesh reads its inputs from files";
    default: return ec ? "cannot be examined: " + ec.message() : "is not a regular file";
  }
}

void require_input_file(const std::filesystem::path& path) {
  if (const std::string problem = input_file_problem(path); !problem.empty()) throw InputError::in(path.string(), problem);
}

}  // namespace hotmesh
