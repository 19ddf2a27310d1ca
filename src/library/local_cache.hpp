#pragma once
// Cached spot and point shadows (Settings::shadow.cache_static_casters): which layers of
// the local map still hold what an earlier frame rendered for the same light, and each
// frame's decision to keep them (core/shadow_cache.hpp's local_layer_reusable). No Vulkan
// calls.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/local_lights.hpp"
#include "core/shadow_cache.hpp"
#include "passes/casters.hpp"
#include "passes/local_shadow_pass.hpp"

namespace penumbra::library {

// The key of each layer of `plan` (per slot: its spot layer or its six cube faces), indexed
// by layer.
std::vector<std::optional<LocalLayerKey>> local_layer_keys(std::span<const core::Light> lights,
                                                           const LocalShadowPlan& plan);

class LocalShadowCache {
public:
    // Forgets every layer: the next frame renders them all (settings changed).
    void invalidate() { layers_.clear(); }

    // Per layer index of `plan`, whether the map still holds it (nothing to cull or render),
    // when the map is the one the cache describes (`map_generation`,
    // LocalMaps::generation()). `changes` are the world bounds of static casters changed
    // since the last commit().
    std::vector<bool> kept_layers(std::span<const core::Light> lights, const LocalShadowPlan& plan,
                                  const passes::CasterScene& scene, std::span<const core::Aabb> changes,
                                  uint64_t map_generation) const;

    // The frame was recorded: the map's layers hold `plan`'s lights.
    void commit(std::span<const core::Light> lights, const LocalShadowPlan& plan, uint64_t map_generation);

private:
    std::vector<std::optional<LocalLayerKey>> layers_;
    uint64_t generation_ = 0;
};

}  // namespace penumbra::library
