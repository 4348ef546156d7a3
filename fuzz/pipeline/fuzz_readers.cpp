// Fuzzes the input readers with the bytes of one file: glTF (JSON and GLB, tinygltf and ellicast's
// own checks, Draco and meshopt decoding), OBJ, PLY, OFF and STL (OpenMesh, after ellicast's own
// prechecks). A reader must answer any file with a result or an InputError, in bounded time and memory.
//
// Input: one byte choosing the file type (modulo 6: glb, gltf, obj, ply, off, stl), then the file.
// Mode bit 3 (of that byte) reads it as an asset with its scene (load_asset) instead of meshes.
//
// Speed: one input costs about its size (under the sanitizers the glTF path reads the file three
// times, byte by byte); run with -max_len=4096 (the small samples still fit) and
// -entropic_scale_per_exec_time=1: about 3,000-5,000 inputs/s on one core, ~750 with -max_len=300000.
#include <ellicast/converters/asset.h>
#include <ellicast/converters/mesh_input.h>

#include <cstdint>
#include <cstdio>
#include <new>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace ellicast;
    if (size < 1) return 0;
    static const char* const kTypes[] = {".glb", ".gltf", ".obj", ".ply", ".off", ".stl"};
    // A folder of its own, so that relative URIs find nothing else; made for each input and removed
    // after it, so that the processes of a -fork run, which end without cleaning up, leave nothing.
    static const std::string dir = [] {
        const char* shm = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
        return std::string(shm) + "/ellicast_fuzz_readers_" + std::to_string(getpid());
    }();
    mkdir(dir.c_str(), 0700);
    struct RemoveFolder {
        const std::string& dir;
        ~RemoveFolder() { rmdir(dir.c_str()); }
    } remove_folder{dir};
    const std::string path = dir + "/model" + kTypes[(data[0] & 7) % 6];
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return 0;
    std::fwrite(data + 1, 1, size - 1, f);
    std::fclose(f);
    try {
        if (data[0] & 8) {
            Asset asset = load_asset(path);
            (void)asset;
        } else {
            LoadResult result = load_meshes(path);
            if (result.meshes.empty()) std::abort();  // the contract: never empty on success
        }
    } catch (const InputError&) {
        // the answer to a bad file
    }
    std::remove(path.c_str());
    return 0;
}
