// hotmesh io: gzip in memory through zlib's inflate/deflate with a gzip wrapper.
#include "gzip.hpp"

#include <zlib.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::io::detail {
namespace {

constexpr int kGzipOrZlib = 15 + 32;  // window bits: detect either header
constexpr int kGzip = 15 + 16;
constexpr std::size_t kChunk = 1 << 20;

Bytef* bytes(std::string_view s) { return reinterpret_cast<Bytef*>(const_cast<char*>(s.data())); }

}  // namespace

namespace {

/// Inflates `compressed` into at most `limit` bytes; `whole` tells whether the stream ended
/// within them. Throws InputError for data that is not gzip or ends early.
GunzipHead inflate_up_to(std::string_view compressed, std::string_view source, std::size_t limit) {
  if (compressed.size() > std::numeric_limits<uInt>::max()) {
    throw InputError::in(source, "compressed file larger than 4 GB: decompress it (gunzip) first");
  }
  z_stream z{};
  if (inflateInit2(&z, kGzipOrZlib) != Z_OK) throw std::runtime_error("zlib: inflateInit2 failed");
  z.next_in = bytes(compressed);
  z.avail_in = static_cast<uInt>(compressed.size());
  GunzipHead head;
  std::string& out = head.content;
  int status = Z_OK;
  while (status == Z_OK && out.size() < limit) {
    const std::size_t done = out.size();
    const std::size_t chunk = std::min(kChunk, limit - done);
    out.resize(done + chunk);
    z.next_out = reinterpret_cast<Bytef*>(out.data() + done);
    z.avail_out = static_cast<uInt>(chunk);
    status = inflate(&z, Z_NO_FLUSH);
    out.resize(done + chunk - z.avail_out);
    if (status == Z_BUF_ERROR && z.avail_in == 0) break;  // the input ended before the stream
  }
  const std::string message = z.msg ? z.msg : "";
  inflateEnd(&z);
  head.whole = status == Z_STREAM_END;
  if (head.whole || (status == Z_OK && out.size() == limit)) return head;
  throw InputError::in(source, status == Z_BUF_ERROR || status == Z_OK
                                   ? "the gzip data ends early (a truncated file)"
                                   : "not valid gzip data" + (message.empty() ? "" : " (" + message + ")"));
}

}  // namespace

std::string gunzip(std::string_view compressed, std::string_view source, std::size_t max_size,
                   std::string_view bound_reason) {
  const std::size_t limit = max_size == std::numeric_limits<std::size_t>::max() ? max_size : max_size + 1;
  GunzipHead all = inflate_up_to(compressed, source, limit);
  if (all.content.size() > max_size || !all.whole) {
    throw InputError::in(source, fmt::format("the gzip data expands to more than {} bytes, more than {}: a damaged "
                                             "file or a gzip bomb",
                                             max_size, bound_reason));
  }
  return std::move(all.content);
}

GunzipHead gunzip_head(std::string_view compressed, std::string_view source, std::size_t size) {
  return inflate_up_to(compressed, source, size);
}

std::string gzip(std::string_view content) {
  if (content.size() > std::numeric_limits<uInt>::max()) {
    throw std::runtime_error("gzip: a file of 4 GB or more is not compressed in one piece");
  }
  z_stream z{};
  if (deflateInit2(&z, Z_DEFAULT_COMPRESSION, Z_DEFLATED, kGzip, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    throw std::runtime_error("zlib: deflateInit2 failed");
  }
  std::string out(deflateBound(&z, static_cast<uLong>(content.size())), '\0');
  z.next_in = bytes(content);
  z.avail_in = static_cast<uInt>(content.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int status = deflate(&z, Z_FINISH);
  out.resize(out.size() - z.avail_out);
  deflateEnd(&z);
  if (status != Z_STREAM_END) throw std::runtime_error("zlib: deflate failed");
  return out;
}

}  // namespace hotmesh::io::detail
