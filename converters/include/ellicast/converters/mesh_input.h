// Reading models into ellicast::Mesh objects: glTF 2.0 (.gltf, .glb, with KHR_draco_mesh_compression,
// KHR_mesh_quantization and EXT_meshopt_compression) and OBJ / PLY / OFF / STL through OpenMesh.
//
// One Mesh per triangle primitive of every mesh instance of the default scene (node transforms
// applied); point primitives become point sets; line primitives are skipped with a warning.
// Degenerate and duplicate faces are dropped with a warning; what cannot be read raises InputError.
#pragma once

#include "ellicast/codec/mesh.h"

#include <stdexcept>
#include <cstdint>
#include <string>
#include <vector>

namespace ellicast {

// A model that cannot be read: the message names the file and what is wrong with it.
class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A piece of the user's input as an error message quotes it: in double quotes, cut after `limit`
// bytes (at a UTF-8 boundary) with "..." and the whole length, so that a 50 MB line or a 300 MB
// data: URI does not end up in a terminal.
std::string quoted_input(const std::string& text, size_t limit = 80);

// How far a reader may go for the files a model names.
struct InputOptions {
    // glTF buffers and images given by URI must lie in the model's folder or below it (after
    // percent-decoding and following symlinks), as glTF tools require: "../../etc/passwd" is
    // refused. true: any readable file is taken (a user's own, trusted assets).
    bool allow_outside_folder = false;
};

struct LoadResult {
    std::vector<Mesh> meshes;           // in scene order; never empty on success
    std::vector<std::string> warnings;  // things dropped, repaired or ignored, one sentence each
};

// Reads any supported model, choosing the reader by the file's extension (and, for glTF, its
// magic). Throws InputError when the file cannot be read, holds no triangles or points, has
// non-finite coordinates, or needs an unsupported glTF extension.
LoadResult load_meshes(const std::string& path, const InputOptions& options = {});

// Bytes a user copies to move the model at `path`: the file, plus for a .gltf the external buffers
// and images it names inside its folder (data: URIs are in the file already). Files that cannot be
// read count 0.
uint64_t model_files_size(const std::string& path);

// The files of the model at `path`: the file itself, plus for a .gltf the external buffers and
// images it names inside its folder. What an output must never overwrite.
std::vector<std::string> model_files(const std::string& path);

// Reads a glTF 2.0 file (.gltf or .glb). Same contract as load_meshes.
LoadResult load_gltf(const std::string& path, const InputOptions& options = {});

// Reads OBJ, PLY, OFF or STL through OpenMesh. Same contract as load_meshes. Per-corner texture
// coordinates (OBJ) split vertices at seams, as glTF does.
LoadResult load_openmesh(const std::string& path);

// Checks and repairs a mesh read from `source` (used in error messages): throws InputError on a
// non-finite coordinate or an index beyond the vertex count; drops degenerate (repeated-index or
// zero-area) and duplicate triangles, drops attribute arrays whose size does not match, and
// replaces non-finite attribute values, each with a warning. Non-manifold edges are kept (the
// encoder needs no manifold) and reported.
void check_and_repair_mesh(Mesh& mesh, const std::string& source, std::vector<std::string>& warnings);

}  // namespace ellicast
