// Internal to converters: tangents for normal-mapped glTF output (tangents.cpp).
#pragma once

#include "ellicast/codec/mesh.h"

#include <array>
#include <vector>

namespace ellicast::gltf_write {

// One glTF TANGENT per vertex of `mesh` (needs normals and TEXCOORD_0; otherwise every tangent is
// (1, 0, 0, 1)): xyz a unit vector perpendicular to the vertex normal along increasing u, w the
// handedness (+1 when cross(normal, tangent) points up the image, i.e. towards decreasing v).
// Vertices no textured triangle touches get some unit vector perpendicular to their normal.
std::vector<std::array<float, 4>> mesh_tangents(const Mesh& mesh);

}  // namespace ellicast::gltf_write
