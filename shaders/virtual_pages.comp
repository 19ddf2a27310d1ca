#version 460
// Virtual shadow maps, step 2 of a frame: physical page allocation on the GPU, without a
// readback (UE5's page allocation; Frogfood's and EEVEE-Next's follow the same order). Run
// as a sequence of dispatches, one per step (VirtualStepPushConstants::step):
//   UPDATE  per page table entry: an entry whose window page changed (its level moved by
//           whole pages, toroidal addressing) or whose texels are stale (invalidations)
//           loses its contents; unrequested, it gives its physical page back; requested,
//           it is drawn again in place. A requested entry with valid texels is cached.
//           Requested entries without a page are queued as needs.
//   SCAN    per physical page: free pages are listed; pages whose entry nobody requested
//           this frame are evictable and counted by age (frames since their last request).
//   PLAN    one thread: how many evictable pages must go, oldest first, for the needs that
//           the free pages do not cover (least recently used); from the counts alone, what
//           the frame will assign and draw, so that the next dispatches (eviction,
//           assignment, the casters' culling) are indirect and empty when there is nothing
//           to do, and the clear pass's draws.
//   EVICT   per physical page: evicts the oldest evictable pages up to that number.
//   ASSIGN  per level and need, coarser levels first: a free page (to be drawn this
//           frame), or unserved: the pool is full, and the receiver samples a coarser level
//           instead (never another page's texels; the marking requests the next coarser
//           level's pages too, for this fallback).
// A page drawn this frame is listed as it is found, in its level's part of the list (the
// casters' culling scans one level's pages at a time).
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"

layout(local_size_x = 64) in;
const uint kGroupSize = 64u;

layout(std140, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_CLIPMAP) uniform ClipmapBlock {
    PenumbraVirtualClipmap clipmap;
};
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_PAGE_TABLE) buffer PageTable { uint page_table[]; };
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_REQUESTS) readonly buffer Requests { uint requests[]; };
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_PHYSICAL) buffer Physical {
    VirtualPhysicalPage physical[];
};
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_COUNTERS) buffer Counters { VirtualCounters counters; };
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_NEEDS) buffer Needs { uint needs[]; };
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_FREE) buffer Free { uint free_pages[]; };
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_RENDER) writeonly buffer Render { uint render_entries[]; };
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_INVALIDATIONS) readonly buffer Invalidations {
    VirtualInvalidation invalidations[];
};
layout(push_constant) uniform PushBlock { VirtualStepPushConstants pages; };

#define PENUMBRA_VIRTUAL_CLIPMAP clipmap
#include "penumbra/glsl/virtual_clipmap.glsl"

uint entry_count() { return clipmap.level_count * penumbra_virtual_slots_per_level(); }

bool is_requested(uint entry) { return requests[entry] == PENUMBRA_VIRTUAL_REQUEST_STAMP(clipmap.frame); }

// A page drawn this frame: counted, listed in its level's part of the list (each level has
// room for the whole pool), flagged for the casters' culling, and valid once the frame's
// draws ran.
uint queue_render(uint entry, uint value) {
    const uint level = penumbra_virtual_level_of_entry(entry);
    atomicAdd(counters.rendered, 1u);
    render_entries[level * clipmap.pool_pages + atomicAdd(counters.level_clears[level].instance_count, 1u)] = entry;
    return value | PENUMBRA_PAGE_VALID | PENUMBRA_PAGE_RENDER;
}

bool invalidated(uint level, ivec2 world_page) {
    if (clipmap.invalidate_all != 0u) return true;
    for (uint i = 0u; i < clipmap.invalidation_count; ++i) {
        const VirtualInvalidation rect = invalidations[i];
        if (rect.level == level && all(greaterThanEqual(world_page, rect.pages.xy)) &&
            all(lessThan(world_page, rect.pages.zw))) {
            return true;
        }
    }
    return false;
}

void update_entry(uint entry) {
    const uint per_level = penumbra_virtual_slots_per_level();
    const uint level = penumbra_virtual_level_of_entry(entry);
    const uint slot = penumbra_virtual_slot_of_entry(entry);
    const bool requested = is_requested(entry);
    if (requested) atomicAdd(counters.requested, 1u);
    uint value = page_table[entry] & ~PENUMBRA_PAGE_RENDER;  // last frame's
    if ((value & PENUMBRA_PAGE_ALLOCATED) == 0u) {
        if (requested) {
            needs[level * per_level + atomicAdd(counters.level_needs[level], 1u)] = entry;
            atomicAdd(counters.needed, 1u);
        }
        return;
    }
    const ivec2 world_page = penumbra_virtual_world_page_of_slot(clipmap.levels[level].first_page, slot);
    const ivec2 previous = penumbra_virtual_world_page_of_slot(clipmap.levels[level].previous_first_page, slot);
    const bool stale = any(notEqual(world_page, previous)) || invalidated(level, world_page);
    const uint page = value & PENUMBRA_PAGE_PHYSICAL_MASK;
    if (stale) value &= ~PENUMBRA_PAGE_VALID;
    if (!requested) {
        if (stale) {
            physical[page].owner = PENUMBRA_PAGE_NO_OWNER;
            value = 0u;
        }
        page_table[entry] = value;
        return;
    }
    physical[page].last_used = clipmap.frame;
    if ((value & PENUMBRA_PAGE_VALID) != 0u) {
        atomicAdd(counters.cached, 1u);
    } else {
        value = queue_render(entry, value);
    }
    page_table[entry] = value;
}

uint age_bucket(uint page) {
    return min(clipmap.frame - physical[page].last_used, uint(PENUMBRA_VIRTUAL_AGE_BUCKETS - 1));
}

void scan_page(uint page) {
    const uint owner = physical[page].owner;
    if (owner == PENUMBRA_PAGE_NO_OWNER) {
        free_pages[atomicAdd(counters.free, 1u)] = page;
    } else if (!is_requested(owner)) {
        atomicAdd(counters.evictable, 1u);
        atomicAdd(counters.age_histogram[age_bucket(page)], 1u);
    }
}

// The oldest age bucket whose pages go, and how many of its own, for `deficit` pages.
void choose_threshold(uint deficit) {
    counters.threshold_bucket = uint(PENUMBRA_VIRTUAL_AGE_BUCKETS);  // none
    counters.take_at_threshold = 0u;
    if (deficit == 0u) return;
    uint older = 0u;
    for (int bucket = PENUMBRA_VIRTUAL_AGE_BUCKETS - 1; bucket >= 0; --bucket) {
        const uint here = counters.age_histogram[bucket];
        counters.threshold_bucket = uint(bucket);
        counters.take_at_threshold = min(here, deficit - older);
        if (older + here >= deficit) return;
        older += here;
    }
}

VirtualDispatch dispatch_if(bool work, uint x, uint y) {
    return work ? VirtualDispatch(x, y, 1u) : VirtualDispatch(0u, 1u, 1u);
}

// What eviction and assignment will do follows from the counts: eviction takes exactly
// min(deficit, evictable) pages (choose_threshold), assignment min(needed, free pages), the
// rest of the needs stay unserved.
void plan() {
    const uint deficit = counters.needed > counters.free ? counters.needed - counters.free : 0u;
    choose_threshold(deficit);
    const uint evicting = min(deficit, counters.evictable);
    const uint assigned = min(counters.needed, counters.free + evicting);
    counters.resident = clipmap.pool_pages - counters.free - evicting + assigned;
    counters.unserved = counters.needed - assigned;
    uint most_needs = 0u;
    for (uint level = 0u; level < clipmap.level_count; ++level) {
        most_needs = max(most_needs, counters.level_needs[level]);
        counters.level_clears[level].vertex_count = 6u;
        counters.level_clears[level].first_instance = level * clipmap.pool_pages;
    }
    const uint pool_groups = (clipmap.pool_pages + kGroupSize - 1u) / kGroupSize;
    counters.evict_groups = dispatch_if(evicting > 0u, pool_groups, 1u);
    counters.assign_groups =
        dispatch_if(assigned > 0u, (most_needs + kGroupSize - 1u) / kGroupSize, clipmap.level_count);
    counters.cull_groups = dispatch_if(counters.rendered + assigned > 0u, pages.cull_columns, pages.cull_rows);
}

void evict_page(uint page) {
    const uint owner = physical[page].owner;
    if (owner == PENUMBRA_PAGE_NO_OWNER || is_requested(owner)) return;
    const uint bucket = age_bucket(page);
    if (bucket < counters.threshold_bucket) return;
    if (bucket == counters.threshold_bucket && atomicAdd(counters.taken, 1u) >= counters.take_at_threshold) return;
    page_table[owner] = 0u;
    physical[page].owner = PENUMBRA_PAGE_NO_OWNER;
    free_pages[atomicAdd(counters.free, 1u)] = page;
    atomicAdd(counters.evicted, 1u);
}

// Need number `need` of `level`. Its rank among all needs counts the coarser levels' first:
// they are served first.
void assign_page(uint level, uint need) {
    if (level >= clipmap.level_count || need >= counters.level_needs[level]) return;
    uint rank = need;
    for (uint coarser = level + 1u; coarser < clipmap.level_count; ++coarser) rank += counters.level_needs[coarser];
    const uint entry = needs[level * penumbra_virtual_slots_per_level() + need];
    if (rank >= counters.free) return;  // unserved (counted by the plan)
    const uint page = free_pages[rank];
    page_table[entry] = queue_render(entry, PENUMBRA_PAGE_ALLOCATED | page);
    physical[page] = VirtualPhysicalPage(entry, clipmap.frame);
}

void main() {
    const uint index = gl_GlobalInvocationID.x;
    const uint step = pages.step;
    if (step == PENUMBRA_VIRTUAL_STEP_PLAN) {
        if (index == 0u) plan();
    } else if (step == PENUMBRA_VIRTUAL_STEP_UPDATE) {
        if (index < entry_count()) update_entry(index);
    } else if (step == PENUMBRA_VIRTUAL_STEP_ASSIGN) {
        assign_page(gl_WorkGroupID.y, index);
    } else if (index < clipmap.pool_pages) {
        if (step == PENUMBRA_VIRTUAL_STEP_SCAN) scan_page(index);
        else evict_page(index);
    }
}
