# `cmake --install BUILD --prefix PREFIX` puts in PREFIX:
#   include/ellicast.h                 the C API
#   include/ellicast/...               the C++ headers of the format, auth, codec, broadcast and converters layers
#   lib/libellicast.so.1.0.0           the C API (SONAME libellicast.so.1), with libellicast.so beside it
#   lib/libellicast_*.a                the C++ libraries, static
#   lib/cmake/ellicast/                find_package(ellicast CONFIG): targets ellicast::ellicast (C API) and
#                                      ellicast::format, ::auth, ::codec, ::broadcast, ::converters (C++)
#   lib/pkgconfig/ellicast.pc          pkg-config --cflags --libs ellicast (the C API)
include(CMakePackageConfigHelpers)

set(ELLICAST_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ellicast)
set_target_properties(ellicast_format PROPERTIES EXPORT_NAME format)
set_target_properties(ellicast_auth PROPERTIES EXPORT_NAME auth)
set_target_properties(ellicast_codec PROPERTIES EXPORT_NAME codec)
set_target_properties(ellicast_broadcast PROPERTIES EXPORT_NAME broadcast)
set_target_properties(ellicast_converters PROPERTIES EXPORT_NAME converters)
# converters' own compiled copy of tinygltf (with Draco): a static library the converters need at link time.
set_target_properties(ellicast_tinygltf PROPERTIES EXPORT_NAME tinygltf)

install(TARGETS ellicast_c ellicast_format ellicast_auth ellicast_codec ellicast_broadcast ellicast_converters ellicast_tinygltf
        EXPORT ellicastTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime NAMELINK_COMPONENT development
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(layer format auth codec broadcast converters capi)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${layer}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT development
          FILES_MATCHING PATTERN "*.h")
endforeach()
install(EXPORT ellicastTargets NAMESPACE ellicast:: DESTINATION ${ELLICAST_CMAKE_DIR} COMPONENT development)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ellicastConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/ellicastConfig.cmake INSTALL_DESTINATION ${ELLICAST_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/ellicastConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/ellicastConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/ellicastConfigVersion.cmake
        DESTINATION ${ELLICAST_CMAKE_DIR} COMPONENT development)

# pkg-config: the C API. The prefix is taken at install time, so `--prefix` moves it.
set(ELLICAST_PC_PREFIX "@prefix@")  # left for the install step to fill
configure_file(${PROJECT_SOURCE_DIR}/cmake/ellicast.pc.in ${CMAKE_CURRENT_BINARY_DIR}/ellicast.pc.in @ONLY)
install(CODE "
  set(prefix \"\${CMAKE_INSTALL_PREFIX}\")
  configure_file(\"${CMAKE_CURRENT_BINARY_DIR}/ellicast.pc.in\" \"${CMAKE_CURRENT_BINARY_DIR}/ellicast.pc\" @ONLY)
" COMPONENT development)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/ellicast.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT development)
