#pragma once
// Cached cascades (render only what changed): which texels of a cascade's depth map the
// previous frame's static casters still give, and which must be rendered again. Engines
// that cache shadow maps (CryEngine's cached far cascades, Unity HDRP's mixed cached maps,
// UE5's virtual shadow map pages) keep the depths of casters that did not move; with the
// stable fit a cascade only ever moves by whole texels in its own plane, and with the
// static instances' depth range along the light (compute_cascades) its depth mapping stays
// put; placed toroidally in its layer (place_in_layers) its kept texels stay where they
// are, and only the strips the move exposes (and the footprints of static casters that
// changed) are drawn again.
// Pure functions; no Vulkan.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/cascades.hpp"

namespace penumbra {

// Texels [min, max) of one map layer (x right, y down as the rasteriser counts them).
struct TexelRect {
    glm::ivec2 min{0};
    glm::ivec2 max{0};

    bool empty() const { return max.x <= min.x || max.y <= min.y; }
    int64_t area() const { return empty() ? 0 : int64_t{max.x - min.x} * (max.y - min.y); }
    friend bool operator==(const TexelRect&, const TexelRect&) = default;
};

TexelRect intersect(const TexelRect& a, const TexelRect& b);

// The whole map: [0, resolution)^2.
TexelRect whole_map(uint32_t resolution);

// Toroidal cascades (Settings' per-cascade passes): sets every cascade's layer_origin to
// its texel_origin modulo `resolution` (zero when `toroidal` is false: the layer is the
// window). A world texel then stays in one layer texel while the cascade moves by whole
// texels, as the clipmaps of Tanner et al. 1998 and the scrolling virtual shadow maps of
// engines keep theirs: a cached cascade keeps its texels where they are instead of copying
// them, and a cached and an uncached render draw every caster at the same layer texels.
void place_in_layers(CascadeSet& set, uint32_t resolution, bool toroidal);

// A part of a window rectangle that does not cross the layer's edges: where it lies in the
// window and in the layer, and which tile of the world grid it is in (bit 0: the window's
// columns that wrapped past the layer's right edge, bit 1: its rows past the bottom; the
// caster pass draws each tile with its own offset, CasterPushConstants::tile).
struct LayerPiece {
    TexelRect window;
    TexelRect layer;
    uint32_t tile = 0;
    friend bool operator==(const LayerPiece&, const LayerPiece&) = default;
};

// The pieces of `window_rect` (window texels, inside [0, resolution)^2) in a layer whose
// window starts at `layer_origin`: one to four, disjoint, their window rectangles covering
// `window_rect` exactly, each layer rectangle the window one moved by a whole number of
// layer sides.
std::vector<LayerPiece> layer_pieces(const TexelRect& window_rect, glm::ivec2 layer_origin, uint32_t resolution);

// How `current` lies against `cached` when it is the same cascade moved in its plane: the
// same light view, texel size and depth mapping, so that only the window's origin in the
// world's texel grid differs (Cascade::texel_origin, whole numbers). The shift is in
// texels: what the cached map holds at texel p belongs at texel p + shift of the current
// one. nullopt otherwise (the light, the cascade's size or the scene's depth range changed).
std::optional<glm::ivec2> whole_texel_shift(const Cascade& cached, const Cascade& current);

// The texels of the current map that a cached map moved by `shift` does not cover: no
// rectangle for a zero shift, the whole map when the shift is a map or more, else a
// column strip and a row strip (at most two rectangles, disjoint).
std::vector<TexelRect> exposed_by_shift(glm::ivec2 shift, uint32_t resolution);

// The texels whose depth a caster inside `world_box` can set in the cascade: the box's
// footprint (its projection onto the map, an orthographic light's shadow-map texels),
// rounded out to whole texels plus one texel of margin for rasterisation at the edges,
// clipped to the map. Empty for an empty box, one outside the map or beyond its far side.
TexelRect caster_footprint(const Cascade& cascade, const core::Aabb& world_box, uint32_t resolution);

// What to draw into a cascade this frame when a cache of its static casters exists.
struct CascadeUpdate {
    bool reuse = false;             // false: the cache is unusable, render every static caster
    glm::ivec2 shift{0};            // the cached depths move by this many texels
    std::vector<TexelRect> redraw;  // clear and render the static casters here (disjoint is not required)
    int64_t redraw_texels() const;
};

// Above this share of the map, redrawing rectangles costs more than it saves: render all.
inline constexpr double kMaxRedrawShare = 0.5;
// More rectangles than this (many changed casters) are rendered as the whole map.
inline constexpr size_t kMaxRedrawRects = 16;

// Plans a cascade's update from its cache: `cached` is the cascade the cache was rendered
// for (nullopt: no cache), `changed_static_bounds` the world bounds, old and new, of every
// static caster added, moved, removed or changed since then. Reuse when the cascade moved
// by whole texels; redraw the exposed strips and the changed casters' footprints in the
// current cascade. Falls back to rendering everything when that is most of the map.
CascadeUpdate plan_cascade_update(const std::optional<Cascade>& cached, const Cascade& current, uint32_t resolution,
                                  std::span<const core::Aabb> changed_static_bounds);

// Cached spot and point lights: a layer of the local map (a spot, or one cube face) as it
// was rendered. The same key, and no caster change that can reach the layer, means its
// texels are still right.
struct LocalLayerKey {
    glm::mat4 view_projection{1.0f};  // world -> the layer's clip space
    uint32_t resolution = 0;          // texels per side used
    glm::vec4 sphere{0.0f};           // cube faces: the light's position and range (w), else w = 0
    friend bool operator==(const LocalLayerKey&, const LocalLayerKey&) = default;
};

// Whether a world box can cast into the layer (its frustum, and the light's range for a cube).
bool may_cast_into_layer(const LocalLayerKey& layer, const core::Aabb& box);

// Whether a layer rendered for `kept` can be sampled as it is for `current`: the same key
// (light position, direction, range, near plane and resolution unchanged), no static caster
// changed where it can cast into the layer (`changed_static_bounds`: old and new bounds),
// and no dynamic caster that can cast into it (`dynamic_bounds`: drawn every frame).
bool local_layer_reusable(const std::optional<LocalLayerKey>& kept, const LocalLayerKey& current,
                          std::span<const core::Aabb> changed_static_bounds,
                          std::span<const core::Aabb> dynamic_bounds);

}  // namespace penumbra
