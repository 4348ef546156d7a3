// Internal to converters: EXT_meshopt_compression output (what gltfpack and glTF-Transform's
// `meshopt` write). The writer builds the file as for --quantize; this then compresses the buffer
// views of vertex attributes, morph targets, indices and animation keys with meshoptimizer's codecs
// and moves their plain bytes into a fallback buffer that holds no data.
#pragma once

#include "gltf_write.h"

#include "ellicast/codec/mesh.h"
#include "ellicast/converters/asset.h"

#include <tiny_gltf.h>

#include <cstddef>
#include <string>

namespace ellicast::meshopt_output {

inline constexpr const char* kExtension = "EXT_meshopt_compression";

struct Report {
    size_t views = 0, compressed = 0;       // buffer views, and of them compressed
    size_t plain_bytes = 0, coded_bytes = 0;  // the compressed views' bytes before and after
};

// Compresses `model`'s buffer 0 (every view that holds whole elements of one accessor, 4-byte
// strides for attributes and keys, 16- or 32-bit indices) and adds the fallback buffer; `patches`
// receives what tinygltf cannot write (a buffer without data or uri). Requires EXT_meshopt_compression
// (the fallback holds no bytes). A model whose views none can be compressed is left as it is.
Report compress(tinygltf::Model& model, gltf_write::JsonPatches& patches);

// `mesh` with its triangles in vertex-cache order and its vertices in the order they are first used
// (vertices no triangle uses dropped), which the codecs compress best; a point set as it is.
// `weights`, when given (one per vertex), are reordered the same way.
Mesh in_fetch_order(const Mesh& mesh, VertexWeights* weights = nullptr);

}  // namespace ellicast::meshopt_output
