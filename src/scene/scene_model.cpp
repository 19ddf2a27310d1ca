#include "penumbra/scene/scene.hpp"

#include <algorithm>

namespace penumbra {

Aabb Scene::world_bounds() const {
    Aabb bounds;
    for (const Instance& instance : instances) {
        bounds.expand(transform_aabb(meshes.at(instance.mesh).bounds, instance.world));
    }
    return bounds;
}

namespace {

bool contains(const Aabb& outer, const Aabb& inner) {
    return glm::all(glm::lessThanEqual(outer.min, inner.min)) && glm::all(glm::greaterThanEqual(outer.max, inner.max));
}

}  // namespace

std::vector<std::string> Scene::enclosing_casters() const {
    std::vector<std::string> names;
    if (instances.size() < 2) return names;
    Aabb eye;
    eye.expand(camera.eye);
    std::vector<Aabb> bounds(instances.size());
    for (size_t i = 0; i < instances.size(); ++i) {
        bounds[i] = transform_aabb(meshes.at(instances[i].mesh).bounds, instances[i].world);
    }
    for (size_t i = 0; i < instances.size(); ++i) {
        if (!instances[i].cast_shadows) continue;
        bool encloses = contains(bounds[i], eye);
        for (size_t j = 0; j < instances.size() && encloses; ++j) {
            encloses = j == i || contains(bounds[i], bounds[j]);
        }
        if (encloses && std::find(names.begin(), names.end(), instances[i].name) == names.end()) {
            names.push_back(instances[i].name);
        }
    }
    return names;
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
