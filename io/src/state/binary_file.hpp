// hotmesh io (internal): what the binary state files (restart.hmr, checkpoint.hmc) share. Both
// are a magic line, a little-endian u64 length and a JSON header of that length, then arrays,
// each a u64 count and its elements as stored in memory.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::io::detail {

static_assert(std::endian::native == std::endian::little, "hotmesh state files are little-endian");

inline constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ull;

/// FNV-1a over bytes.
inline void hash_bytes(std::uint64_t& h, const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
}

/// FNV-1a over 8-byte words (the tail bytewise): eight times faster, for large buffers and
/// files. Detects changes; not meant to resist someone forging a collision.
inline void hash_words(std::uint64_t& h, const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    std::uint64_t w;
    std::memcpy(&w, p + i, 8);
    h ^= w;
    h *= 0x100000001b3ull;
    h ^= h >> 29;
  }
  hash_bytes(h, p + i, size - i);
}

template <class T>
void write_array(std::ostream& out, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  out.write(reinterpret_cast<const char*>(&n), sizeof n);
  out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
}

/// Magic line, header length, header.
inline void write_header(std::ostream& out, std::string_view magic, const std::string& header) {
  out.write(magic.data(), static_cast<std::streamsize>(magic.size()));
  const std::uint64_t length = header.size();
  out.write(reinterpret_cast<const char*>(&length), sizeof length);
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
}

/// Reads a state file held in memory, refusing to run past its end. `kind` names the file in
/// messages ("restart file").
class BinaryReader {
 public:
  BinaryReader(const std::string& bytes, const std::filesystem::path& path, std::string kind)
      : bytes_(bytes), path_(path), kind_(std::move(kind)) {}

  /// Checks the magic line and returns the JSON header's text; `what_to_do` completes the
  /// message for a file that is not of this kind.
  std::string header(std::string_view magic, std::string_view what_to_do) {
    if (bytes_.compare(0, magic.size(), magic) != 0) {
      throw InputError::in(path_.string(), "not a hotmesh " + kind_ + " (" + std::string(what_to_do) + ")");
    }
    at_ = magic.size();
    std::uint64_t length = 0;
    read(&length, sizeof length);
    if (length > bytes_.size() - at_) cut_short();
    std::string text = bytes_.substr(at_, static_cast<std::size_t>(length));
    at_ += static_cast<std::size_t>(length);
    return text;
  }

  void read(void* out, std::size_t size) {
    if (size > bytes_.size() - at_) cut_short();
    if (size == 0) return;  // an empty array's out may be null, which memcpy may not take
    std::memcpy(out, bytes_.data() + at_, size);
    at_ += size;
  }

  template <class T>
  std::vector<T> array(std::uint64_t expected) {
    std::uint64_t n = 0;
    read(&n, sizeof n);
    if (n != expected || n > (bytes_.size() - at_) / sizeof(T)) {
      throw InputError::in(path_.string(), "the " + kind_ + " is damaged (array sizes do not match)");
    }
    std::vector<T> v(static_cast<std::size_t>(n));
    read(v.data(), v.size() * sizeof(T));
    return v;
  }

  std::size_t at() const { return at_; }

 private:
  [[noreturn]] void cut_short() const { throw InputError::in(path_.string(), "the " + kind_ + " is cut short (damaged?)"); }

  const std::string& bytes_;
  const std::filesystem::path& path_;
  std::string kind_;
  std::size_t at_ = 0;
};

}  // namespace hotmesh::io::detail
