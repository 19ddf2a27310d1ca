// The few constructs in which GLSL and HLSL differ, as the shared shadow library writes them
// (penumbra/glsl/*.glsl is one source for penumbra/shadow.glsl and penumbra/shadow.hlsl).
// Everything else in those files is the subset both languages read alike: GLSL's vector
// and matrix names (penumbra/hlsl/dialect_begin.hlsl maps them to HLSL's), struct fields
// assigned one by one (HLSL has no struct constructors), array initializer lists, and
// matrices built and multiplied only through the macros below. This file gives the GLSL
// meaning; under PENUMBRA_HLSL the HLSL dialect has already given the other.
#ifndef PENUMBRA_GLSL_DIALECT
#define PENUMBRA_GLSL_DIALECT
#ifndef PENUMBRA_HLSL

// A constant at file scope (HLSL needs `static`, or the constant becomes a uniform).
#define PENUMBRA_CONST const
// Matrix times column vector, and row vector times matrix.
#define PENUMBRA_MUL(matrix, vector) ((matrix) * (vector))
#define PENUMBRA_ROW_MUL(vector, matrix) ((vector) * (matrix))
// One element of a matrix (GLSL indexes columns first, HLSL rows).
#define PENUMBRA_MATRIX_ELEMENT(matrix, column, row) ((matrix)[column][row])
// A 2 x 2 matrix of two column vectors.
#define PENUMBRA_MAT2_COLUMNS(first, second) mat2(first, second)

// A shadow map as a function parameter, and the argument that passes one: GLSL's combined
// image samplers are one parameter, HLSL's textures and samplers two.
#define PENUMBRA_COMPARISON_ARRAY(name) sampler2DArrayShadow name  // layered depth, comparison sampler
#define PENUMBRA_TEXTURE_ARRAY(name) sampler2DArray name           // layered depth or moments
#define PENUMBRA_DEPTH_TEXTURE(name) sampler2D name                // depth, read as floats
#define PENUMBRA_MAP(name) name

#endif
#endif
