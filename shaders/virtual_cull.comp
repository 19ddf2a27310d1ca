#version 460
// Virtual shadow maps, step 3 of a frame: the casters of the pages drawn this frame. One
// workgroup per caster instance: per level, the pages its light-space rectangle reaches
// (shadows fall along the light, so a caster can only change the texels under its own
// rectangle) that the allocation flagged PENUMBRA_PAGE_RENDER. The workgroup's threads
// share the candidates: the rectangle's pages, or, when the rectangle holds more pages than
// the level draws (a ground tile under a fine level), the level's part of the list of pages
// drawn (the allocation lists them by level). Each page found gets a VirtualPageDraw, and
// the instance one indexed indirect command per level whose instances are those page
// draws (firstInstance: the first of them; their order does not matter, the depth test
// keeps the nearest); the vertex shader (caster.vert, PENUMBRA_VIRTUAL) sends each
// instance to its page's layer and viewport of the pool. Commands go into the layered
// strategy's buffers, but a bucket's commands of every level lie together (from
// bucket_first_command * level_count on) and count together: one indirect draw per bucket
// draws every level's. Pages whose draws do not fit the buffer lose their valid texels and
// are drawn again in a later frame (the next frames' allocation budgets the pages it draws,
// virtual_pages.comp). The allocation sizes this dispatch: no workgroup runs in
// a frame that draws no page.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"

layout(local_size_x = 64) in;
const uint kGroupSize = 64u;

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

// Per level: the pages the workgroup found, the first of its page draws, and how many of
// them are written (one slot each; a level's counters are never reused, so no barrier
// separates one level's reads from the next level's writes).
shared uint found_pages[PENUMBRA_MAX_VIRTUAL_LEVELS];
shared uint first_draw[PENUMBRA_MAX_VIRTUAL_LEVELS];
shared uint written[PENUMBRA_MAX_VIRTUAL_LEVELS];

// Where a level's candidates come from: the rectangle [first, last) of world pages, or the
// level's `count` pages drawn, from `list_first` on in the list.
struct Candidates {
    uint level;
    ivec2 window;  // the level's first world page
    ivec2 first;
    ivec2 last;
    bool from_list;
    uint list_first;
    uint count;
};

// The page table entry of candidate `i` if it is drawn this frame and under the rectangle,
// else PENUMBRA_PAGE_NO_OWNER.
uint candidate(Candidates c, uint i) {
    if (c.from_list) {
        const uint entry = render_entries[c.list_first + i];
        const ivec2 page = penumbra_virtual_world_page_of_slot(c.window, penumbra_virtual_slot_of_entry(entry));
        const bool inside = all(greaterThanEqual(page, c.first)) && all(lessThan(page, c.last));
        return inside ? entry : PENUMBRA_PAGE_NO_OWNER;
    }
    const int width = c.last.x - c.first.x;
    const ivec2 page = c.first + ivec2(int(i) % width, int(i) / width);
    const uint entry = penumbra_virtual_entry(c.level, page - c.window);
    return (page_table[entry] & PENUMBRA_PAGE_RENDER) != 0u ? entry : PENUMBRA_PAGE_NO_OWNER;
}

// The instance's indexed indirect command for one level: `pages` instances from `base`.
void write_command(CullInstance instance, uint level, uint pages, uint base) {
    const uint command =
        bucket_first_command[instance.bucket] * cull.level_count + atomicAdd(counts[instance.bucket], 1u);
    commands[5 * command + 0] = instance.index_count;
    commands[5 * command + 1] = pages;
    commands[5 * command + 2] = instance.first_index;
    commands[5 * command + 3] = uint(instance.vertex_offset);
    commands[5 * command + 4] = base;
    // The level's statistics after the counts' room (FrameInfo): page draws and their triangles.
    const uint statistics = cull.level_count * cull.bucket_count + 2u * level;
    atomicAdd(counts[statistics], pages);
    atomicAdd(counts[statistics + 1u], pages * (instance.index_count / 3u));
}

// How many of `pages` draws from `base` on the buffer holds.
uint room_for(uint base, uint pages) {
    return base >= cull.draw_capacity ? 0u : min(pages, cull.draw_capacity - base);
}

// The workgroup's pass over one level: count the pages, take room for their draws (and
// invalidate the pages there is none for), write the draws and the command.
void cull_level(Candidates c, uint instance_index, CullInstance instance) {
    const uint thread = gl_LocalInvocationIndex;
    for (uint i = thread; i < c.count; i += kGroupSize) {
        if (candidate(c, i) != PENUMBRA_PAGE_NO_OWNER) atomicAdd(found_pages[c.level], 1u);
    }
    barrier();
    const uint pages = found_pages[c.level];
    if (pages == 0u) return;
    if (thread == 0u) {
        const uint base = atomicAdd(counters.page_draws, pages);
        first_draw[c.level] = base;
        if (base + pages > cull.draw_capacity) atomicAdd(counters.dropped_page_draws, pages - room_for(base, pages));
    }
    barrier();
    // The pages that find room are drawn, the others are dropped one by one: they stay stale
    // and are drawn again next frame, while every page this instance did reach still counts
    // (a buffer that a group of pages overflows still makes progress every frame).
    const uint base = first_draw[c.level];
    const uint room = room_for(base, pages);
    for (uint i = thread; i < c.count; i += kGroupSize) {
        const uint entry = candidate(c, i);
        if (entry == PENUMBRA_PAGE_NO_OWNER) continue;
        const uint place = atomicAdd(written[c.level], 1u);
        if (place < room) {
            page_draws[base + place] = VirtualPageDraw(instance_index, entry);
        } else {
            atomicAnd(page_table[entry], ~PENUMBRA_PAGE_VALID);
        }
    }
    if (room > 0u && thread == 0u) write_command(instance, c.level, room, base);
}

void main() {
    // Workgroups beyond the first dimension's limit continue in the second.
    const uint index = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    // (A frame that draws no page dispatches no workgroup: the allocation sized it.)
    if (index >= cull.instance_count) return;
    if (gl_LocalInvocationIndex < PENUMBRA_MAX_VIRTUAL_LEVELS) {
        found_pages[gl_LocalInvocationIndex] = 0u;
        written[gl_LocalInvocationIndex] = 0u;
    }
    barrier();
    const CullInstance instance = instances[index];
    const vec3 box_min = instance.bounds_min.xyz;
    const vec3 box_max = instance.bounds_max.xyz;
    if (any(greaterThan(box_min, box_max))) return;  // casts nothing
    vec2 low, high;
    light_rectangle(box_min, box_max, low, high);
    const bool bounded = finite(low) && finite(high);
    for (uint level = 0u; level < clipmap.level_count; ++level) {
        const uint level_pages = counters.level_clears[level].instance_count;
        if (level_pages == 0u) continue;
        const float texel = clipmap.levels[level].texel_world_size;
        const float page_metres = texel * float(kPenumbraVirtualPageTexels);
        Candidates c;
        c.level = level;
        c.window = clipmap.levels[level].first_page;
        c.first = c.window;
        c.last = c.window + ivec2(clipmap.pages_per_side);
        // One texel more on each side: the rasteriser's coverage at the rectangle's edges.
        if (bounded) {
            c.first = max(ivec2(clamp(floor((low - texel) / page_metres), vec2(-1e9), vec2(1e9))), c.first);
            c.last = min(ivec2(clamp(floor((high + texel) / page_metres) + 1.0, vec2(-1e9), vec2(1e9))), c.last);
        }
        if (any(greaterThanEqual(c.first, c.last))) continue;
        const uint area = uint(c.last.x - c.first.x) * uint(c.last.y - c.first.y);
        c.from_list = area > level_pages;
        c.list_first = level * clipmap.pool_pages;
        c.count = c.from_list ? level_pages : area;
        cull_level(c, index, instance);
    }
}
