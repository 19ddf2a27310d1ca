#pragma once
// Cascades' draws per frame, and cached cascades between frames
// (Settings::shadow.cache_static_casters): which cascade each map layer holds the static
// casters of, whether the cache image holds them too, and where dynamic casters were drawn
// over the map; and each frame's draws from that (core/shadow_cache.hpp plans the texels
// and splits them into the layer's tiles, this picks the casters for them). No Vulkan calls.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/cascades.hpp"
#include "core/shadow_cache.hpp"
#include "passes/casters.hpp"
#include "passes/shadow_pass.hpp"

namespace penumbra::library {

// What a cascade's draws cost this frame (FrameInfo::cascades).
struct CascadeDrawStats {
    uint32_t draws = 0;
    bool cache_reused = false;
    uint64_t texels_rendered = 0;
    uint64_t texels_copied = 0;
};

class CascadeCache {
public:
    // Forgets every cascade: the next frame draws everything (settings or the sun changed).
    void invalidate();

    // The draws of every cascade of `set` (placed in its layers: place_in_layers), per
    // piece of the window (layer_pieces). Uncached: every caster whose footprint meets the
    // piece. Cached: the static casters only where the plan says (everything without a
    // usable cache), the dynamic ones every frame, and the copies between the map and the
    // cache that keep the cache's static texels where the dynamic casters draw. `changes`
    // are the world bounds of static casters changed since the last commit().
    // `list_casters` false (the layered strategy, whose GPU culls the casters into the
    // regions): the regions' lists of static casters stay empty, and no pass visits every
    // caster; the dynamic casters are still listed (their reach is copied to and from the cache).
    std::vector<passes::CascadeDraws> plan(const CascadeSet& set, const passes::CasterScene& scene, bool cull,
                                           bool cached, std::span<const core::Aabb> changes, uint32_t resolution,
                                           bool list_casters = true) const;

    // The frame that plan() made was recorded: the map now holds `set`'s static casters.
    void commit(const CascadeSet& set, const std::vector<passes::CascadeDraws>& draws, uint32_t resolution);

private:
    struct Layer {
        Cascade cascade;                        // the map layer's static texels were drawn for it
        bool cache_complete = false;            // the cache holds the same static texels as the map
        std::vector<TexelRect> dynamic_window;  // window texels the dynamic casters were drawn over
    };
    std::vector<std::optional<Layer>> layers_;
};

CascadeDrawStats cascade_draw_stats(const passes::CascadeDraws& draws, uint32_t resolution);

// Calls `visit` with every draw index of the cascade's lists (a draw in two regions
// twice: it is drawn twice).
template <typename Visit>
void for_each_draw(const passes::CascadeDraws& draws, Visit visit) {
    for (const passes::CascadeDraws::Region& region : draws.regions) {
        for (const uint32_t draw : region.casters) visit(draw);
    }
    for (const passes::CascadeDraws::Region& region : draws.dynamic) {
        for (const uint32_t draw : region.casters) visit(draw);
    }
}

}  // namespace penumbra::library
