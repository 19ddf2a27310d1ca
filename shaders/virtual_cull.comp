#version 460
// Virtual shadow maps, step 3 of a frame: the casters of the pages drawn this frame. One
// thread per caster instance: per level, the pages its light-space rectangle reaches
// (shadows fall along the light, so a caster can only change the texels under its own
// rectangle) that the allocation flagged PENUMBRA_PAGE_RENDER. Each such page gets a
// VirtualPageDraw, and the instance one indexed indirect command per level whose instances
// are those page draws (firstInstance: the first of them); the vertex shader
// (caster.vert, PENUMBRA_VIRTUAL) places each instance in its page of the pool and clips
// it to the page. Commands go where the layered strategy's culling puts them (one region
// per level and bucket), so the same indirect draws record them. Pages whose draws do not
// fit the buffer lose their valid texels and are drawn again the next frame.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"

layout(local_size_x = 64) in;

layout(std140, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_CLIPMAP) uniform ClipmapBlock {
    PenumbraVirtualClipmap clipmap;
};
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_PAGE_TABLE) buffer PageTable { uint page_table[]; };
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_COUNTERS) buffer Counters { VirtualCounters counters; };
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_RENDER) readonly buffer Render { uint render_entries[]; };
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_DRAWS) writeonly buffer PageDraws {
    VirtualPageDraw page_draws[];
};
layout(std430, set = 1, binding = PENUMBRA_BINDING_CULL_INSTANCES) readonly buffer Instances {
    CullInstance instances[];
};
layout(std430, set = 1, binding = PENUMBRA_BINDING_CULL_BUCKETS) readonly buffer Buckets {
    uint bucket_first_command[];
};
// VkDrawIndexedIndirectCommand: indexCount, instanceCount, firstIndex, vertexOffset, firstInstance.
layout(std430, set = 1, binding = PENUMBRA_BINDING_CULL_COMMANDS) writeonly buffer Commands { uint commands[]; };
layout(std430, set = 1, binding = PENUMBRA_BINDING_CULL_COUNTS) buffer Counts { uint counts[]; };

layout(push_constant) uniform PushBlock { VirtualCullPushConstants cull; };

#define PENUMBRA_VIRTUAL_CLIPMAP clipmap
#include "penumbra/glsl/virtual_clipmap.glsl"

// A rectangle of world pages larger than this is matched against the list of pages drawn
// this frame instead of page by page (a ground plane under every page).
const int kMaxScannedPages = 64;

bool finite(vec2 v) { return !any(isnan(v)) && !any(isinf(v)); }

// The box's rectangle in the light view's XY plane (Arvo's method for the affine view).
void light_rectangle(vec3 box_min, vec3 box_max, out vec2 low, out vec2 high) {
    low = clipmap.light_view[3].xy;
    high = low;
    for (int column = 0; column < 3; ++column) {
        const vec2 a = clipmap.light_view[column].xy * box_min[column];
        const vec2 b = clipmap.light_view[column].xy * box_max[column];
        low += min(a, b);
        high += max(a, b);
    }
}

bool drawn(uint entry) { return (page_table[entry] & PENUMBRA_PAGE_RENDER) != 0u; }

// What visit_drawn_pages() does with each page drawn this frame that it finds.
const uint kCountPages = 0u;
const uint kWritePageDraws = 1u;  // page_draws[base + i] for the i-th page
const uint kInvalidatePages = 2u;  // drawn again next frame (the draws did not fit)

// Visits the pages drawn this frame among world pages [first, last) of `level`: by the
// rectangle's pages, or, for a large rectangle, by the list of drawn pages. Returns how many.
uint visit_drawn_pages(uint level, ivec2 first, ivec2 last, uint action, uint instance, uint base) {
    const ivec2 window = clipmap.levels[level].first_page;
    const ivec2 size = last - first;
    uint found = 0u;
    if (size.x * size.y <= kMaxScannedPages) {
        for (int y = first.y; y < last.y; ++y) {
            for (int x = first.x; x < last.x; ++x) {
                const uint entry = penumbra_virtual_entry(level, ivec2(x, y) - window);
                if (!drawn(entry)) continue;
                if (action == kWritePageDraws) page_draws[base + found] = VirtualPageDraw(instance, entry);
                if (action == kInvalidatePages) atomicAnd(page_table[entry], ~PENUMBRA_PAGE_VALID);
                ++found;
            }
        }
        return found;
    }
    const uint per_level = clipmap.pages_per_side * clipmap.pages_per_side;
    for (uint r = 0u; r < counters.rendered; ++r) {
        const uint entry = render_entries[r];
        if (entry / per_level != level) continue;
        const ivec2 page = penumbra_virtual_world_page_of_slot(window, entry % per_level);
        if (any(lessThan(page, first)) || any(greaterThanEqual(page, last))) continue;
        if (action == kWritePageDraws) page_draws[base + found] = VirtualPageDraw(instance, entry);
        if (action == kInvalidatePages) atomicAnd(page_table[entry], ~PENUMBRA_PAGE_VALID);
        ++found;
    }
    return found;
}

void main() {
    const uint index = gl_GlobalInvocationID.x;
    // A frame whose pages are all cached (a still or walking camera) draws nothing.
    if (index >= cull.instance_count || counters.rendered == 0u) return;
    const CullInstance instance = instances[index];
    const vec3 box_min = instance.bounds_min.xyz;
    const vec3 box_max = instance.bounds_max.xyz;
    if (any(greaterThan(box_min, box_max))) return;  // casts nothing
    vec2 low, high;
    light_rectangle(box_min, box_max, low, high);
    const bool bounded = finite(low) && finite(high);
    for (uint level = 0u; level < clipmap.level_count; ++level) {
        const float texel = clipmap.levels[level].texel_world_size;
        const float page_metres = texel * float(kPenumbraVirtualPageTexels);
        const ivec2 window = clipmap.levels[level].first_page;
        const ivec2 window_end = window + ivec2(clipmap.pages_per_side);
        // One texel more on each side: the rasteriser's coverage at the rectangle's edges.
        ivec2 first = window, last = window_end;
        if (bounded) {
            first = max(ivec2(clamp(floor((low - texel) / page_metres), vec2(-1e9), vec2(1e9))), window);
            last = min(ivec2(clamp(floor((high + texel) / page_metres) + 1.0, vec2(-1e9), vec2(1e9))), window_end);
        }
        if (any(greaterThanEqual(first, last))) continue;
        const uint pages = visit_drawn_pages(level, first, last, kCountPages, index, 0u);
        if (pages == 0u) continue;
        const uint base = atomicAdd(counters.page_draws, pages);
        if (base + pages > cull.draw_capacity) {
            atomicAdd(counters.dropped_page_draws, pages);
            visit_drawn_pages(level, first, last, kInvalidatePages, index, 0u);
            continue;
        }
        visit_drawn_pages(level, first, last, kWritePageDraws, index, base);
        const uint command = level * cull.instance_count + bucket_first_command[instance.bucket] +
                             atomicAdd(counts[level * cull.bucket_count + instance.bucket], 1u);
        commands[5 * command + 0] = instance.index_count;
        commands[5 * command + 1] = pages;
        commands[5 * command + 2] = instance.first_index;
        commands[5 * command + 3] = uint(instance.vertex_offset);
        commands[5 * command + 4] = base;
        // The level's statistics after the counts (FrameInfo): page draws and their triangles.
        const uint statistics = clipmap.level_count * cull.bucket_count + 2u * level;
        atomicAdd(counts[statistics], pages);
        atomicAdd(counts[statistics + 1u], pages * (instance.index_count / 3u));
    }
}
