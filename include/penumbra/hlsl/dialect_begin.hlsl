// The HLSL meaning of the shared shadow library's GLSL names (penumbra/glsl/dialect.glsl
// says which constructs the shared files limit themselves to). penumbra/shadow.hlsl and
// penumbra/shadow_fragment.hlsl include this before the shared files and
// penumbra/hlsl/dialect_end.hlsl after them, so that none of these names reaches the
// caller's own code. No include guard: each of the two files opens and closes the dialect.
#define PENUMBRA_HLSL 1

#define vec2 float2
#define vec3 float3
#define vec4 float4
#define ivec2 int2
#define ivec3 int3
#define ivec4 int4
#define uvec2 uint2
#define uvec3 uint3
#define uvec4 uint4
#define bvec2 bool2
#define mat2 float2x2
#define mat4 float4x4

#define mix lerp
#define fract frac
#define inversesqrt rsqrt
#define dFdx ddx
#define dFdy ddy
#define lessThan(a, b) ((a) < (b))
#define lessThanEqual(a, b) ((a) <= (b))
#define greaterThan(a, b) ((a) > (b))
#define greaterThanEqual(a, b) ((a) >= (b))
#define equal(a, b) ((a) == (b))

#define PENUMBRA_CONST static const
// HLSL's float4x4 indexes rows; mul() multiplies as written. Penumbra's matrices are laid out
// column by column in memory, which HLSL's default (column_major) packing reads as written.
#define PENUMBRA_MUL(matrix, vector) mul(matrix, vector)
#define PENUMBRA_ROW_MUL(vector, matrix) mul(vector, matrix)
#define PENUMBRA_MATRIX_ELEMENT(matrix, column, row) ((matrix)[row][column])
#define PENUMBRA_MAT2_COLUMNS(first, second) transpose(float2x2(first, second))

// A map is a texture and its sampler, bound together at one combined-image-sampler binding.
#define PENUMBRA_COMPARISON_ARRAY(name) Texture2DArray name, SamplerComparisonState name##_sampler
#define PENUMBRA_TEXTURE_ARRAY(name) Texture2DArray name, SamplerState name##_sampler
#define PENUMBRA_DEPTH_TEXTURE(name) Texture2D<float> name, SamplerState name##_sampler
#define PENUMBRA_MAP(name) name, name##_sampler
