#pragma once
// Ground truth for shadow rays: an Embree BVH of every Scene instance (one BVH per mesh,
// instanced with its world transform), with alpha-masked materials tested in an
// occlusion filter function exactly as the shadow pass tests them (alpha_mask.hpp).
// Thread-safe: occluded() may be called from many threads at once.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "penumbra/scene/scene.hpp"

namespace penumbra::quality {

// Which instances a tracer holds: the shadow casters (what the shadow maps draw), or
// every instance (what the camera sees).
enum class TracedInstances { Casters, Everything };

// The first surface a ray meets.
struct SurfaceHit {
    float distance = 0.0f;  // along the ray's unit direction
    size_t instance = 0;    // index into Scene::instances
};

class ShadowRayTracer {
public:
    // Keeps a reference to `scene` (the filter reads its meshes, materials and textures).
    // `only`, when not empty, limits the tracer to those instances (indices into
    // Scene::instances) among the selected ones.
    explicit ShadowRayTracer(const Scene& scene, TracedInstances selection = TracedInstances::Casters,
                             std::span<const size_t> only = {});
    ~ShadowRayTracer();
    ShadowRayTracer(const ShadowRayTracer&) = delete;
    ShadowRayTracer& operator=(const ShadowRayTracer&) = delete;

    // True when an opaque (or alpha-tested opaque) surface lies on origin + t * direction
    // for t in (0, infinity).
    bool occluded(const glm::vec3& origin, const glm::vec3& direction) const;

    // The same for t in (0, max_distance), with `direction` a unit vector: a segment toward
    // a light point (spot and point lights), so that nothing behind the light occludes.
    bool occluded(const glm::vec3& origin, const glm::vec3& direction, float max_distance) const;

    // The nearest surface on origin + t * direction for t in (min_distance, max_distance),
    // `direction` a unit vector; alpha-tested as occluded() tests.
    std::optional<SurfaceHit> first_hit(const glm::vec3& origin, const glm::vec3& direction, float min_distance,
                                        float max_distance) const;

    uint64_t triangle_count() const { return triangles_; }

private:
    struct Embree;
    std::unique_ptr<Embree> embree_;
    uint64_t triangles_ = 0;
};

}  // namespace penumbra::quality
