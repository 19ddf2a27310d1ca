#version 460
// GPU-driven caster culling (the layered strategy): one invocation per caster draw tests its
// world bounds against every layer and appends, for each layer it can shadow, one indexed
// indirect command to that layer's region of its bucket (the draws sharing one pipeline
// state). The command's firstInstance is its own index, which the GPU-driven vertex shaders
// (caster.vert, PENUMBRA_GPU_DRIVEN) read the draw and its layer back from.
//
// The tests are the CPU culling's, in the same operations and order, so that both select
// the same casters:
// - cascade tiles (core/shadow_cache.cpp caster_footprint, and library/cascade_cache.cpp's
//   pieces): the box bounded in clip space by Arvo's method (scene.hpp transform_aabb),
//   culled only beyond the far side (depth < 0, reverse-Z) and outside the window's [-1, 1]
//   rectangle; a box whose projection is not finite may reach every texel; then its
//   footprint in texels (rounded out, one texel of margin) against the tile's rectangles
//   (CullTile: what a cached cascade draws again, or the tile's whole piece);
// - spot and point layers (core/local_lights.cpp caster_may_shadow_frustum and, for cube
//   faces, caster_may_shadow_sphere): the box's positive vertex against the frustum's five
//   Gribb-Hartmann planes, and its closest point within the light's range.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"

layout(local_size_x = 64) in;

layout(std140, set = PENUMBRA_SET_CASTER_FRAME, binding = PENUMBRA_BINDING_CASTER_SHADOW_UNIFORMS) uniform ShadowBlock {
    PenumbraShadowUniforms shadow;
};
layout(std430, set = PENUMBRA_SET_CASTER_FRAME, binding = PENUMBRA_BINDING_CASTER_LOCAL_SHADOWS) readonly buffer
    LocalBlock {
    PenumbraLocalShadows local_shadows;
};
layout(std430, set = PENUMBRA_SET_CULL_DRAWS, binding = PENUMBRA_BINDING_CULL_INSTANCES) readonly buffer Instances {
    CullInstance instances[];
};
layout(std430, set = PENUMBRA_SET_CULL_DRAWS, binding = PENUMBRA_BINDING_CULL_BUCKETS) readonly buffer Buckets {
    uint bucket_first_command[];
};
layout(std430, set = PENUMBRA_SET_CULL_DRAWS, binding = PENUMBRA_BINDING_CULL_RECORDS) writeonly buffer Records {
    CullRecord records[];
};
// VkDrawIndexedIndirectCommand: indexCount, instanceCount, firstIndex, vertexOffset, firstInstance.
layout(std430, set = PENUMBRA_SET_CULL_DRAWS, binding = PENUMBRA_BINDING_CULL_COMMANDS) writeonly buffer Commands {
    uint commands[];
};
layout(std430, set = PENUMBRA_SET_CULL_DRAWS, binding = PENUMBRA_BINDING_CULL_COUNTS) buffer Counts {
    uint counts[];
};

layout(std430, set = PENUMBRA_SET_CULL_DRAWS, binding = PENUMBRA_BINDING_CULL_TILES) readonly buffer CullTiles {
    CullTile tiles[PENUMBRA_MAX_CULL_TILES];
    ivec4 rects[];
};

layout(push_constant) uniform PushBlock { CullPushConstants cull; };

bool finite(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

// Every texel of a cascade's window, [xy, zw).
ivec4 whole_window() { return ivec4(0, 0, int(cull.resolution), int(cull.resolution)); }

bool empty_rect(ivec4 rect) { return rect.z <= rect.x || rect.w <= rect.y; }
bool rects_meet(ivec4 a, ivec4 b) { return !empty_rect(ivec4(max(a.xy, b.xy), min(a.zw, b.zw))); }

// The window texels [xy, zw) a caster inside the box can set in the cascade (empty: none).
ivec4 cascade_footprint(mat4 view_projection, vec3 box_min, vec3 box_max) {
    const ivec4 window = whole_window();
    precise vec3 low = view_projection[3].xyz;
    precise vec3 high = view_projection[3].xyz;
    for (int column = 0; column < 3; ++column) {
        for (int row = 0; row < 3; ++row) {
            precise float a = view_projection[column][row] * box_min[column];
            precise float b = view_projection[column][row] * box_max[column];
            low[row] += min(a, b);
            high[row] += max(a, b);
        }
    }
    if (!finite(low) || !finite(high)) return window;
    if (high.z < 0.0) return ivec4(0);
    if (low.x > 1.0 || high.x < -1.0 || low.y > 1.0 || high.y < -1.0) return ivec4(0);
    const float size = float(cull.resolution);
    precise vec2 texel_low = (low.xy * 0.5 + 0.5) * size;
    precise vec2 texel_high = (high.xy * 0.5 + 0.5) * size;
    // One texel of margin: rasterisation covers texels whose centres the triangles reach.
    const vec2 limit = vec2(size + 2.0);
    const ivec2 first = ivec2(clamp(floor(texel_low) - 1.0, vec2(-2.0), limit));
    const ivec2 last = ivec2(clamp(ceil(texel_high) + 1.0, vec2(-2.0), limit));
    return ivec4(max(first, window.xy), min(last, window.zw));
}

// Whether a caster whose footprint is `footprint` is drawn into tile `layer`: a dynamic one
// wherever its piece is, a static one where the tile is drawn again.
bool reaches_tile(uint layer, ivec4 footprint, bool dynamic) {
    const CullTile tile = tiles[layer];
    if (dynamic) return rects_meet(footprint, tile.piece);
    for (uint r = tile.rects.x; r < tile.rects.x + tile.rects.y; ++r) {
        if (rects_meet(footprint, rects[r])) return true;
    }
    return false;
}

// glm's dot: (x + y) + z.
float dot3(vec3 a, vec3 b) {
    precise float xy = a.x * b.x + a.y * b.y;
    precise float result = xy + a.z * b.z;
    return result;
}

bool may_shadow_frustum(mat4 view_projection, vec3 box_min, vec3 box_max) {
    const mat4 m = transpose(view_projection);
    vec4 planes[5] = vec4[5](m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[2]);
    for (int p = 0; p < 5; ++p) {
        precise vec4 plane = planes[p];
        const vec3 positive = mix(box_min, box_max, greaterThanEqual(plane.xyz, vec3(0.0)));
        precise float distance = dot3(plane.xyz, positive) + plane.w;
        if (distance < 0.0) return false;
    }
    return true;
}

bool may_shadow_sphere(vec3 centre, float radius, vec3 box_min, vec3 box_max) {
    precise vec3 offset = clamp(centre, box_min, box_max) - centre;
    precise float squared = dot3(offset, offset);
    precise float radius_squared = radius * radius;
    return squared <= radius_squared;
}

bool layer_enabled(uint layer) { return (cull.layer_mask[layer / 128u][(layer / 32u) % 4u] & (1u << (layer % 32u))) != 0u; }

void emit(uint index, uint bucket, uint layer, CullInstance instance) {
    const uint command = layer * cull.instance_count + bucket_first_command[bucket] +
                         atomicAdd(counts[layer * cull.bucket_count + bucket], 1u);
    records[command] = CullRecord(index, layer);
    commands[5 * command + 0] = instance.index_count;
    commands[5 * command + 1] = 1u;
    commands[5 * command + 2] = instance.first_index;
    commands[5 * command + 3] = uint(instance.vertex_offset);
    commands[5 * command + 4] = command;
    // The layer's statistics after the counts (FrameInfo's draws and triangles).
    const uint statistics = cull.layer_count * cull.bucket_count + 2u * layer;
    atomicAdd(counts[statistics], 1u);
    atomicAdd(counts[statistics + 1u], instance.index_count / 3u);
}

void main() {
    const uint index = gl_GlobalInvocationID.x;
    if (index >= cull.instance_count) return;
    const CullInstance instance = instances[index];
    const vec3 box_min = instance.bounds_min.xyz;
    const vec3 box_max = instance.bounds_max.xyz;
    // An empty box casts nothing (without culling every draw goes into every layer).
    if (cull.cull != 0 && any(greaterThan(box_min, box_max))) return;
    if (cull.mode == PENUMBRA_CULL_CASCADE_TILES) {
        const bool dynamic = instance.bucket >= cull.first_dynamic_bucket;
        for (uint cascade = 0; 4u * cascade < cull.layer_count; ++cascade) {
            const uint first = 4u * cascade;
            if (!(layer_enabled(first) || layer_enabled(first + 1u) || layer_enabled(first + 2u) ||
                  layer_enabled(first + 3u)))
                continue;
            // Without culling a caster may reach every texel.
            const ivec4 footprint =
                cull.cull != 0 ? cascade_footprint(shadow.cascades[cascade].view_projection, box_min, box_max)
                               : whole_window();
            if (empty_rect(footprint)) continue;
            for (uint layer = first; layer < first + 4u; ++layer) {
                if (layer_enabled(layer) && reaches_tile(layer, footprint, dynamic))
                    emit(index, instance.bucket, layer, instance);
            }
        }
        return;
    }
    for (uint light = 0; light < local_shadows.light_count; ++light) {
        const PenumbraLocalShadow shadowed = local_shadows.lights[light];
        if (shadowed.first_layer < 0) continue;
        const uint faces = shadowed.cube != 0u ? 6u : 1u;
        const bool in_range =
            shadowed.cube == 0u || may_shadow_sphere(shadowed.position, shadowed.range, box_min, box_max);
        for (uint face = 0; face < faces; ++face) {
            const uint layer = uint(shadowed.first_layer) + face;
            if (layer >= cull.layer_count || !layer_enabled(layer)) continue;
            const bool casts =
                in_range && may_shadow_frustum(local_shadows.layer_view_projection[layer], box_min, box_max);
            if (cull.cull != 0 && !casts) continue;
            emit(index, instance.bucket, layer, instance);
        }
    }
}
