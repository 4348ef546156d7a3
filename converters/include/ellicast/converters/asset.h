// A scene as ellicast carries it: the objects of a stream plus the scene description (nodes,
// meshes, materials, textures) of format 1.1, read from glTF with the scene graph intact.
//
// Objects are in the local frame of their mesh: a mesh instanced by several nodes is one set of
// objects, sent once. Object i of an Asset is object i of the stream.
#pragma once

#include "ellicast/codec/mesh.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/format.h"

#include <string>
#include <vector>

namespace ellicast {

struct Asset {
    // Object i of the stream, in its mesh's local frame. At the receiver an object with no
    // positions is one that has not arrived: write_asset leaves it out.
    std::vector<Mesh> objects;
    // Nodes, meshes (primitive -> object + material), materials, textures (image file bytes).
    SceneDescription scene;
    // What was dropped, repaired or ignored, one sentence each.
    std::vector<std::string> warnings;
};

// Reads a model with its scene. glTF (.gltf, .glb): the default scene's nodes (names, transforms,
// hierarchy), every distinct triangle or point primitive once as an object in its mesh's frame,
// materials (PBR metallic-roughness factors, alpha mode, double-sided, texture references with
// their texture-coordinate set) and the textures they use (the PNG or JPEG file bytes exactly as
// the asset had them, from a bufferView, a data: URI or an external file, with their sampler;
// identical image + sampler pairs are sent once). What ellicast does not carry (animations, skins,
// morph targets, cameras, lights, other scenes, other image types, TANGENT / TEXCOORD_1+ /
// JOINTS / WEIGHTS attributes, unknown extensions) is named in a warning; geometry is taken in its
// bind/rest pose. OBJ / PLY / OFF / STL: one node with one mesh, no material. Throws InputError
// when the file cannot be read or holds nothing to send.
Asset load_asset(const std::string& path);

}  // namespace ellicast
