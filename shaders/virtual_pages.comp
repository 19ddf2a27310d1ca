#version 460
// Virtual shadow maps, step 2 of a frame: physical page allocation on the GPU, without a
// readback (UE5's page allocation; Frogfood's and EEVEE-Next's follow the same order). Run
// as a sequence of dispatches, one per step (VirtualStepPushConstants::step):
//   UPDATE    per page table entry: an entry whose window page changed (its level moved by
//             whole pages, toroidal addressing) or whose texels are stale (invalidations)
//             loses its contents; unrequested, it gives its physical page back; requested,
//             it is drawn again in place. A requested entry with valid texels is cached.
//             Requested entries without a page are queued as needs.
//   SCAN      per physical page: free pages are listed; pages whose entry nobody requested
//             this frame are evictable and counted by age (frames since their last request).
//   THRESHOLD one thread: how many evictable pages must go, oldest first, for the needs
//             that the free pages do not cover (least recently used).
//   EVICT     per physical page: evicts the oldest evictable pages up to that number.
//   ASSIGN    per need, coarser levels first: a free page (to be drawn this frame), or
//             unserved: the pool is full, and the receiver samples a coarser level instead
//             (never another page's texels; the marking requests the next coarser level's
//             pages too, for this fallback).
//   COUNT     per physical page: resident pages, for the statistics; the list of pages to
//             draw, grouped by level (the casters' culling scans one level's pages at a
//             time); and the clear pass's indirect draw (a quad per page to draw).
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"

layout(local_size_x = 64) in;

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

bool is_requested(uint entry) { return requests[entry] != 0u; }

// A page drawn this frame: counted (COUNT lists it), flagged for the casters' culling, and
// valid once the frame's draws ran.
uint queue_render(uint entry, uint value) {
    atomicAdd(counters.rendered, 1u);
    atomicAdd(counters.level_rendered[penumbra_virtual_level_of_entry(entry)], 1u);
    return value | PENUMBRA_PAGE_VALID | PENUMBRA_PAGE_RENDER;
}

// Lists a page drawn this frame after the finer levels' pages: the list is grouped by level.
void list_render(uint entry) {
    const uint level = penumbra_virtual_level_of_entry(entry);
    uint first = 0u;
    for (uint finer = 0u; finer < level; ++finer) first += counters.level_rendered[finer];
    render_entries[first + atomicAdd(counters.level_listed[level], 1u)] = entry;
}

// COUNT, per physical page: every page drawn this frame holds one physical page.
void count_page(uint page) {
    const uint owner = physical[page].owner;
    if (owner == PENUMBRA_PAGE_NO_OWNER) return;
    atomicAdd(counters.resident, 1u);
    if ((page_table[owner] & PENUMBRA_PAGE_RENDER) != 0u) list_render(owner);
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

void choose_threshold() {
    const uint deficit = counters.needed > counters.free ? counters.needed - counters.free : 0u;
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

// `index`: the level's need number `index % per_level` of level `index / per_level`. Its
// rank among all needs counts the coarser levels' first: they are served first.
void assign_page(uint index) {
    const uint per_level = penumbra_virtual_slots_per_level();
    const uint level = index / per_level;
    const uint need = index % per_level;
    if (need >= counters.level_needs[level]) return;
    uint rank = need;
    for (uint coarser = level + 1u; coarser < clipmap.level_count; ++coarser) rank += counters.level_needs[coarser];
    const uint entry = needs[index];
    if (rank >= counters.free) {
        atomicAdd(counters.unserved, 1u);
        return;
    }
    const uint page = free_pages[rank];
    page_table[entry] = queue_render(entry, PENUMBRA_PAGE_ALLOCATED | page);
    physical[page] = VirtualPhysicalPage(entry, clipmap.frame);
}

void main() {
    const uint index = gl_GlobalInvocationID.x;
    const uint step = pages.step;
    if (step == PENUMBRA_VIRTUAL_STEP_THRESHOLD) {
        if (index == 0u) choose_threshold();
        return;
    }
    if (step == PENUMBRA_VIRTUAL_STEP_UPDATE || step == PENUMBRA_VIRTUAL_STEP_ASSIGN) {
        if (index >= entry_count()) return;
        if (step == PENUMBRA_VIRTUAL_STEP_UPDATE) update_entry(index);
        else assign_page(index);
        return;
    }
    if (step == PENUMBRA_VIRTUAL_STEP_COUNT && index == 0u) {
        // The clear pass's indirect draw: a quad per page to draw.
        counters.clear_vertex_count = 6u;
        counters.clear_instance_count = counters.rendered;
    }
    if (index >= clipmap.pool_pages) return;
    if (step == PENUMBRA_VIRTUAL_STEP_SCAN) scan_page(index);
    else if (step == PENUMBRA_VIRTUAL_STEP_EVICT) evict_page(index);
    else count_page(index);
}
