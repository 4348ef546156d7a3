// The mesh an object of a stream is made from (encoder input) and comes back as (decoder output).
// Plain indexed arrays so that converters (glTF, OBJ, PLY) and the codec meet without either
// knowing the other's libraries. Attributes are per vertex; an attribute array is either empty
// or has one entry per position.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace ellicast {

struct Mesh {
    std::string name;
    std::vector<std::array<float, 3>> positions;
    std::vector<std::array<uint32_t, 3>> triangles;  // empty for a point set
    std::vector<std::array<float, 3>> normals;
    std::vector<std::array<float, 2>> texcoords;     // TEXCOORD_0
    // TEXCOORD_1, TEXCOORD_2, ... (format 1.14): texcoord_sets[k] is TEXCOORD_<k + 1>, one entry per
    // position each; at most 7, and only with TEXCOORD_0 (glTF numbers the sets without gaps).
    std::vector<std::vector<std::array<float, 2>>> texcoord_sets;
    std::vector<std::array<float, 4>> colors;        // COLOR_0, linear RGBA in [0,1]
    bool colors_have_alpha = false;                  // COLOR_0 was RGBA rather than RGB
    bool is_point_set = false;                       // a point primitive: no surface to rebuild
    // Data will be attached to its points by index (skin weights, morph targets): the encoder then
    // sends every vertex as a point and carries none in the exact layer (format 1.11, spec 27.3).
    bool per_point_data = false;

    bool has_normals() const { return !normals.empty(); }
    bool has_texcoords() const { return !texcoords.empty(); }
    bool has_colors() const { return !colors.empty(); }
};

}  // namespace ellicast
