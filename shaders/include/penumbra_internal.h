// Push constants of Penumbra's own passes, shared by C++ and GLSL (src/passes/
// shader_interface.hpp checks the offsets). Not installed: callers see only
// penumbra/shadow_interface.h.
#ifndef PENUMBRA_INTERNAL_H
#define PENUMBRA_INTERNAL_H

#include "penumbra/shadow_interface.h"

// Descriptor sets of the caster passes: set 0 holds the frame's uniforms, set 1 the
// alpha mask of a masked caster.
#define PENUMBRA_SET_CASTER_FRAME 0
#define PENUMBRA_BINDING_CASTER_SHADOW_UNIFORMS 0  // PenumbraShadowUniforms
#define PENUMBRA_BINDING_CASTER_LOCAL_SHADOWS 1    // PenumbraLocalShadows
#define PENUMBRA_SET_ALPHA_MASK 1
#define PENUMBRA_BINDING_ALPHA_MASK 0
// The layered strategy (GPU-driven culling, shaders/caster_cull.comp): set 2 of its caster
// pipelines and set 1 of the culling dispatch.
#define PENUMBRA_SET_CASTER_DRAWS 2
#define PENUMBRA_SET_CULL_DRAWS 1
#define PENUMBRA_BINDING_CULL_INSTANCES 0  // CullInstance per caster draw
#define PENUMBRA_BINDING_CULL_BUCKETS 1    // per bucket: its first command within a layer's commands
#define PENUMBRA_BINDING_CULL_RECORDS 2    // per command: CullRecord (gl_InstanceIndex reads it)
#define PENUMBRA_BINDING_CULL_COMMANDS 3   // VkDrawIndexedIndirectCommand per command
// PENUMBRA_BINDING_CULL_COUNTS: per layer and bucket, how many commands the dispatch wrote;
// then per layer, its draws and triangles (statistics for the host).
#define PENUMBRA_BINDING_CULL_COUNTS 4
// The moments blur pass and the local moments pass: set 0 holds the image they read.
#define PENUMBRA_BINDING_BLUR_SOURCE 0

// Vertex inputs of the caster passes (one binding each: positions, uvs).
#define PENUMBRA_LOCATION_POSITION 0
#define PENUMBRA_LOCATION_UV 1

// One caster draw: its transform, the shadow map layer (a cascade, or a local light's
// layer; 0 with multiview, which adds gl_ViewIndex), its alpha test, and for a cascade
// which tile of the world's texel grid the draw renders (a toroidal cascade wraps around
// its layer's edges: bit 0, the columns past the right edge, drawn one layer side to the
// left; bit 1, the rows past the bottom edge; the pass scissors each tile).
struct CasterPushConstants {
    mat4 model;  // model -> world
    PENUMBRA_UINT layer;
    float alpha_cutoff;  // masked casters: a texel casts where alpha_scale * texture alpha >= cutoff
    float alpha_scale;
    PENUMBRA_UINT tile;
};

// One caster draw as the GPU culls it (the layered strategy): its transform, the world
// bounds the CPU's culling tests too (caster_footprint), the bucket of draws that share its
// pipeline state, and its mesh's indexed draw.
struct CullInstance {
    mat4 model;
    vec4 bounds_min;  // w unused
    vec4 bounds_max;
    PENUMBRA_UINT bucket;
    PENUMBRA_UINT index_count;
    PENUMBRA_UINT first_index;
    PENUMBRA_INT vertex_offset;
};

// What one culled command draws: a CullInstance into a cascade (the layer it writes).
struct CullRecord {
    PENUMBRA_UINT instance;
    PENUMBRA_UINT layer;
};

#define PENUMBRA_CULL_CASCADES 0      // layers are the sun's cascades (PenumbraShadowUniforms)
#define PENUMBRA_CULL_LOCAL_LAYERS 1  // layers are spot/point light layers (PenumbraLocalShadows)

// The commands of layer L, bucket B start at L * instance_count + the bucket's first
// command, and its count is counts[L * bucket_count + B].
struct CullPushConstants {
    PENUMBRA_UINT instance_count;
    PENUMBRA_UINT layer_count;
    PENUMBRA_UINT cull;  // 0: every draw into every culled layer (Settings::shadow.cull_casters off)
    PENUMBRA_UINT mode;  // PENUMBRA_CULL_*
    PENUMBRA_UINT bucket_count;
    PENUMBRA_UINT padding0;
    PENUMBRA_UINT padding1;
    PENUMBRA_UINT padding2;
    // Bit L % 32 of word L / 32: layer L is culled and drawn (0: kept from an earlier frame,
    // or nothing can reach it).
    uvec4 layer_mask[2];
};

// The moments compute passes (shaders/moments_convert.comp, moments_blur.comp), per layer.
struct MomentsPushConstants {
    // x: layer, y: texels per side the layer uses from its top-left corner, z: blur radius
    // in texels, w: blur direction (1 horizontal, 0 vertical)
    uvec4 layer;
    // x: near plane, y: far plane (the light's range; 0: orthographic, distance = 1 - depth),
    // zw: EVSM exponents (positive, negative)
    vec4 depth_range;
    // xy: the layer texel of the used texels' first one (a toroidal cascade's
    // layer_origin; 0 for local lights), z: the layer's side. The used texels wrap around
    // the layer's edges from there; filters clamp at the used texels' own edges.
    uvec4 window;
    // The used texels this dispatch writes: x, y the first, z, w how many (all of them
    // unless a cached cascade changed only some).
    uvec4 region;
};

// The screen-space resolve (shaders/visibility_resolve.comp).
struct ResolvePushConstants {
    mat4 inverse_view_projection;  // the caller's clip -> world
    PENUMBRA_UINT width;
    PENUMBRA_UINT height;
    PENUMBRA_UINT has_normals;       // 0: normals from the depth
    PENUMBRA_UINT normal_encoding;   // NormalEncoding: 0 signed float, 1 unsigned normalized, 2 octahedral
    float background_depth;          // no geometry: visibility 1
    PENUMBRA_UINT slot_count;        // 1 (the sun) + the shadowed local lights
    PENUMBRA_UINT has_face_normals;  // 0: each pixel's plane from its neighbours' depths
    PENUMBRA_UINT padding;
};

#endif
