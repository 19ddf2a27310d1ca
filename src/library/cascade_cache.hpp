#pragma once
// Cached cascades between frames (Settings::shadow.cache_static_casters): which cascade
// each layer of the pass's cache holds the static casters of, and whether dynamic casters
// were drawn over the map's layer; and each frame's draws from that (core/shadow_cache.hpp
// plans the texels, this picks the casters for them). No Vulkan calls.
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

    // The draws of every cascade of `set`. Uncached: every caster the cascade may receive
    // a shadow from, in one list per layer. Cached: the static casters only where the plan
    // says (everything without a usable cache), the dynamic ones every frame. `changes`
    // are the world bounds of static casters changed since the last commit().
    std::vector<passes::CascadeDraws> plan(const CascadeSet& set, const passes::CasterScene& scene, bool cull,
                                           bool cached, std::span<const Aabb> changes, uint32_t resolution) const;

    // The frame that plan() made was recorded: the cache now holds `set`'s static casters.
    void commit(const CascadeSet& set, const std::vector<passes::CascadeDraws>& draws);

private:
    std::vector<std::optional<Cascade>> cached_;
    std::vector<bool> dynamic_over_;  // dynamic casters drawn over the map's layer last time
};

CascadeDrawStats cascade_draw_stats(const passes::CascadeDraws& draws, uint32_t resolution);

// Calls `visit` with every draw index of the cascade's lists (a draw in two redraw
// rectangles twice: it is drawn twice).
template <typename Visit>
void for_each_draw(const passes::CascadeDraws& draws, Visit visit) {
    for (const uint32_t draw : draws.casters) visit(draw);
    for (const passes::CascadeDraws::Redraw& redraw : draws.redraw) {
        for (const uint32_t draw : redraw.casters) visit(draw);
    }
    for (const uint32_t draw : draws.dynamic) visit(draw);
}

}  // namespace penumbra::library
