// The live view's own page (viewer/web: HTML, script, style), compiled into the library so that
// the tool serves it from wherever it is installed. three.js is not among them: it comes from npm
// (see find_three_dir in the tool) and is served from its folder.
#pragma once

#include <cstddef>
#include <string_view>

namespace ellicast::viewer {

struct WebAsset {
    const char* name;  // file name in viewer/web, e.g. "index.html"
    const unsigned char* data;
    size_t size;
};

// The asset of that file name, or nullptr.
const WebAsset* find_web_asset(std::string_view name);

}  // namespace ellicast::viewer
