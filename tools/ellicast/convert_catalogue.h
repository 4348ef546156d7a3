// `ellicast convert DIR OUTDIR`: a catalogue of glTF assets converted one process an asset.
#pragma once

#include <string>
#include <vector>

namespace ellicast::cli {

struct CatalogueArgs {
    std::string input, output;           // folders
    int jobs = 1;                        // conversions at once
    std::string validator;               // command run on each output ("" for none)
    std::vector<std::string> forwarded;  // options passed to each `ellicast convert`
    bool quiet = false;
};

// Converts every .gltf/.glb under `input` into the same relative path under `output`, prints and
// writes (OUTDIR/catalogue.md) a table; exit 0 when every asset converted (and validated).
int run_convert_catalogue(const CatalogueArgs& args);

}  // namespace ellicast::cli
