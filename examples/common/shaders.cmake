# example_shaders(<target> <shader files...>): compiles GLSL with glslc at build time, with
# Penumbra's installed shader includes on the include path, into <file>.inc (SPIR-V as a C
# array) that an INTERFACE target named <target> makes includable. <name>.<stage>.hlsl is
# HLSL for that stage (glslang's HLSL front end, SPIR-V 1.3: it decorates structured
# buffers as BufferBlock, which later SPIR-V versions no longer have).
function(example_shaders target)
  get_target_property(penumbra_includes Penumbra::penumbra INTERFACE_INCLUDE_DIRECTORIES)
  set(include_flags "")
  foreach(dir ${penumbra_includes})
    list(APPEND include_flags -I ${dir})
  endforeach()
  set(outputs "")
  foreach(shader ${ARGN})
    set(output ${CMAKE_CURRENT_BINARY_DIR}/${shader}.inc)
    set(language_flags "")
    if(shader MATCHES "\\.([a-z]+)\\.hlsl$")
      set(language_flags -x hlsl -fshader-stage=${CMAKE_MATCH_1} --target-spv=spv1.3)
    endif()
    add_custom_command(
      OUTPUT ${output}
      COMMAND Vulkan::glslc --target-env=vulkan1.3 -Werror ${language_flags} ${include_flags} -mfmt=c -MD -MF ${output}.d -o ${output}
              ${CMAKE_CURRENT_SOURCE_DIR}/${shader}
      DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${shader}
      DEPFILE ${output}.d
      VERBATIM)
    list(APPEND outputs ${output})
  endforeach()
  add_custom_target(${target}_spirv DEPENDS ${outputs})
  add_library(${target} INTERFACE)
  target_include_directories(${target} INTERFACE ${CMAKE_CURRENT_BINARY_DIR})
  add_dependencies(${target} ${target}_spirv)
endfunction()
