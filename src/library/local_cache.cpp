#include "library/local_cache.hpp"

namespace penumbra::library {

std::vector<std::optional<LocalLayerKey>> local_layer_keys(std::span<const core::Light> lights,
                                                           const LocalShadowPlan& plan) {
    std::vector<std::optional<LocalLayerKey>> keys(plan.layer_count);
    for (const LocalShadowSlot& slot : plan.slots) {
        const core::Light& light = lights[slot.light];
        const glm::vec4 sphere = local_shadow_is_cube(light) ? glm::vec4(light.position, light.range) : glm::vec4(0.0f);
        for (size_t face = 0; face < slot.view_projection.size(); ++face) {
            const size_t layer = slot.first_layer + face;
            if (layer < keys.size()) keys[layer] = LocalLayerKey{slot.view_projection[face], slot.resolution, sphere};
        }
    }
    return keys;
}

std::vector<bool> LocalShadowCache::kept_layers(std::span<const core::Light> lights, const LocalShadowPlan& plan,
                                                const passes::CasterScene& scene, std::span<const core::Aabb> changes,
                                                uint64_t map_generation) const {
    std::vector<bool> kept(plan.layer_count, false);
    if (map_generation != generation_ || layers_.empty()) return kept;
    std::vector<core::Aabb> dynamic;
    for (const uint32_t draw : scene.dynamic_draws) dynamic.push_back(scene.draws[draw].world_bounds);
    const std::vector<std::optional<LocalLayerKey>> keys = local_layer_keys(lights, plan);
    for (size_t layer = 0; layer < keys.size(); ++layer) {
        if (!keys[layer]) continue;
        const std::optional<LocalLayerKey> before = layer < layers_.size() ? layers_[layer] : std::nullopt;
        kept[layer] = local_layer_reusable(before, *keys[layer], changes, dynamic);
    }
    return kept;
}

void LocalShadowCache::commit(std::span<const core::Light> lights, const LocalShadowPlan& plan,
                              uint64_t map_generation) {
    layers_ = local_layer_keys(lights, plan);
    generation_ = map_generation;
}

}  // namespace penumbra::library
