# penumbra_internal_library(<target> <sources...>)
# A static library of the layers inside Penumbra::penumbra (core, gpu, passes): compiled
# with the project's warnings and position-independent code. Its include root is src/ for
# builds in this tree only ($<BUILD_INTERFACE:...>): installed, it is a link dependency of
# Penumbra::penumbra without headers, and glm stays a build-time dependency.
function(penumbra_internal_library target)
  add_library(${target} STATIC ${ARGN})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src>
                                              $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>)
  target_link_libraries(${target} PRIVATE $<BUILD_INTERFACE:penumbra_warnings>)
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
endfunction()
