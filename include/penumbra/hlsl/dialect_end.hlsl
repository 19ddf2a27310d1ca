// Closes penumbra/hlsl/dialect_begin.hlsl: the GLSL names go, so that the caller's HLSL
// keeps its own meaning of them. (The PENUMBRA_ macros stay: the library's names.)
#undef vec2
#undef vec3
#undef vec4
#undef ivec2
#undef ivec3
#undef ivec4
#undef uvec2
#undef uvec3
#undef uvec4
#undef bvec2
#undef mat2
#undef mat4
#undef mix
#undef fract
#undef inversesqrt
#undef dFdx
#undef dFdy
#undef lessThan
#undef lessThanEqual
#undef greaterThan
#undef greaterThanEqual
#undef equal
