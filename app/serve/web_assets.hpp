// hotmesh serve: the files of the inspection page (app/serve/web/), embedded in the binary at
// build time (cmake/EmbedFiles.cmake generates web_assets.cpp), so the page works offline.
#pragma once

#include <span>
#include <string_view>

namespace hotmesh::app::serve {

struct WebAsset {
  std::string_view name;          ///< file name, e.g. "index.html"
  std::string_view content_type;  ///< from the extension
  std::string_view content;
};

std::span<const WebAsset> web_assets();

}  // namespace hotmesh::app::serve
