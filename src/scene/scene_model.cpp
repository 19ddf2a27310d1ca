#include "penumbra/scene/scene.hpp"

namespace penumbra {

Aabb Scene::world_bounds() const {
    Aabb bounds;
    for (const Instance& instance : instances) {
        bounds.expand(transform_aabb(meshes.at(instance.mesh).bounds, instance.world));
    }
    return bounds;
}

const Light* Scene::sun() const {
    for (const Light& light : lights) {
        if (light.type == LightType::Directional) return &light;
    }
    return nullptr;
}

uint64_t Scene::triangle_count() const {
    uint64_t count = 0;
    for (const Instance& instance : instances) count += meshes.at(instance.mesh).indices.size() / 3;
    return count;
}

}  // namespace penumbra
