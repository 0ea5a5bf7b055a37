// hotmesh io (internal): gzip compression of whole files in memory, with zlib. OpenFOAM
// writes compressed mesh files as `points.gz` etc. Decompression is bounded: a few MB of
// gzip data can expand a thousandfold, so the reader says how much its content can need.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace hotmesh::io::detail {

/// The content of a gzip (or zlib) stream, at most `max_size` bytes. Throws
/// hotmesh::InputError naming `source` if the data is not gzip, ends early, or expands beyond
/// `max_size` (the message says so and why the bound: `bound_reason`, "what 12 points can
/// need"), before holding more than that.
std::string gunzip(std::string_view compressed, std::string_view source, std::size_t max_size,
                   std::string_view bound_reason);

/// The first `size` bytes of the content of a gzip stream (all of it if it is shorter), and
/// whether that is all of it: for reading a file's header before its content is bounded.
struct GunzipHead {
  std::string content;
  bool whole = false;
};
GunzipHead gunzip_head(std::string_view compressed, std::string_view source, std::size_t size);

/// `content` as a gzip stream.
std::string gzip(std::string_view content);

}  // namespace hotmesh::io::detail
