// The sun's virtual shadow map (included by penumbra/shadow.glsl before the filters): the
// level a receiver samples, its coordinates there, and the texel reads every filter makes
// through the page table. A level's texels live in 128^2-texel pages scattered over the
// pool image's layers, so a bilinear comparison is four texel reads, each through its own page
// (neighbouring texels may lie in different pages); the filters (penumbra/glsl/
// filters.glsl) call these instead of the cascades' hardware taps when a view is virtual.
//
// A receiver takes the finest level whose texel is no larger than its pixel footprint
// (the marking pass requested exactly those pages), or, where the pool could not hold a
// page its filter reads, the next coarser level whose pages are all there (the marking
// requested that level too). Nothing is ever read from a page that does not hold the
// receiver's own part of the world.
#ifndef PENUMBRA_GLSL_VIRTUAL
#define PENUMBRA_GLSL_VIRTUAL

#include "penumbra/glsl/dialect.glsl"

#include "penumbra/glsl/virtual_clipmap.glsl"

// Whether the sun's shadow is the virtual shadow map (Settings::shadow.technique).
bool penumbra_sun_is_virtual() { return penumbra_virtual.level_count > 0u; }

uint penumbra_virtual_side() { return penumbra_virtual.pages_per_side * kPenumbraVirtualPageTexels; }

// The page table entry's value of a window page, when the page holds valid texels.
bool penumbra_virtual_page_ready(uint level, ivec2 window_page) {
    const uint value = penumbra_page_table[penumbra_virtual_entry(level, window_page)];
    const uint ready = PENUMBRA_PAGE_ALLOCATED | PENUMBRA_PAGE_VALID;
    return (value & ready) == ready;
}

// The stored reverse-Z depth of a level's texel (clamped to the window), 0 (nothing, lit)
// where its page holds no valid texels.
float penumbra_virtual_texel_depth(uint level, ivec2 texel) {
    const int side = int(penumbra_virtual_side());
    const ivec2 clamped = clamp(texel, ivec2(0), ivec2(side - 1));
    const int page_texels = int(kPenumbraVirtualPageTexels);
    const uint value = penumbra_page_table[penumbra_virtual_entry(level, clamped / page_texels)];
    const uint ready = PENUMBRA_PAGE_ALLOCATED | PENUMBRA_PAGE_VALID;
    if ((value & ready) != ready) return 0.0;
    const ivec3 pool_page = penumbra_virtual_pool_page(value & PENUMBRA_PAGE_PHYSICAL_MASK);
    return penumbra_map_texel(PENUMBRA_MAP(penumbra_virtual_pool_depth), pool_page.xy * page_texels + clamped % page_texels,
                              pool_page.z);
}

// The four comparisons of the texels around a bilinear tap whose first (lowest) texel is
// `first`, in textureGather's order: x (0, 1), y (1, 1), z (1, 0), w (0, 0). Lit (1) where
// the receiver's reverse-Z depth is >= the stored one, as the cascades' comparison sampler.
vec4 penumbra_virtual_gather(uint level, ivec2 first, float reference) {
    return vec4(reference >= penumbra_virtual_texel_depth(level, first + ivec2(0, 1)) ? 1.0 : 0.0,
                reference >= penumbra_virtual_texel_depth(level, first + ivec2(1, 1)) ? 1.0 : 0.0,
                reference >= penumbra_virtual_texel_depth(level, first + ivec2(1, 0)) ? 1.0 : 0.0,
                reference >= penumbra_virtual_texel_depth(level, first) ? 1.0 : 0.0);
}

// A bilinear comparison tap at `uv` (the level's window in [0, 1]), as a hardware
// comparison sampler with linear filtering reads a map. Where the four texels lie in one
// page (127 taps in 128 per axis) it is one hardware comparison in that page of the pool;
// across a page's edge, four texel reads, each through its own page. (One return after an
// if/else: see penumbra_compare_at.)
float penumbra_virtual_compare(uint level, vec2 uv, float reference) {
    const vec2 position = uv * float(penumbra_virtual_side()) - 0.5;
    const vec2 first = floor(position);
    const vec2 weight = position - first;
    const ivec2 texel = ivec2(first);
    const int page_texels = int(kPenumbraVirtualPageTexels);
    const ivec2 in_page = texel % page_texels;
    const uint value = penumbra_page_table[penumbra_virtual_entry(level, max(texel, ivec2(0)) / page_texels)];
    const uint ready = PENUMBRA_PAGE_ALLOCATED | PENUMBRA_PAGE_VALID;
    float lit;
    if (all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(in_page, ivec2(page_texels - 1))) &&
        (value & ready) == ready) {
        const ivec3 pool_page = penumbra_virtual_pool_page(value & PENUMBRA_PAGE_PHYSICAL_MASK);
        const float layer_texels = float(kPenumbraVirtualPoolLayerPages * kPenumbraVirtualPageTexels);
        // The hardware reads texels floor(c - 0.5) and the next with weight fract(c - 0.5).
        const vec2 coordinate = vec2(pool_page.xy * page_texels + in_page) + weight + 0.5;
        // An explicit level: implicit derivatives are undefined in this divergent branch.
        lit = penumbra_map_compare_level_zero(PENUMBRA_MAP(penumbra_virtual_pool), coordinate / layer_texels,
                                              float(pool_page.z), reference);
    } else {
        const vec4 taps = penumbra_virtual_gather(level, texel, reference);
        lit = mix(mix(taps.w, taps.z, weight.x), mix(taps.x, taps.y, weight.x), weight.y);
    }
    return lit;
}

// The stored depth of the texel under `uv` (PCSS's blocker search).
float penumbra_virtual_depth(uint level, vec2 uv) {
    return penumbra_virtual_texel_depth(level, ivec2(floor(uv * float(penumbra_virtual_side()))));
}

// Whether every page a receiver's filter reads around `texel` (the marking's radius) holds
// valid texels.
bool penumbra_virtual_footprint_ready(uint level, vec2 texel) {
    const float radius = penumbra_virtual.mark_radius_texels;
    const float page = float(kPenumbraVirtualPageTexels);
    const ivec2 limit = ivec2(penumbra_virtual.pages_per_side) - 1;
    const ivec2 first = clamp(ivec2(floor((texel - radius) / page)), ivec2(0), limit);
    const ivec2 last = clamp(ivec2(floor((texel + radius) / page)), ivec2(0), limit);
    for (int y = first.y; y <= last.y; ++y) {
        for (int x = first.x; x <= last.x; ++x) {
            if (!penumbra_virtual_page_ready(level, ivec2(x, y))) return false;
        }
    }
    return true;
}

// The level a receiver samples (see the header comment), -1 beyond the shadow distance or
// where no level holds its pages.
int penumbra_virtual_receiver_level(vec3 world_position) {
    const float view_depth = -PENUMBRA_MUL(penumbra_shadow.camera_view, vec4(world_position, 1.0)).z;
    if (view_depth > penumbra_virtual.shadow_distance) return -1;
    const float margin = penumbra_virtual.mark_radius_texels;
    const int level = penumbra_select_virtual_level(world_position, margin);
    if (level < 0) return -1;
    const int last = int(penumbra_virtual.level_count) - 1;
    const vec2 light_xy = penumbra_virtual_light_xy(world_position);
    for (int candidate = level; candidate <= last; ++candidate) {
        const vec2 texel = penumbra_virtual_texel_at(uint(candidate), light_xy);
        if (!penumbra_virtual_window_holds(texel, margin)) continue;
        if (penumbra_virtual_footprint_ready(uint(candidate), texel)) return candidate;
    }
    return -1;
}

// The receiver's coordinates in `level`: (u, v) over the level's window and its reverse-Z
// depth, after the normal offset in that level's texels (normal-offset shadows, as the
// cascades').
vec3 penumbra_project_to_virtual_level(int level, vec3 world_position, vec3 world_normal) {
    const PenumbraVirtualLevel l = penumbra_virtual.levels[level];
    const float offset = penumbra_shadow.normal_offset_texels * l.texel_world_size;
    const vec3 moved = world_position + world_normal * offset;
    const vec2 uv = penumbra_virtual_texel_of(uint(level), moved) / float(penumbra_virtual_side());
    const float light_z = PENUMBRA_MUL(penumbra_virtual.light_view, vec4(moved, 1.0)).z;
    return vec3(uv, light_z * l.depth_scale + l.depth_offset);
}

// The receiver-plane gradient's clamp of a level, in its depth per UV (as a cascade's
// max_depth_gradient: the slope limit times the window's width over the depth range).
vec2 penumbra_virtual_max_depth_gradient(int level) {
    const PenumbraVirtualLevel l = penumbra_virtual.levels[level];
    const float extent = l.texel_world_size * float(penumbra_virtual_side());
    return vec2(penumbra_virtual.max_receiver_slope * extent * abs(l.depth_scale));
}

// The sun's light radius in UV per unit of reverse-Z depth in a level (PCSS): the depth
// range times tan(angular radius) over the window's width.
vec2 penumbra_virtual_light_radius_uv_per_depth(int level) {
    const PenumbraVirtualLevel l = penumbra_virtual.levels[level];
    const float extent = l.texel_world_size * float(penumbra_virtual_side());
    return vec2(penumbra_virtual.light_tan_half_angle / (abs(l.depth_scale) * extent));
}

#endif
