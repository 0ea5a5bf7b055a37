// hotmesh io (internal): gzip compression of whole files in memory, with zlib. OpenFOAM
// writes compressed mesh files as `points.gz` etc.
#pragma once

#include <string>
#include <string_view>

namespace hotmesh::io::detail {

/// The content of a gzip (or zlib) stream. Throws hotmesh::InputError naming `source` if the
/// data is not gzip or ends early.
std::string gunzip(std::string_view compressed, std::string_view source);

/// `content` as a gzip stream.
std::string gzip(std::string_view content);

}  // namespace hotmesh::io::detail
