// Penumbra's shadow sampling library for the caller's own HLSL shaders: the functions of
// penumbra/shadow.glsl (docs/library.md, "Forward shading"), from the same source
// (penumbra/glsl/*.glsl, written in the subset both languages share), for HLSL compiled to
// SPIR-V. Tested with glslang's HLSL front end (glslc -x hlsl).
//
//   #define PENUMBRA_SHADOW_SET 2      // the set index you bind FrameInfo::descriptor_set at (required)
//   #define PENUMBRA_SPEC_ID_BASE 100  // first specialization constant id (default 0)
//   #include "penumbra/shadow.hlsl"
//   #include "penumbra/shadow_fragment.hlsl"  // pixel shaders: helpers with derivatives
//
// and specialize the pipeline with ShadowSystem::shader_specialization(PENUMBRA_SPEC_ID_BASE),
// or define PENUMBRA_FILTER_FROM_UNIFORMS first (one pipeline for every filter).
// The functions and their arguments are penumbra/shadow.glsl's, in HLSL's types (float3
// for vec3); where a GLSL function takes a combined image sampler, the HLSL one takes the
// texture and its sampler: penumbra_sun_contact(depth, depth_sampler, screen, ...) with a
// Texture2D<float> and a SamplerState. Every name this library declares starts with
// penumbra_, Penumbra or kPenumbra; the set's maps are textures whose samplers are named
// after them with _sampler (penumbra_cascade_map, penumbra_cascade_map_sampler), both at
// the map's combined-image-sampler binding, which Vulkan allows.
#ifndef PENUMBRA_SHADOW_HLSL
#define PENUMBRA_SHADOW_HLSL

#ifndef PENUMBRA_SHADOW_SET
// No default: set 0 (space0) is the set most shaders already use for their own resources.
#error "define PENUMBRA_SHADOW_SET, the descriptor set index the ShadowSystem's set is bound at, before including penumbra/shadow.hlsl"
#endif

#include "penumbra/hlsl/dialect_begin.hlsl"
#include "penumbra/shadow_interface.h"

#define PENUMBRA_HLSL_BINDING(index) [[vk::binding(index, PENUMBRA_SHADOW_SET)]]

PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_SHADOW_UNIFORMS) ConstantBuffer<PenumbraShadowUniforms> penumbra_shadow;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_CASCADE_MAP) Texture2DArray penumbra_cascade_map;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_CASCADE_MAP) SamplerComparisonState penumbra_cascade_map_sampler;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_CASCADE_DEPTH) Texture2DArray penumbra_cascade_depth;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_CASCADE_DEPTH) SamplerState penumbra_cascade_depth_sampler;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_CASCADE_MOMENTS) Texture2DArray penumbra_cascade_moments;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_CASCADE_MOMENTS) SamplerState penumbra_cascade_moments_sampler;
// One element: the block is a storage buffer (it outgrows a uniform buffer's guaranteed size).
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_LOCAL_SHADOWS) StructuredBuffer<PenumbraLocalShadows> penumbra_local_block;
#define penumbra_local penumbra_local_block[0]
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_LOCAL_MAP) Texture2DArray penumbra_local_map;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_LOCAL_MAP) SamplerComparisonState penumbra_local_map_sampler;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_LOCAL_DEPTH) Texture2DArray penumbra_local_depth;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_LOCAL_DEPTH) SamplerState penumbra_local_depth_sampler;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_LOCAL_MOMENTS) Texture2DArray penumbra_local_moments;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_LOCAL_MOMENTS) SamplerState penumbra_local_moments_sampler;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_VIRTUAL_CLIPMAP_BLOCK) ConstantBuffer<PenumbraVirtualClipmap> penumbra_virtual;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_VIRTUAL_PAGE_TABLE_BUFFER) StructuredBuffer<uint> penumbra_page_table;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_VIRTUAL_POOL) Texture2DArray penumbra_virtual_pool;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_VIRTUAL_POOL) SamplerComparisonState penumbra_virtual_pool_sampler;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_VIRTUAL_POOL_DEPTH) Texture2DArray penumbra_virtual_pool_depth;
PENUMBRA_HLSL_BINDING(PENUMBRA_BINDING_VIRTUAL_POOL_DEPTH) SamplerState penumbra_virtual_pool_depth_sampler;

#include "penumbra/hlsl/reads.hlsl"
#include "penumbra/glsl/filter_constants.glsl"
#include "penumbra/glsl/poisson_disks.glsl"
#include "penumbra/glsl/moments.glsl"
#include "penumbra/glsl/pcf.glsl"
#include "penumbra/glsl/virtual.glsl"
#include "penumbra/glsl/filters.glsl"
#include "penumbra/glsl/sun.glsl"
#include "penumbra/glsl/local.glsl"
#include "penumbra/glsl/contact.glsl"

#include "penumbra/hlsl/dialect_end.hlsl"

#endif
