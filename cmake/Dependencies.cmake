# Third-party libraries, all from Debian packages (see README "Setup").
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(OpenMesh CONFIG REQUIRED)          # Debian ships no version file: ask for no version
find_package(draco CONFIG REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(meshoptimizer CONFIG REQUIRED)   # EXT_meshopt_compression input (decoders only)
find_package(Threads REQUIRED)
if(ELLICAST_BUILD_TESTS)
  find_package(doctest CONFIG REQUIRED)
endif()
# tinygltf is NOT taken from libtinygltf.so: Debian's libdraco.so exports its own older copy of
# tinygltf, and mixing the two crashes. converters/ compiles tiny_gltf.h once, with Draco enabled.
find_path(TINYGLTF_INCLUDE_DIR tiny_gltf.h REQUIRED)
find_path(STB_INCLUDE_DIR stb_image.h PATHS /usr/include/stb REQUIRED)
