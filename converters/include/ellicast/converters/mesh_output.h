// Writing meshes to files: glTF 2.0 (.glb, .gltf + .bin), PLY (binary), OBJ.
//
// Every writer takes the decoder's std::vector<ellicast::Mesh> (one entry per object), writes through
// a temporary name and a rename (a failed write leaves no partial file) and returns false with a
// readable `error` naming the file and the problem. glTF output passes the Khronos glTF-Validator
// with no error: normals are written unit length, colours clamped to [0, 1], every accessor has
// the bounds the spec requires, and meshes without vertices are left out.
#pragma once

#include "ellicast/codec/mesh.h"

#include <string>
#include <vector>

namespace ellicast {

enum class MeshFileType { Glb, Gltf, Ply, Obj };

// The file type named by `path`'s extension (.glb, .gltf, .ply, .obj; any case). False otherwise.
bool mesh_file_type_from_path(const std::string& path, MeshFileType& type);

// Writes `meshes` to `path` in the type its extension names.
bool write_meshes(const std::string& path, const std::vector<Mesh>& meshes, std::string& error);

// glTF 2.0: one scene, one node and one mesh per input mesh (a point set becomes a POINTS
// primitive). Binary (.glb) holds everything in one file; otherwise `path` gets the JSON and the
// buffer goes to a .bin next to it (same stem).
bool write_gltf(const std::string& path, const std::vector<Mesh>& meshes, bool binary, std::string& error);

// Binary little-endian PLY. Several meshes are written as one (indices offset); attributes are
// written when every mesh has them: nx ny nz, s t, red green blue [alpha] (uchar).
bool write_ply(const std::string& path, const std::vector<Mesh>& meshes, std::string& error);

// Wavefront OBJ: one `o` group per mesh with v (plus r g b when the mesh has colours, a common
// extension), vt, vn and f v/vt/vn; a point set is written as `p` elements.
bool write_obj(const std::string& path, const std::vector<Mesh>& meshes, std::string& error);

}  // namespace ellicast
