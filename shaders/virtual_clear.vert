#version 460
// Virtual shadow maps: clears the pages drawn this frame before their casters are drawn.
// One indirect draw per level whose instances are the level's places in the list of pages
// drawn (the allocation wrote their count and first place), a quad per page over the page's
// viewport in its layer of the pool at depth 0
// (reverse-Z: the far plane, no caster); the pipeline writes depth with
// VK_COMPARE_OP_ALWAYS.
#extension GL_GOOGLE_include_directive : require
#extension GL_ARB_shader_viewport_layer_array : require
#include "penumbra_internal.h"

layout(std140, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_CLIPMAP) uniform ClipmapBlock {
    PenumbraVirtualClipmap clipmap;
};
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_PAGE_TABLE) readonly buffer PageTable { uint page_table[]; };
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_RENDER) readonly buffer Render { uint render_entries[]; };

#define PENUMBRA_VIRTUAL_CLIPMAP clipmap
#include "penumbra/glsl/virtual_clipmap.glsl"

void main() {
    const uint physical = page_table[render_entries[gl_InstanceIndex]] & PENUMBRA_PAGE_PHYSICAL_MASK;
    // Two triangles: corners (0,0) (1,0) (0,1), (0,1) (1,0) (1,1).
    const uint corner_index = gl_VertexIndex < 3 ? gl_VertexIndex : 6 - gl_VertexIndex;
    const vec2 corner = vec2(float(corner_index & 1u), float(corner_index >> 1u));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
    gl_Layer = penumbra_virtual_pool_page(physical).z;
    gl_ViewportIndex = int(penumbra_virtual_pool_place(physical));
}
