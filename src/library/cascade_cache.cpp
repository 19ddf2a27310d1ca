#include "library/cascade_cache.hpp"

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace penumbra::library {
namespace {

// The draws of `scene` that pass `keep` and, with culling, `may_cast`.
template <typename Keep, typename MayCast>
passes::DrawList select_draws(const passes::CasterScene& scene, bool cull, Keep keep, MayCast may_cast) {
    passes::DrawList list;
    for (uint32_t d = 0; d < scene.draws.size(); ++d) {
        const passes::CasterDraw& draw = scene.draws[d];
        if (keep(draw) && (!cull || may_cast(draw.world_bounds))) list.push_back(d);
    }
    return list;
}

passes::CascadeDraws cached_draws(const CascadeUpdate& update, const Cascade& cascade, const passes::CasterScene& scene,
                                  bool cull, bool dynamic_over, uint32_t resolution) {
    const auto is_static = [](const passes::CasterDraw& draw) { return !draw.dynamic; };
    const auto is_dynamic = [](const passes::CasterDraw& draw) { return draw.dynamic; };
    const auto in_cascade = [&](const Aabb& box) { return caster_may_shadow_cascade(cascade, box); };
    passes::CascadeDraws draws;
    draws.dynamic = select_draws(scene, cull, is_dynamic, in_cascade);
    if (!update.reuse) {
        draws.casters = select_draws(scene, cull, is_static, in_cascade);
        draws.store = true;
        return draws;
    }
    draws.reuse = true;
    draws.shift = update.shift;
    draws.restore = update.shift != glm::ivec2(0) || dynamic_over;
    // Culling for the redraw: a static caster goes into a rectangle its footprint meets.
    // Each footprint is projected once, then tested against every rectangle.
    std::vector<std::pair<uint32_t, TexelRect>> footprints;
    if (!update.redraw.empty()) {
        for (uint32_t d = 0; d < scene.draws.size(); ++d) {
            if (!is_static(scene.draws[d])) continue;
            const TexelRect footprint =
                cull ? caster_footprint(cascade, scene.draws[d].world_bounds, resolution) : whole_map(resolution);
            if (!footprint.empty()) footprints.emplace_back(d, footprint);
        }
    }
    for (const TexelRect& rect : update.redraw) {
        passes::DrawList list;
        for (const auto& [draw, footprint] : footprints) {
            if (!intersect(footprint, rect).empty()) list.push_back(draw);
        }
        draws.redraw.push_back({rect, std::move(list)});
    }
    draws.store = update.shift != glm::ivec2(0) || !update.redraw.empty();
    return draws;
}

}  // namespace

void CascadeCache::invalidate() {
    cached_.clear();
    dynamic_over_.clear();
}

std::vector<passes::CascadeDraws> CascadeCache::plan(const CascadeSet& set, const passes::CasterScene& scene, bool cull,
                                                     bool cached, std::span<const Aabb> changes,
                                                     uint32_t resolution) const {
    std::vector<passes::CascadeDraws> draws(set.cascades.size());
    for (size_t c = 0; c < set.cascades.size(); ++c) {
        const Cascade& cascade = set.cascades[c];
        if (!cached) {
            const auto any = [](const passes::CasterDraw&) { return true; };
            draws[c].casters = select_draws(scene, cull, any,
                                            [&](const Aabb& box) { return caster_may_shadow_cascade(cascade, box); });
            continue;
        }
        const std::optional<Cascade> previous = c < cached_.size() ? cached_[c] : std::nullopt;
        const bool dynamic_over = c < dynamic_over_.size() && dynamic_over_[c];
        const CascadeUpdate update = plan_cascade_update(previous, cascade, resolution, changes);
        draws[c] = cached_draws(update, cascade, scene, cull, dynamic_over, resolution);
    }
    return draws;
}

void CascadeCache::commit(const CascadeSet& set, const std::vector<passes::CascadeDraws>& draws) {
    cached_.assign(set.cascades.begin(), set.cascades.end());
    dynamic_over_.clear();
    for (const passes::CascadeDraws& cascade : draws) dynamic_over_.push_back(!cascade.dynamic.empty());
}

CascadeDrawStats cascade_draw_stats(const passes::CascadeDraws& draws, uint32_t resolution) {
    CascadeDrawStats stats;
    const int64_t layer = whole_map(resolution).area();
    stats.cache_reused = draws.reuse;
    stats.draws = static_cast<uint32_t>(draws.casters.size() + draws.dynamic.size());
    stats.texels_rendered = draws.reuse ? 0u : static_cast<uint64_t>(layer);
    for (const passes::CascadeDraws::Redraw& redraw : draws.redraw) {
        stats.draws += static_cast<uint32_t>(redraw.casters.size());
        stats.texels_rendered += static_cast<uint64_t>(redraw.rect.area());
    }
    const int64_t side = static_cast<int64_t>(resolution);
    if (draws.restore) {
        stats.texels_copied += static_cast<uint64_t>(std::max<int64_t>(side - std::abs(draws.shift.x), 0) *
                                                     std::max<int64_t>(side - std::abs(draws.shift.y), 0));
    }
    if (draws.store) stats.texels_copied += static_cast<uint64_t>(layer);
    return stats;
}

}  // namespace penumbra::library
