#pragma once
// Ground truth for shadow rays: an Embree BVH of every Scene instance (one BVH per mesh,
// instanced with its world transform), with alpha-masked materials tested in an
// occlusion filter function exactly as the shadow pass tests them (alpha_mask.hpp).
// Thread-safe: occluded() may be called from many threads at once.
#include <cstdint>
#include <memory>

#include "penumbra/scene/scene.hpp"

namespace penumbra::quality {

class ShadowRayTracer {
public:
    // Keeps a reference to `scene` (the filter reads its meshes, materials and textures).
    explicit ShadowRayTracer(const Scene& scene);
    ~ShadowRayTracer();
    ShadowRayTracer(const ShadowRayTracer&) = delete;
    ShadowRayTracer& operator=(const ShadowRayTracer&) = delete;

    // True when an opaque (or alpha-tested opaque) surface lies on origin + t * direction
    // for t in (0, infinity).
    bool occluded(const glm::vec3& origin, const glm::vec3& direction) const;

    // The same for t in (0, max_distance), with `direction` a unit vector: a segment toward
    // a light point (spot and point lights), so that nothing behind the light occludes.
    bool occluded(const glm::vec3& origin, const glm::vec3& direction, float max_distance) const;

    uint64_t triangle_count() const { return triangles_; }

private:
    struct Embree;
    std::unique_ptr<Embree> embree_;
    uint64_t triangles_ = 0;
};

}  // namespace penumbra::quality
