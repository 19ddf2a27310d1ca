// Penumbra's shadow sampling library for the caller's own shaders (docs/library.md,
// "Forward shading"). Every filter of Settings::shadow.filter, for the sun and for spot
// and point lights, reading the maps of a ShadowSystem through its descriptor set.
//
//   #define PENUMBRA_SHADOW_SET 2      // the set index you bind FrameInfo::descriptor_set at (required)
//   #define PENUMBRA_SPEC_ID_BASE 100  // first specialization constant id (default 0)
//   #include "penumbra/shadow.glsl"
//   #include "penumbra/shadow_fragment.glsl"  // fragment shaders: helpers with derivatives
//
// and specialize the pipeline with ShadowSystem::shader_specialization(PENUMBRA_SPEC_ID_BASE),
// or define PENUMBRA_FILTER_FROM_UNIFORMS first: one pipeline for every filter, which reads
// the filter from the uniforms (penumbra/glsl/filter_constants.glsl).
// Everything here works in any stage (the compute resolve uses it too); `pixel` is the
// pixel's centre in framebuffer coordinates (gl_FragCoord.xy), which rotates the Poisson
// patterns per pixel. Every name this library declares starts with penumbra_, Penumbra or
// kPenumbra. Requires GL_GOOGLE_include_directive.
//
// The API:
//   PenumbraSunReceiver penumbra_sun_receiver(world_position, normal, pixel)
//   void penumbra_set_receiver_plane(receiver, coord_dx[2], coord_dy[2], seam)  // optional
//   float penumbra_sun_shadow(receiver)                // the shadow alone, 1 beyond the cascades
//   float penumbra_sun_visibility(receiver, normal)    // 0 without a sun or facing away, else the shadow
//   bool penumbra_faces_light(normal, face_normal, to_light)  // by the shading normal and the face
//   float penumbra_light_shadow(index, world_position, normal, plane_normal, pixel)
//   float penumbra_light_visibility(index, world_position, normal, plane_normal, pixel)
//   int penumbra_select_cascade(penumbra_view_depth(world_position))   // debug views
//   int penumbra_sun_map_of(world_position)  // the cascade, or with virtual shadow maps the level
//   float penumbra_sun_contact(depth, screen, world_position, geometric_normal, pixel)    // contact shadows
//   float penumbra_light_contact(index, depth, screen, world_position, geometric_normal, pixel)
//     (Settings::contact: a ray through the caller's depth buffer, penumbra/glsl/contact.glsl)
//
// With Settings::shadow.technique = virtual (penumbra_sun_is_virtual()), the sun's functions
// read the virtual shadow map instead of the cascades: PenumbraSunReceiver::cascade is then
// the clipmap level, and the same calls work unchanged (penumbra/glsl/virtual.glsl).
#ifndef PENUMBRA_SHADOW_GLSL
#define PENUMBRA_SHADOW_GLSL

#include "penumbra/shadow_interface.h"

#ifndef PENUMBRA_SHADOW_SET
// No default: set 0 is the set most shaders already use for their own resources.
#error "define PENUMBRA_SHADOW_SET, the descriptor set index the ShadowSystem's set is bound at, before including penumbra/shadow.glsl"
#endif

layout(std140, set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_BINDING_SHADOW_UNIFORMS) uniform PenumbraShadowBlock {
    PenumbraShadowUniforms penumbra_shadow;
};
layout(set = PENUMBRA_SHADOW_SET,
       binding = PENUMBRA_BINDING_CASCADE_MAP) uniform sampler2DArrayShadow penumbra_cascade_map;
layout(set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_BINDING_CASCADE_DEPTH) uniform sampler2DArray penumbra_cascade_depth;
layout(set = PENUMBRA_SHADOW_SET,
       binding = PENUMBRA_BINDING_CASCADE_MOMENTS) uniform sampler2DArray penumbra_cascade_moments;
// A storage buffer: with 256 lights and 192 layers the block outgrows the 16 KiB that
// Vulkan guarantees for uniform buffers.
layout(std430, set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_BINDING_LOCAL_SHADOWS) readonly buffer PenumbraLocalBlock {
    PenumbraLocalShadows penumbra_local;
};
layout(set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_BINDING_LOCAL_MAP) uniform sampler2DArrayShadow penumbra_local_map;
layout(set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_BINDING_LOCAL_DEPTH) uniform sampler2DArray penumbra_local_depth;
layout(set = PENUMBRA_SHADOW_SET,
       binding = PENUMBRA_BINDING_LOCAL_MOMENTS) uniform sampler2DArray penumbra_local_moments;

layout(std140, set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_BINDING_VIRTUAL_CLIPMAP_BLOCK) uniform PenumbraVirtualBlock {
    PenumbraVirtualClipmap penumbra_virtual;
};
layout(std430, set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_BINDING_VIRTUAL_PAGE_TABLE_BUFFER) readonly buffer
    PenumbraPageTableBlock {
    uint penumbra_page_table[];
};
layout(set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_BINDING_VIRTUAL_POOL) uniform sampler2DArrayShadow penumbra_virtual_pool;
layout(set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_BINDING_VIRTUAL_POOL_DEPTH) uniform sampler2DArray penumbra_virtual_pool_depth;

#include "penumbra/glsl/reads.glsl"
#include "penumbra/glsl/filter_constants.glsl"
#include "penumbra/glsl/poisson_disks.glsl"
#include "penumbra/glsl/moments.glsl"
#include "penumbra/glsl/pcf.glsl"
#include "penumbra/glsl/virtual.glsl"
#include "penumbra/glsl/filters.glsl"
#include "penumbra/glsl/sun.glsl"
#include "penumbra/glsl/local.glsl"
#include "penumbra/glsl/contact.glsl"

#endif
