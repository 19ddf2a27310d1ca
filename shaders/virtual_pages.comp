#version 460
// Virtual shadow maps, step 2 of a frame: physical page allocation on the GPU, without a
// readback (UE5's page allocation; Frogfood's and EEVEE-Next's follow the same order), in
// two dispatches (VirtualStepPushConstants::step), since each dispatch and the barrier after
// it costs more than the work of a frame whose pages are cached:
//   SCAN    per page table entry: an entry whose window page changed (its level moved by
//           whole pages, toroidal addressing) or whose texels are stale (invalidations)
//           loses its contents; unrequested, it gives its physical page back; requested,
//           it is drawn again in place. A requested entry with valid texels is cached.
//           Requested entries without a page are queued as needs.
//           Per physical page, from the same facts about its owner: free pages (and the
//           ones given back now) are listed; pages whose entry nobody requested this frame
//           are evictable and counted by age (frames since their last request).
//           The last workgroup to finish plans: how many evictable pages must go, oldest
//           first, for the needs that the free pages do not cover (least recently used),
//           and from the counts alone what the frame assigns and draws, so that the next
//           dispatches (assignment, the casters' culling) are indirect and empty when there
//           is nothing to do, and the clear pass's draws.
//   ASSIGN  per level and need, coarser levels first (a need's rank): the free page of its
//           rank, if the free list is that long. Per physical page: the oldest evictable
//           pages up to the plan's number are evicted, and the k-th evicted page serves the
//           need ranked just after the free pages' k-th. Needs beyond both stay unserved:
//           the pool is full, and the receiver samples a coarser level instead (never
//           another page's texels; the marking requests the next coarser level's pages
//           too, for this fallback).
// A page drawn this frame is listed as it is found, in its level's part of the list (the
// casters' culling scans one level's pages at a time). How many pages a frame draws at most
// is the plan's render budget (after frames whose page draws overflowed their buffer).
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
// Coherent: the scan's last workgroup reads what every workgroup counted.
layout(std430, set = 0, binding = PENUMBRA_BINDING_VIRTUAL_COUNTERS) coherent buffer Counters {
    VirtualCounters counters;
};
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

// Where a level's need number `need` lies in the needs buffer: each level has room for all
// its slots.
uint need_index(uint level, uint need) { return level * penumbra_virtual_slots_per_level() + need; }

bool is_requested(uint entry) { return requests[entry] == PENUMBRA_VIRTUAL_REQUEST_STAMP(clipmap.frame); }

// A page drawn this frame: counted, listed in its level's part of the list (each level has
// room for the whole pool), flagged for the casters' culling, and valid once the frame's
// draws ran. Beyond the render budget (a small page-draw buffer's last frames overflowed),
// the page keeps its physical page but stays stale, and its pixels read a coarser level
// until a later frame draws it: the pages that are drawn get every draw they need.
uint queue_render(uint entry, uint value) {
    const uint budget = counters.render_budget;
    if (atomicAdd(counters.render_claims, 1u) >= budget && budget != 0u) {
        atomicAdd(counters.deferred, 1u);
        return value;
    }
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

// Whether an allocated entry's texels are stale: its slot holds another world page than last
// frame (its level moved), or a changed caster reaches it. An entry of a level the clipmap
// no longer has (a sun that casts nothing) keeps its page until it is evicted.
bool is_stale(uint entry) {
    const uint level = penumbra_virtual_level_of_entry(entry);
    if (level >= clipmap.level_count) return false;
    const uint slot = penumbra_virtual_slot_of_entry(entry);
    const ivec2 world_page = penumbra_virtual_world_page_of_slot(clipmap.levels[level].first_page, slot);
    const ivec2 previous = penumbra_virtual_world_page_of_slot(clipmap.levels[level].previous_first_page, slot);
    return any(notEqual(world_page, previous)) || invalidated(level, world_page);
}

// The page table's side of an entry (its physical page's side is scan_page()).
void update_entry(uint entry) {
    const uint level = penumbra_virtual_level_of_entry(entry);
    const bool requested = is_requested(entry);
    if (requested) atomicAdd(counters.requested, 1u);
    uint value = page_table[entry] & ~PENUMBRA_PAGE_RENDER;  // last frame's
    if ((value & PENUMBRA_PAGE_ALLOCATED) == 0u) {
        if (requested) {
            needs[need_index(level, atomicAdd(counters.level_needs[level], 1u))] = entry;
            atomicAdd(counters.needed, 1u);
        }
        return;
    }
    const bool stale = is_stale(entry);
    if (stale) value &= ~PENUMBRA_PAGE_VALID;
    if (!requested) {
        page_table[entry] = stale ? 0u : value;  // a stale page is given back
        return;
    }
    physical[value & PENUMBRA_PAGE_PHYSICAL_MASK].last_used = clipmap.frame;
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

// The physical page's side: an owner that nobody requested gives a stale page back (its
// entry's thread clears the entry) and keeps a valid one, evictable.
void scan_page(uint page) {
    uint owner = physical[page].owner;
    if (owner != PENUMBRA_PAGE_NO_OWNER && !is_requested(owner) && is_stale(owner)) {
        physical[page].owner = PENUMBRA_PAGE_NO_OWNER;
        owner = PENUMBRA_PAGE_NO_OWNER;
    }
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

// The render budget that the assignment and the next frame's scan keep to, from the last
// frame's casters' culling (whose counts the per-frame clearing keeps, and which are
// cleared here for this frame's). After a frame whose page draws overflowed: the pages whose
// draws the buffer would have held, had each needed that frame's average, less a quarter
// for the pages that need more (at least one page). After a frame that drew pages and fit:
// half as many again, until the budget holds the whole pool (0: no limit).
void plan_render_budget() {
    uint budget = counters.render_budget;
    if (counters.dropped_page_draws > 0u) {
        const float fitting = float(counters.last_rendered) * float(pages.draw_capacity) / float(counters.page_draws);
        budget = max(1u, uint(0.75 * fitting));
    } else if (budget != 0u && counters.last_rendered > 0u) {
        budget += budget / 2u + 1u;
        if (budget >= clipmap.pool_pages) budget = 0u;
    }
    counters.render_budget = budget;
    counters.page_draws = 0u;
    counters.dropped_page_draws = 0u;
}

// The pages this frame draws: the scan's, and the assigned ones the budget leaves room for
// (their claims follow the scan's).
uint pages_drawn(uint assigned) {
    const uint budget = counters.render_budget;
    if (budget == 0u) return counters.rendered + assigned;
    const uint claims = counters.render_claims;
    return counters.rendered + (budget > claims ? min(assigned, budget - claims) : 0u);
}

// What eviction and assignment will do follows from the counts: eviction takes exactly
// min(deficit, evictable) pages (choose_threshold), assignment min(needed, free pages), the
// rest of the needs stay unserved.
void plan() {
    plan_render_budget();
    const uint deficit = counters.needed > counters.free ? counters.needed - counters.free : 0u;
    choose_threshold(deficit);
    const uint evicting = min(deficit, counters.evictable);
    const uint assigned = min(counters.needed, counters.free + evicting);
    counters.resident = clipmap.pool_pages - counters.free - evicting + assigned;
    counters.unserved = counters.needed - assigned;
    counters.last_rendered = pages_drawn(assigned);
    uint most_needs = 0u;
    for (uint level = 0u; level < clipmap.level_count; ++level) {
        most_needs = max(most_needs, counters.level_needs[level]);
        counters.level_clears[level].vertex_count = 6u;
        counters.level_clears[level].first_instance = level * clipmap.pool_pages;
    }
    // Rows 0 .. level_count - 1: each level's needs; the last row: the physical pages.
    const uint columns = max(most_needs, evicting > 0u ? clipmap.pool_pages : 0u);
    counters.assign_groups = assigned > 0u
                                 ? VirtualDispatch((columns + kGroupSize - 1u) / kGroupSize, clipmap.level_count + 1u, 1u)
                                 : VirtualDispatch(0u, 1u, 1u);
    counters.cull_groups = counters.last_rendered > 0u ? VirtualDispatch(pages.cull_columns, pages.cull_rows, 1u)
                                                       : VirtualDispatch(0u, 1u, 1u);
}

// The scan's last workgroup to finish sees every workgroup's counts (atomics, made visible
// before each workgroup counts itself done) and plans.
shared bool last_group;
void plan_if_last() {
    memoryBarrierBuffer();
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        const uint groups = gl_NumWorkGroups.x * gl_NumWorkGroups.y * gl_NumWorkGroups.z;
        last_group = atomicAdd(counters.scan_groups_done, 1u) == groups - 1u;
    }
    barrier();
    if (last_group && gl_LocalInvocationIndex == 0u) {
        memoryBarrierBuffer();
        plan();
    }
}

// Page `page` to the need of `entry`: drawn this frame.
void give_page(uint entry, uint page) {
    page_table[entry] = queue_render(entry, PENUMBRA_PAGE_ALLOCATED | page);
    physical[page] = VirtualPhysicalPage(entry, clipmap.frame);
}

// The need of rank `rank` (coarser levels first).
uint need_of_rank(uint rank) {
    for (int level = int(clipmap.level_count) - 1; level >= 0; --level) {
        const uint count = counters.level_needs[level];
        if (rank < count) return needs[need_index(uint(level), rank)];
        rank -= count;
    }
    return PENUMBRA_PAGE_NO_OWNER;
}

// Need number `need` of `level` takes the free page of its rank, if there is one.
void assign_free_page(uint level, uint need) {
    if (need >= counters.level_needs[level]) return;
    uint rank = need;
    for (uint coarser = level + 1u; coarser < clipmap.level_count; ++coarser) rank += counters.level_needs[coarser];
    if (rank < counters.free) give_page(needs[need_index(level, need)], free_pages[rank]);
}

// Evicts the page if it is among the oldest the plan takes; it serves the next need after
// the free pages'.
void evict_page(uint page) {
    const uint owner = physical[page].owner;
    if (owner == PENUMBRA_PAGE_NO_OWNER || is_requested(owner)) return;
    const uint bucket = age_bucket(page);
    if (bucket < counters.threshold_bucket) return;
    if (bucket == counters.threshold_bucket && atomicAdd(counters.taken, 1u) >= counters.take_at_threshold) return;
    page_table[owner] = 0u;
    const uint evicted = atomicAdd(counters.evicted, 1u);
    give_page(need_of_rank(counters.free + evicted), page);
}

// The entry scan thread `index` updates. While a render budget defers pages, the entries
// turn by whole workgroups, a different number every frame: which pages claim the budget
// first follows the order the workgroups run in, and the deferred ones must take turns
// (a page whose own draws overflow the buffer would otherwise hold back every other).
uint scanned_entry(uint index) {
    if (counters.render_budget == 0u) return index;
    const uint groups = pages.first_page_thread / kGroupSize;
    const uint turned = index + (clipmap.frame * 40503u) % groups * kGroupSize;
    return turned >= pages.first_page_thread ? turned - pages.first_page_thread : turned;
}

void main() {
    const uint index = gl_GlobalInvocationID.x;
    if (pages.step == PENUMBRA_VIRTUAL_STEP_SCAN) {
        if (index < pages.first_page_thread) {
            const uint entry = scanned_entry(index);
            if (entry < entry_count()) update_entry(entry);
        } else if (index - pages.first_page_thread < clipmap.pool_pages) {
            scan_page(index - pages.first_page_thread);
        }
        plan_if_last();
    } else if (gl_WorkGroupID.y < clipmap.level_count) {
        assign_free_page(gl_WorkGroupID.y, index);
    } else if (index < clipmap.pool_pages) {
        evict_page(index);
    }
}
