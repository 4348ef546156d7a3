// Internal to converters: glTF reading pieces shared by gltf_input.cpp (flattened meshes) and
// asset_input.cpp (the scene as it is). Implemented in gltf_input.cpp. Every function checks what it
// reads against what is really there and throws InputError naming the file, element and problem.
#pragma once

#include "ellicast/converters/mesh_input.h"

#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include <Eigen/Dense>

#include <set>
#include <functional>
#include <string>
#include <vector>

namespace ellicast::gltf_read {

// Extensions that change how geometry is stored and that the reader implements.
extern const std::set<std::string> kGeometryExtensions;

// True for extensions that only change appearance (materials, textures, lights).
bool appearance_only(const std::string& ext);

// An image loader for tinygltf that accepts every image without decoding or keeping it.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*);

// Reads `path` as .gltf or .glb (chosen by its magic) into `model`, images going through
// `image_loader`. Throws InputError when the file cannot be read, is not glTF 2.x, or requires an
// extension that is neither a geometry extension above nor appearance-only (those give a warning,
// unless `carried` says the caller carries them: the scene reader carries material extensions).
void load_model(const std::string& path, tinygltf::Model& model, tinygltf::LoadImageDataFunction image_loader,
                void* image_user_data, std::vector<std::string>& warnings, const InputOptions& options,
                const std::function<bool(const std::string&)>& carried = {});

// The file a glTF's relative URI names, percent-decoded, relative to the folder of `model_path`.
// Unless `options` allow it, throws InputError (naming `what` and the URI) when it leaves that
// folder: absolute, a drive or root name, ".." above the folder, or a symlink out of it.
std::string resource_file(const std::string& model_path, const std::string& uri, const std::string& what,
                          const InputOptions& options);

// The bytes of every buffer of the glTF `doc` (parsed from the file `bytes` read from `path`): a
// GLB's BIN chunk, a base64 data: URI, or a file that resource_file allows; empty for a buffer
// without data. Throws InputError when a buffer holds less than its byteLength or cannot be read.
std::vector<std::vector<uint8_t>> gltf_buffers(const std::string& path, const std::vector<uint8_t>& bytes, bool binary,
                                               const nlohmann::json& doc, const InputOptions& options);

// The JSON text of a .gltf file, or the JSON chunk of a GLB (12-byte header, then chunks of length,
// type, data); "" when a GLB is too short to hold it.
std::string json_text(const std::vector<uint8_t>& bytes, bool binary);

// When the glTF file `bytes` (read from `path`) uses EXT_meshopt_compression: the same asset as a
// GLB with every buffer view decoded into one buffer and the extension removed, for tinygltf (which
// does not know it). Empty when the file does not use it. Throws InputError naming the buffer view
// and what is wrong when the compressed data or its description is bad. (meshopt_input.cpp)
std::vector<uint8_t> decode_meshopt(const std::string& path, const std::vector<uint8_t>& bytes, bool binary,
                                    const InputOptions& options);

// The whole file at `path`, read in one go. Throws InputError when it cannot be opened or read.
std::vector<uint8_t> read_file_bytes(const std::string& path);

// The JSON of the glTF file at `path` (a .gltf file's text or a GLB's JSON chunk), for what tinygltf
// does not keep (e.g. the mimeType of an image given by URI); discarded when it cannot be parsed.
nlohmann::json read_json(const std::string& path);

// Values per element of a glTF accessor type (1 for SCALAR ... 4 for VEC4; 0 otherwise), and bytes
// per component of a component type (0 when unknown).
int component_count(int type);
int component_size(int component_type);

// One component at `p` as a double, with glTF's normalization rules.
double read_component(const unsigned char* p, int component_type, bool normalized);

// Reads `count` elements of `components` values of a buffer view, checking every byte is there.
void read_view(const tinygltf::Model& model, int view_index, size_t byte_offset, size_t count, int components,
               int component_type, bool normalized, size_t stride_override, const std::string& what,
               std::vector<double>& out);

// An accessor as doubles (count x components), sparse substitution applied.
std::vector<double> read_accessor(const tinygltf::Model& model, int index, const std::string& what, int& components);

// A node's local transform: its matrix, or T * R * S.
Eigen::Matrix4d local_transform(const tinygltf::Node& node);

// Triangles of an index list in a triangle mode (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN).
std::vector<std::array<uint32_t, 3>> primitive_triangles(const std::vector<uint32_t>& idx, int mode);

// "TRIANGLES", "POINTS", ... for a primitive mode.
const char* mode_name(int mode);

// One primitive, transformed by `world` (identity: the mesh's own frame), as a Mesh with POSITION,
// NORMAL, TEXCOORD_0 and COLOR_0. Returns false (with a warning) when skipped (lines, no POSITION).
bool primitive_to_mesh(const tinygltf::Model& model, const tinygltf::Primitive& prim, const Eigen::Matrix4d& world,
                       const std::string& where, Mesh& mesh, std::vector<std::string>& warnings);

}  // namespace ellicast::gltf_read
