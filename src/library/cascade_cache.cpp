#include "library/cascade_cache.hpp"

#include <algorithm>
#include <utility>

namespace penumbra::library {
namespace {

using passes::CascadeDraws;

// A draw and the window texels it can reach (caster_footprint; the whole window without
// culling).
struct Footprint {
    uint32_t draw = 0;
    TexelRect window;
};

// A draw's footprint in the cascade (the whole window without culling).
Footprint footprint_of(const Cascade& cascade, const passes::CasterScene& scene, bool cull, uint32_t resolution,
                       uint32_t draw) {
    return {draw, cull ? caster_footprint(cascade, scene.draws[draw].world_bounds, resolution) : whole_map(resolution)};
}

// The footprints of the draws of `scene` that pass `keep`, projected once per cascade and
// then tested against every piece and rectangle; none when the CPU does not list the
// casters (`list_casters` false: the GPU culls them).
template <typename Keep>
std::vector<Footprint> footprints(bool list_casters, const Cascade& cascade, const passes::CasterScene& scene,
                                  bool cull, uint32_t resolution, Keep keep) {
    if (!list_casters) return {};
    std::vector<Footprint> result;
    result.reserve(scene.draws.size());
    for (uint32_t d = 0; d < scene.draws.size(); ++d) {
        if (!keep(scene.draws[d])) continue;
        const Footprint footprint = footprint_of(cascade, scene, cull, resolution, d);
        if (!footprint.window.empty()) result.push_back(footprint);
    }
    return result;
}

// The dynamic draws' footprints (CasterScene::dynamic_draws: no pass over every draw).
std::vector<Footprint> dynamic_footprints(const Cascade& cascade, const passes::CasterScene& scene, bool cull,
                                          uint32_t resolution) {
    std::vector<Footprint> result;
    for (const uint32_t d : scene.dynamic_draws) {
        const Footprint footprint = footprint_of(cascade, scene, cull, resolution, d);
        if (!footprint.window.empty()) result.push_back(footprint);
    }
    return result;
}

// The regions that draw `window_rect`: its pieces in the layer, each with the casters
// whose footprint meets it. `cover`, when given, receives per region the texels its
// casters can reach (window texels, inside the region's piece). One pass over the casters:
// a footprint meets the pieces on the sides of the layer's wrap lines it reaches (a
// forest's thousands of casters per cascade).
std::vector<CascadeDraws::Region> regions_of(const TexelRect& window_rect, const Cascade& cascade,
                                             const std::vector<Footprint>& casters, uint32_t resolution,
                                             std::vector<TexelRect>* cover = nullptr) {
    const std::vector<LayerPiece> pieces = layer_pieces(window_rect, cascade.layer_origin, resolution);
    std::vector<CascadeDraws::Region> regions;
    int region_of_tile[4] = {-1, -1, -1, -1};
    for (const LayerPiece& piece : pieces) {
        region_of_tile[piece.tile] = static_cast<int>(regions.size());
        regions.push_back({piece.layer, piece.tile, {}, piece.window});
    }
    std::vector<TexelRect> reach(regions.size());
    const glm::ivec2 split = glm::ivec2(static_cast<int32_t>(resolution)) - cascade.layer_origin;
    for (const Footprint& caster : casters) {
        const TexelRect overlap = intersect(caster.window, window_rect);
        if (overlap.empty()) continue;
        // Which sides of the wrap lines (split.x, split.y) the footprint reaches.
        const bool left = overlap.min.x < split.x;
        const bool right = overlap.max.x > split.x;
        const bool top = overlap.min.y < split.y;
        const bool bottom = overlap.max.y > split.y;
        for (uint32_t tile = 0; tile < 4; ++tile) {
            const int index = region_of_tile[tile];
            const bool across = (tile & 1u) ? right : left;
            const bool down = (tile & 2u) ? bottom : top;
            if (index < 0 || !across || !down) continue;
            regions[static_cast<size_t>(index)].casters.push_back(caster.draw);
            if (!cover) continue;
            const TexelRect part = intersect(overlap, pieces[static_cast<size_t>(index)].window);
            TexelRect& total = reach[static_cast<size_t>(index)];
            total = total.empty() ? part : TexelRect{glm::min(total.min, part.min), glm::max(total.max, part.max)};
        }
    }
    for (size_t r = 0; cover && r < regions.size(); ++r) {
        if (!reach[r].empty()) cover->push_back(reach[r]);
    }
    return regions;
}

bool is_static(const passes::CasterDraw& draw) { return !draw.dynamic; }

// The window texels whose depth may differ from the last frame's in a reused cascade (for
// the moments): what is redrawn, what the dynamic casters reach now and reached last frame
// (moved with the window), and after a move one texel along the window's edges, whose
// moments were clamped at the old edges or are clamped at the new ones.
std::vector<TexelRect> changed_texels(const CascadeUpdate& update, const std::vector<TexelRect>& dynamic_now,
                                      const std::vector<TexelRect>& dynamic_before, uint32_t resolution) {
    const TexelRect window = whole_map(resolution);
    std::vector<TexelRect> changed = update.redraw;
    changed.insert(changed.end(), dynamic_now.begin(), dynamic_now.end());
    for (const TexelRect& before : dynamic_before) {
        const TexelRect moved = intersect({before.min + update.shift, before.max + update.shift}, window);
        if (!moved.empty()) changed.push_back(moved);
    }
    const int32_t side = static_cast<int32_t>(resolution);
    if (update.shift.x != 0) {
        changed.push_back({{0, 0}, {1, side}});
        changed.push_back({{side - 1, 0}, {side, side}});
    }
    if (update.shift.y != 0) {
        changed.push_back({{0, 0}, {side, 1}});
        changed.push_back({{0, side - 1}, {side, side}});
    }
    return changed;
}

// The layer texels of `window_rects` of a cascade placed at `layer_origin` (each rectangle
// lies in one piece of the window, as regions_of's reach does).
std::vector<TexelRect> layer_texels(const std::vector<TexelRect>& window_rects, glm::ivec2 layer_origin,
                                    uint32_t resolution) {
    std::vector<TexelRect> rects;
    for (const TexelRect& rect : window_rects) {
        for (const LayerPiece& piece : layer_pieces(rect, layer_origin, resolution)) rects.push_back(piece.layer);
    }
    return rects;
}

// `before`: the cascade the map's layer was last drawn for, with where the dynamic casters
// reached then (its window texels).
CascadeDraws cached_draws(const CascadeUpdate& update, const Cascade& cascade, const passes::CasterScene& scene,
                          bool cull, bool list_casters, const Cascade* before,
                          const std::vector<TexelRect>& dynamic_window_before, bool cache_complete,
                          uint32_t resolution) {
    const TexelRect window = whole_map(resolution);
    CascadeDraws draws;
    draws.layer_origin = cascade.layer_origin;
    const std::vector<Footprint> dynamic = dynamic_footprints(cascade, scene, cull, resolution);
    if (!dynamic.empty()) draws.dynamic = regions_of(window, cascade, dynamic, resolution, &draws.dynamic_window);
    if (!update.reuse) {
        draws.regions = regions_of(window, cascade,
                                   footprints(list_casters, cascade, scene, cull, resolution, is_static), resolution);
        // The cache must hold the static texels the dynamic casters are about to cover.
        if (!draws.dynamic_window.empty()) draws.store = {window};
        return draws;
    }
    draws.reuse = true;
    draws.shift = update.shift;
    // The static texels under last frame's dynamic casters come back from the cache.
    draws.restore = layer_texels(dynamic_window_before, before->layer_origin, resolution);
    draws.changed = changed_texels(update, draws.dynamic_window, dynamic_window_before, resolution);
    // Static footprints only when something is redrawn (a still camera projects none).
    const std::vector<Footprint> statics = update.redraw.empty()
                                               ? std::vector<Footprint>{}
                                               : footprints(list_casters, cascade, scene, cull, resolution, is_static);
    for (const TexelRect& rect : update.redraw) {
        std::vector<CascadeDraws::Region> regions = regions_of(rect, cascade, statics, resolution);
        draws.regions.insert(draws.regions.end(), regions.begin(), regions.end());
    }
    if (cache_complete) {
        for (const CascadeDraws::Region& region : draws.regions) draws.store.push_back(region.rect);
    } else if (!draws.dynamic_window.empty()) {
        draws.store = {window};
    }
    return draws;
}

}  // namespace

void CascadeCache::invalidate() { layers_.clear(); }

std::vector<CascadeDraws> CascadeCache::plan(const CascadeSet& set, const passes::CasterScene& scene, bool cull,
                                             bool cached, std::span<const core::Aabb> changes, uint32_t resolution,
                                             bool list_casters) const {
    std::vector<CascadeDraws> draws(set.cascades.size());
    for (size_t c = 0; c < set.cascades.size(); ++c) {
        const Cascade& cascade = set.cascades[c];
        if (!cached) {
            const auto any = [](const passes::CasterDraw&) { return true; };
            draws[c].layer_origin = cascade.layer_origin;
            draws[c].regions = regions_of(whole_map(resolution), cascade,
                                          footprints(list_casters, cascade, scene, cull, resolution, any), resolution);
            continue;
        }
        const std::optional<Layer>& previous = c < layers_.size() ? layers_[c] : std::nullopt;
        const std::optional<Cascade> kept = previous ? std::optional<Cascade>(previous->cascade) : std::nullopt;
        const CascadeUpdate update = plan_cascade_update(kept, cascade, resolution, changes);
        const std::vector<TexelRect> none;
        draws[c] =
            cached_draws(update, cascade, scene, cull, list_casters, previous ? &previous->cascade : nullptr,
                         previous ? previous->dynamic_window : none, previous && previous->cache_complete, resolution);
    }
    return draws;
}

void CascadeCache::commit(const CascadeSet& set, const std::vector<CascadeDraws>& draws, uint32_t resolution) {
    std::vector<std::optional<Layer>> layers(set.cascades.size());
    for (size_t c = 0; c < set.cascades.size(); ++c) {
        const CascadeDraws& cascade = draws[c];
        const bool was_complete = c < layers_.size() && layers_[c] && layers_[c]->cache_complete;
        const bool stored_all = cascade.store.size() == 1 && cascade.store.front() == whole_map(resolution);
        layers[c] = Layer{set.cascades[c], stored_all || (cascade.reuse && was_complete), cascade.dynamic_window};
    }
    layers_ = std::move(layers);
}

CascadeDrawStats cascade_draw_stats(const CascadeDraws& draws, uint32_t resolution) {
    CascadeDrawStats stats;
    stats.cache_reused = draws.reuse;
    stats.texels_rendered = draws.reuse ? 0u : static_cast<uint64_t>(whole_map(resolution).area());
    for (const CascadeDraws::Region& region : draws.regions) {
        stats.draws += static_cast<uint32_t>(region.casters.size());
        if (draws.reuse) stats.texels_rendered += static_cast<uint64_t>(region.rect.area());
    }
    for (const CascadeDraws::Region& region : draws.dynamic)
        stats.draws += static_cast<uint32_t>(region.casters.size());
    for (const TexelRect& rect : draws.restore) stats.texels_copied += static_cast<uint64_t>(rect.area());
    for (const TexelRect& rect : draws.store) stats.texels_copied += static_cast<uint64_t>(rect.area());
    return stats;
}

}  // namespace penumbra::library
