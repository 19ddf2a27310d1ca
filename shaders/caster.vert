#version 460
// The caster passes' vertex shader: transforms a caster into one shadow-map layer's clip
// space. Compiled in variants (shaders/CMakeLists.txt):
//   PENUMBRA_LOCAL_LAYER: a spot or point light's layer, PenumbraLocalShadows.layer_view_projection;
//                         otherwise a cascade
//   PENUMBRA_MULTIVIEW:   one pass renders every cascade; gl_ViewIndex is added to the layer
//                         (only this variant needs the device's multiview feature)
//   PENUMBRA_GPU_DRIVEN:  the layered strategy: draws the commands shaders/caster_cull.comp
//                         wrote; the draw (transform) and its layer come from
//                         CullRecord[gl_InstanceIndex]. For cascades one pass renders them
//                         all and the vertex goes to its cascade's layer (gl_Layer: Vulkan
//                         1.2's shaderOutputLayer) with its tile's offset (the record's layer
//                         is the cascade's tile); a local layer is still one pass per layer
//   PENUMBRA_VIRTUAL:     the sun's virtual shadow map: draws the commands
//                         shaders/virtual_cull.comp wrote, one instance per page
//                         (VirtualPageDraw[gl_InstanceIndex]), into that page of the pool:
//                         its layer and the viewport of its place in the layer, whose
//                         scissor keeps the caster inside the page
//   PENUMBRA_MASKED:      also passes the UVs on to the alpha test
#extension GL_GOOGLE_include_directive : require
#ifdef PENUMBRA_MULTIVIEW
#extension GL_EXT_multiview : require
#define PENUMBRA_VIEW_INDEX gl_ViewIndex
#else
#define PENUMBRA_VIEW_INDEX 0
#endif
#if (defined(PENUMBRA_GPU_DRIVEN) && !defined(PENUMBRA_LOCAL_LAYER)) || defined(PENUMBRA_VIRTUAL)
#define PENUMBRA_WRITES_LAYER
#extension GL_ARB_shader_viewport_layer_array : require
#endif
#include "penumbra_internal.h"

layout(push_constant) uniform PushBlock { CasterPushConstants caster; };

#if defined(PENUMBRA_VIRTUAL)
layout(std430, set = PENUMBRA_SET_CASTER_DRAWS, binding = PENUMBRA_BINDING_CULL_INSTANCES) readonly buffer Instances {
    CullInstance instances[];
};
layout(std140, set = PENUMBRA_SET_VIRTUAL_PAGES, binding = PENUMBRA_BINDING_VIRTUAL_CLIPMAP) uniform ClipmapBlock {
    PenumbraVirtualClipmap clipmap;
};
layout(std430, set = PENUMBRA_SET_VIRTUAL_PAGES, binding = PENUMBRA_BINDING_VIRTUAL_PAGE_TABLE) readonly buffer
    PageTable {
    uint page_table[];
};
layout(std430, set = PENUMBRA_SET_VIRTUAL_PAGES, binding = PENUMBRA_BINDING_VIRTUAL_DRAWS) readonly buffer PageDraws {
    VirtualPageDraw page_draws[];
};
#define PENUMBRA_VIRTUAL_CLIPMAP clipmap
#include "penumbra/glsl/virtual_clipmap.glsl"
mat4 draw_model() { return instances[page_draws[gl_InstanceIndex].instance].model; }
uint draw_physical_page() { return page_table[page_draws[gl_InstanceIndex].entry] & PENUMBRA_PAGE_PHYSICAL_MASK; }
uint draw_layer() { return uint(penumbra_virtual_pool_page(draw_physical_page()).z); }
// The page's viewport: one per place in a layer (VirtualShadowPass).
int draw_viewport() { return int(penumbra_virtual_pool_place(draw_physical_page())); }
// The page's texels of the level's texel grid fixed in the world (as a cascade's: the world
// page's first texel is a whole number, so a caster lands on the same texels of its page
// with the same values in every frame that draws it, and a cached page equals a fresh
// one), over the page's viewport. What falls outside the page the scissor discards; the
// rasteriser's guard band spares the triangles that cross its edges any clipping.
vec4 layer_position(vec4 world) {
    const VirtualPageDraw draw = page_draws[gl_InstanceIndex];
    const uint level = penumbra_virtual_level_of_entry(draw.entry);
    const ivec2 world_page =
        penumbra_virtual_world_page_of_slot(clipmap.levels[level].first_page, penumbra_virtual_slot_of_entry(draw.entry));
    const vec3 light = (clipmap.light_view * world).xyz;
    precise vec2 texel = light.xy * clipmap.levels[level].texels_per_metre - vec2(world_page * int(kPenumbraVirtualPageTexels));
    texel = round(texel * 256.0) * (1.0 / 256.0);
    precise vec2 clip = texel * (2.0 / float(kPenumbraVirtualPageTexels)) - 1.0;
    return vec4(clip, light.z * clipmap.levels[level].depth_scale + clipmap.levels[level].depth_offset, 1.0);
}
#elif defined(PENUMBRA_GPU_DRIVEN)
layout(std430, set = PENUMBRA_SET_CASTER_DRAWS, binding = PENUMBRA_BINDING_CULL_INSTANCES) readonly buffer Instances {
    CullInstance instances[];
};
layout(std430, set = PENUMBRA_SET_CASTER_DRAWS, binding = PENUMBRA_BINDING_CULL_RECORDS) readonly buffer Records {
    CullRecord records[];
};
// firstInstance of each command is its own index (caster_cull.comp).
CullRecord draw_record() { return records[gl_InstanceIndex]; }
mat4 draw_model() { return instances[draw_record().instance].model; }
#ifdef PENUMBRA_LOCAL_LAYER
uint draw_layer() { return draw_record().layer; }
#else
// The culled layer is a cascade's tile (PENUMBRA_CULL_CASCADE_TILES): 4 cascade + tile.
uint draw_layer() { return draw_record().layer / 4u; }
uint draw_tile() { return draw_record().layer % 4u; }
#endif
#else
mat4 draw_model() { return caster.model; }
uint draw_layer() { return caster.layer + PENUMBRA_VIEW_INDEX; }
uint draw_tile() { return caster.tile; }
#endif

#if defined(PENUMBRA_VIRTUAL)
// layer_position() above
#elif defined(PENUMBRA_LOCAL_LAYER)
layout(std430, set = PENUMBRA_SET_CASTER_FRAME, binding = PENUMBRA_BINDING_CASTER_LOCAL_SHADOWS) readonly buffer
    LocalBlock {
    PenumbraLocalShadows local_shadows;
};
vec4 layer_position(vec4 world) { return local_shadows.layer_view_projection[draw_layer()] * world; }
#else
layout(std140, set = PENUMBRA_SET_CASTER_FRAME, binding = PENUMBRA_BINDING_CASTER_SHADOW_UNIFORMS) uniform ShadowBlock {
    PenumbraShadowUniforms shadow;
};
// The cascade's clip space through its texel grid (PenumbraCascade). A toroidal cascade
// wraps around its layer: the layer holds a tile of the world's texel grid, less one
// layer side where the window crosses the layer's right or bottom edge (caster.tile's
// bits; the pass scissors each tile's texels). The tile's first grid texel is a whole
// number and the same whatever the cascade's origin, so a caster lands at the same layer
// texels, with the same values, in every frame that draws it: a cached cascade's kept
// texels equal freshly drawn ones. The texel is computed without contraction (precise: no
// fused multiply-add) and snapped to 1/256 texel (what rasterisers keep).
vec4 layer_position(vec4 world) {
    const PenumbraCascade cascade = shadow.cascades[draw_layer()];
    const vec3 light = (shadow.light_view * world).xyz;
    const float texels_per_side = 1.0 / shadow.texel_uv;
    const uint tile = draw_tile();
    const vec2 wrapped = vec2(float(tile & 1u), float(tile >> 1u));
    const vec2 tile_origin = cascade.texel_origin - cascade.layer_origin + wrapped * texels_per_side;
    precise vec2 texel = light.xy * cascade.texels_per_metre - tile_origin;
    texel = round(texel * 256.0) * (1.0 / 256.0);
    precise vec2 clip = texel * (2.0 / texels_per_side) - 1.0;
    return vec4(clip, light.z * cascade.depth_scale + cascade.depth_offset, 1.0);
}
#endif

layout(location = PENUMBRA_LOCATION_POSITION) in vec3 in_position;
#ifdef PENUMBRA_MASKED
layout(location = PENUMBRA_LOCATION_UV) in vec2 in_uv;
layout(location = 0) out vec2 out_uv;
#endif

void main() {
    gl_Position = layer_position(draw_model() * vec4(in_position, 1.0));
#ifdef PENUMBRA_WRITES_LAYER
    gl_Layer = int(draw_layer());
#endif
#ifdef PENUMBRA_VIRTUAL
    gl_ViewportIndex = draw_viewport();
#endif
#ifdef PENUMBRA_MASKED
    out_uv = in_uv;
#endif
}
