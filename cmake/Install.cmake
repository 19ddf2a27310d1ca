# `cmake --install build --prefix P`: the library (its archive and those of the layers it
# is made of, which carry no headers), the Vulkan helper component it is built on
# (Penumbra::gpu, with its public headers in include/penumbra/gpu/), the public headers and
# GLSL includes, and the package configuration with exported targets. The scene component goes in only when it
# is built (PENUMBRA_BUILD_TOOLS), in an export set of its own, so that a user who asks
# for the library alone never needs toml++ or tinygltf.
include(CMakePackageConfigHelpers)
set(PENUMBRA_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Penumbra)

install(TARGETS penumbra_library penumbra_passes penumbra_gpu penumbra_core penumbra_shaders
        EXPORT PenumbraTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/penumbra/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/penumbra
        FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h" PATTERN "*.glsl" PATTERN "*.hlsl" PATTERN "scene" EXCLUDE)
install(FILES ${PENUMBRA_GENERATED_INCLUDE}/penumbra/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/penumbra)
install(EXPORT PenumbraTargets NAMESPACE Penumbra:: DESTINATION ${PENUMBRA_CMAKE_DIR})

if(TARGET penumbra_scene)
  install(TARGETS penumbra_scene EXPORT PenumbraSceneTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/penumbra/scene/
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/penumbra/scene FILES_MATCHING PATTERN "*.hpp")
  install(EXPORT PenumbraSceneTargets NAMESPACE Penumbra:: DESTINATION ${PENUMBRA_CMAKE_DIR})
endif()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/PenumbraConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/PenumbraConfig.cmake INSTALL_DESTINATION ${PENUMBRA_CMAKE_DIR})
# 0.x: a minor version may change the API, so only the same minor version is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/PenumbraConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/PenumbraConfig.cmake ${PROJECT_BINARY_DIR}/PenumbraConfigVersion.cmake
        DESTINATION ${PENUMBRA_CMAKE_DIR})
