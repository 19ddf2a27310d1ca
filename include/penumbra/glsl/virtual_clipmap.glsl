// The sun's virtual shadow map clipmap (included by penumbra/glsl/virtual.glsl and by
// Penumbra's own page passes): which level a receiver samples, its texel in that level, and
// the page table entry of a page. The same operations as Penumbra's CPU math, so that the
// pages a pixel's marking requests are the pages its sampling reads. Reads the
// PenumbraVirtualClipmap named by PENUMBRA_VIRTUAL_CLIPMAP (penumbra_virtual by default).
#ifndef PENUMBRA_GLSL_VIRTUAL_CLIPMAP
#define PENUMBRA_GLSL_VIRTUAL_CLIPMAP

#include "penumbra/glsl/dialect.glsl"

#ifndef PENUMBRA_VIRTUAL_CLIPMAP
#define PENUMBRA_VIRTUAL_CLIPMAP penumbra_virtual
#endif

PENUMBRA_CONST uint kPenumbraVirtualPageTexels = 128u;
// The pool image is a 2D array whose layers hold 4 x 4 pages (512^2 texels).
PENUMBRA_CONST uint kPenumbraVirtualPoolLayerPages = 4u;

PENUMBRA_CONST uint kPenumbraVirtualPagesPerPoolLayer = kPenumbraVirtualPoolLayerPages * kPenumbraVirtualPoolLayerPages;

// A physical page's place in its pool layer: pages fill a layer row by row (the place is also
// the viewport the page is drawn through).
uint penumbra_virtual_pool_place(uint physical) { return physical % kPenumbraVirtualPagesPerPoolLayer; }

// Where physical page `physical` lies in the pool: xy its page in the layer, z the layer.
ivec3 penumbra_virtual_pool_page(uint physical) {
    const uint place = penumbra_virtual_pool_place(physical);
    return ivec3(int(place % kPenumbraVirtualPoolLayerPages), int(place / kPenumbraVirtualPoolLayerPages),
                 int(physical / kPenumbraVirtualPagesPerPoolLayer));
}

// A point's position across the light (metres; every level's texel grid is a scale of it).
vec2 penumbra_virtual_light_xy(vec3 world_position) {
    return PENUMBRA_MUL(PENUMBRA_VIRTUAL_CLIPMAP.light_view, vec4(world_position, 1.0)).xy;
}

// The virtual texel in `level` of a point across the light at `light_xy`, from the window's
// corner: the world grid's texel less the window's first texel (a whole number of pages).
vec2 penumbra_virtual_texel_at(uint level, vec2 light_xy) {
    precise vec2 texel = light_xy * PENUMBRA_VIRTUAL_CLIPMAP.levels[level].texels_per_metre;
    return texel - vec2(PENUMBRA_VIRTUAL_CLIPMAP.levels[level].first_page * int(kPenumbraVirtualPageTexels));
}

// A receiver's virtual texel in `level` (penumbra_virtual_texel_at).
vec2 penumbra_virtual_texel_of(uint level, vec3 world_position) {
    return penumbra_virtual_texel_at(level, penumbra_virtual_light_xy(world_position));
}

bool penumbra_virtual_window_holds(vec2 texel, float margin_texels) {
    const float side = float(PENUMBRA_VIRTUAL_CLIPMAP.pages_per_side * kPenumbraVirtualPageTexels);
    return all(greaterThanEqual(texel, vec2(margin_texels))) && all(lessThanEqual(texel, vec2(side - margin_texels)));
}

// The finest level whose texel is no larger than the receiver's pixel footprint times
// 2^lod_bias, or the first coarser one whose window holds it `margin_texels` inside; -1
// when none does (penumbra_select_virtual_level).
int penumbra_select_virtual_level(vec3 world_position, float margin_texels) {
    const float footprint =
        (PENUMBRA_VIRTUAL_CLIPMAP.footprint_base + length(world_position - PENUMBRA_VIRTUAL_CLIPMAP.camera_position.xyz) * PENUMBRA_VIRTUAL_CLIPMAP.camera_position.w) * PENUMBRA_VIRTUAL_CLIPMAP.lod_scale;
    const float finest = PENUMBRA_VIRTUAL_CLIPMAP.levels[0].texel_world_size;
    const int last = int(PENUMBRA_VIRTUAL_CLIPMAP.level_count) - 1;
    const int wanted = footprint > finest ? int(floor(log2(footprint / finest))) : 0;
    const vec2 light_xy = penumbra_virtual_light_xy(world_position);
    for (int level = min(wanted, last); level <= last; ++level) {
        if (penumbra_virtual_window_holds(penumbra_virtual_texel_at(uint(level), light_xy), margin_texels)) return level;
    }
    return -1;
}

int penumbra_floor_mod(int value, int modulus) {
    const int remainder = value % modulus;
    return remainder < 0 ? remainder + modulus : remainder;
}

// The page table holds every level's slots in turn: entry = level * slots per level + slot.
uint penumbra_virtual_slots_per_level() {
    return PENUMBRA_VIRTUAL_CLIPMAP.pages_per_side * PENUMBRA_VIRTUAL_CLIPMAP.pages_per_side;
}
uint penumbra_virtual_level_of_entry(uint entry) { return entry / penumbra_virtual_slots_per_level(); }
uint penumbra_virtual_slot_of_entry(uint entry) { return entry % penumbra_virtual_slots_per_level(); }

// The page table entry of a window page (toroidal: the world page modulo the window's side).
uint penumbra_virtual_entry(uint level, ivec2 window_page) {
    const int side = int(PENUMBRA_VIRTUAL_CLIPMAP.pages_per_side);
    const ivec2 world_page = PENUMBRA_VIRTUAL_CLIPMAP.levels[level].first_page + window_page;
    const uint slot = uint(penumbra_floor_mod(world_page.x, side) + penumbra_floor_mod(world_page.y, side) * side);
    return level * penumbra_virtual_slots_per_level() + slot;
}

// The world page a slot holds for a window starting at `first_page`.
ivec2 penumbra_virtual_world_page_of_slot(ivec2 first_page, uint slot) {
    const int side = int(PENUMBRA_VIRTUAL_CLIPMAP.pages_per_side);
    const ivec2 slot_xy = ivec2(int(slot % PENUMBRA_VIRTUAL_CLIPMAP.pages_per_side), int(slot / PENUMBRA_VIRTUAL_CLIPMAP.pages_per_side));
    return first_page + ivec2(penumbra_floor_mod(slot_xy.x - first_page.x, side),
                              penumbra_floor_mod(slot_xy.y - first_page.y, side));
}

#endif
