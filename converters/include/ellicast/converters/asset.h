// A scene as ellicast carries it: the objects of a stream plus the scene description of format 1.1
// and later (nodes, meshes, materials with their extensions, textures, animations, skins with their
// joint weights, morph targets: spec/format.md sections 15, 18 and 20 to 22). Read from glTF with
// the scene graph intact (load_asset), rebuilt from what a receiver has (received_asset), written
// back to glTF/GLB with the scene graph restored, optionally Draco-compressed or quantized
// (write_asset).
//
// Objects are in the local frame of their mesh: a mesh instanced by several nodes is one set of
// objects, sent once. Object i of an Asset is object i of the stream.
#pragma once

#include "ellicast/codec/mesh.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/format.h"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace ellicast {

// Skin joints and weights per vertex of an object (glTF JOINTS_0 / WEIGHTS_0): joint indices into
// the skin's joint list, weights summing to 1 (unused slots 0).
struct VertexWeights {
    std::vector<std::array<uint16_t, 4>> joints;
    std::vector<std::array<float, 4>> weights;
    bool empty() const { return joints.empty(); }
};

// Morph target displacements per vertex of an object (glTF primitive targets): per vertex, per
// target, the POSITION displacement (attributes & kMorphPosition) and then the NORMAL displacement
// (attributes & kMorphNormal), 3 floats each: morph_record_values(targets, attributes) per vertex.
struct VertexMorph {
    uint8_t targets = 0;
    uint8_t attributes = 0;
    std::vector<float> values;
    bool empty() const { return targets == 0; }
};

struct Asset {
    // Object i of the stream, in its mesh's local frame. At the receiver an object with no
    // positions is one that has not arrived: write_asset leaves it out.
    std::vector<Mesh> objects;
    // Format 1.5 (spec 21): weights[i], when present and not empty, holds one entry per vertex of
    // objects[i]. Nodes name their skin in scene.nodes[n].skin, skins are in scene.skins.
    std::vector<VertexWeights> weights;
    // Format 1.6 (spec 22): morphs[i], when present and not empty, holds objects[i]'s morph targets;
    // the mesh showing it has as many default weights (scene.meshes[m].weights).
    std::vector<VertexMorph> morphs;
    // Nodes, meshes (primitive -> object + material), materials, textures (image file bytes).
    SceneDescription scene;
    // What was dropped, repaired or ignored, one sentence each.
    std::vector<std::string> warnings;
    // How the input's meshes were stored (glTF's extensionsUsed: KHR_draco_mesh_compression,
    // KHR_mesh_quantization, EXT_meshopt_compression), so that a conversion can write its output
    // the same way (AssetWriteOptions like_input).
    bool source_draco = false, source_quantized = false, source_meshopt = false;
};

// Reads a model with its scene. glTF (.gltf, .glb): the default scene's nodes (names, transforms,
// hierarchy), every distinct triangle or point primitive once as an object in its mesh's frame,
// materials (PBR metallic-roughness factors, alpha mode, double-sided, texture references with
// their texture-coordinate set) and the textures they use (the PNG or JPEG file bytes exactly as
// the asset had them, from a bufferView, a data: URI or an external file, with their sampler;
// identical image + sampler pairs are sent once), animations (format 1.4), skins with JOINTS_0 /
// WEIGHTS_0 (1.5) and morph targets with their default weights and `weights` channels (1.6). What
// ellicast does not carry (cameras, lights, other scenes, other image types, TANGENT / TEXCOORD_1+ /
// JOINTS_1+ / WEIGHTS_1+ attributes, TANGENT displacements of morph targets, a node's own morph
// weights, unknown extensions) is named in a warning; geometry is taken in its bind/rest pose. A material's texture on another set than TEXCOORD_0 is not sent (warning
// naming the material and slot): the material keeps its factors and its other textures. A
// material's KHR_texture_transform is applied to the texture coordinates of the objects drawn
// with it (same accessors under another transform: another object); a texture whose transform
// differs from the material's first texture is not sent. OBJ / PLY / OFF / STL: one node with one mesh, no material.
// Throws InputError when the file cannot be read or holds nothing to send.
Asset load_asset(const std::string& path, const InputOptions& options = {});

// True when `path` names a glTF file: a .gltf or .glb extension (any case), or the GLB magic.
bool is_gltf_file(const std::string& path);

// The asset a receiver can write from what has arrived: `objects[i]` is the decoded object i
// (empty positions: not arrived), the scene from the stream's SCENE / MATERIAL / TEXTURE_FRAGMENT
// packets. Nodes whose ancestors did not all arrive are left out; textures that did not
// completely arrive (every byte, matching checksum) are left out; a material that did not arrive,
// or that refers to a texture not yet complete, is left out and its primitives get glTF's default
// material (a textured material is shown whole or not at all); a reference to a texture set
// other than TEXCOORD_0 is cleared (not carried); objects that no arrived node shows get a root
// node of their own. Without any scene (a format 1.0 stream, or every SCENE packet lost) each object gets
// its own node and mesh. Every such gap is named in `warnings` of the result.
Asset received_asset(const ReceivedStream& stream, std::vector<Mesh> objects);

struct AssetWriteOptions {
    // KHR_draco_mesh_compression for triangle primitives (point primitives stay plain: the
    // extension covers triangles only). Quantization bits for Draco's attribute quantization.
    bool draco = false;
    int draco_position_bits = 14, draco_normal_bits = 10, draco_texcoord_bits = 12, draco_color_bits = 8;
    int draco_speed = 5;  // Draco encoder/decoder speed 0 (smallest) .. 10 (fastest)
    // KHR_mesh_quantization: positions as normalized int16 in a per-mesh cube (the dequantizing
    // transform goes into a wrapper node under each node showing the mesh), normals as normalized
    // int8, texture coordinates in [0,1] as normalized uint16, colours as normalized uint16.
    bool quantize = false;
    // EXT_meshopt_compression (what gltfpack and glTF-Transform's `meshopt` write): the quantized
    // output above (it implies `quantize`), then its vertex, index and animation buffer views
    // compressed with meshoptimizer's codecs; the file requires the extension (its fallback buffer
    // holds no bytes). Not with `draco`.
    bool meshopt = false;
    // Format 1.13 (spec 29.2): name, in a warning, the source's required extensions this output does
    // not use. `ellicast convert` turns it off: its encoder has named them already (once per asset).
    bool warn_unused_required = true;
};

// Checks options: empty when valid, else a message naming the bad option.
std::string check_asset_write_options(const AssetWriteOptions& options);

// Writes `asset` in the type the extension of `path` names. glTF 2.0, binary (.glb) or .gltf with
// a .bin next to it (same stem): the scene graph, meshes (each object one primitive of its mesh),
// materials and textures (images embedded in the buffer, bytes as given); anything that does not
// hold together (an absent object, an out-of-range reference, an empty texture image, a texture
// set the primitive lacks) is left out with a warning appended to `warnings`, so the file is
// always valid glTF; a primitive whose material uses a texture that cannot be written gets the
// default material. PLY / OBJ (no scene graph): the world-space meshes of flatten_asset. Writes
// through a temporary name. Returns false with `error` naming the file and the problem when it
// cannot write (or when Draco / quantization is asked of PLY / OBJ).
bool write_asset(const std::string& path, const Asset& asset, const AssetWriteOptions& options,
                 std::vector<std::string>& warnings, std::string& error);

// The GLB file write_asset would write for a .glb, as bytes in memory (warnings name the asset "glb").
// False with `error` when the options are invalid or the model cannot be serialized.
bool write_asset_glb(const Asset& asset, const AssetWriteOptions& options, std::vector<uint8_t>& out,
                     std::vector<std::string>& warnings, std::string& error);

// Every present object under every node that shows it, in world space (node transforms applied,
// normals by the inverse transpose, winding kept outward under a mirroring transform), named after
// its node. Without nodes: the present objects as they are.
std::vector<Mesh> flatten_asset(const Asset& asset);

// For each object of `asset`, the world transforms (4x4, column-major) of the nodes that show it,
// as flatten_asset applies them; with no scene graph, every object has the identity alone. An
// object no node shows has none.
std::vector<std::vector<std::array<double, 16>>> object_world_transforms(const Asset& asset);

// A node's local transform: its matrix, or T * R * S.
Eigen::Matrix4d node_matrix(const SceneNode& node);

}  // namespace ellicast
