#include "quality/local_light_reference.hpp"

#include <algorithm>
#include <cmath>

#include "quality/parallel_rows.hpp"
#include "quality/sun_disk_sampling.hpp"

namespace penumbra::quality {
namespace {

// Segments stop this far (relative to the light point's largest coordinate, at least
// 0.1 mm) before the light, the receiver-side offset's counterpart: a light placed on a
// surface is not occluded by that surface.
constexpr float kRelativeEndOffset = 1e-4f;

float smoothstep(float edge0, float edge1, float x) {
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

float end_offset(const glm::vec3& light) {
    return kRelativeEndOffset * std::max({std::abs(light.x), std::abs(light.y), std::abs(light.z), 1.0f});
}

// Whether the segment from `origin` to `target` is blocked.
bool segment_occluded(const ShadowRayTracer& tracer, const glm::vec3& origin, const glm::vec3& target, float offset) {
    const glm::vec3 to_target = target - origin;
    const float distance = glm::length(to_target);
    if (distance <= offset) return false;
    return tracer.occluded(origin, to_target / distance, distance - offset);
}

float soft_visibility(const ShadowRayTracer& tracer, const Light& light, const glm::vec3& origin, uint32_t rays,
                      uint32_t pixel, float offset) {
    // The disk through the light's centre perpendicular to the receiver's view of it.
    const TangentBasis basis = orthonormal_basis(glm::normalize(light.position - origin));
    const glm::vec2 shift = hash_to_unit_square(pixel);
    uint32_t unoccluded = 0;
    for (uint32_t i = 0; i < rays; ++i) {
        const glm::vec2 disk = concentric_disk(fibonacci_lattice(i, rays, shift)) * light.radius;
        const glm::vec3 target = light.position + basis.tangent * disk.x + basis.bitangent * disk.y;
        unoccluded += segment_occluded(tracer, origin, target, offset) ? 0u : 1u;
    }
    return static_cast<float>(unoccluded) / static_cast<float>(rays);
}

// The renderer's `in_range` (lighting.frag): strictly inside the range, normal facing the light point.
bool in_range_and_facing(const Light& light, const glm::vec3& position, const glm::vec3& normal) {
    const glm::vec3 to_light = light.position - position;
    return glm::length(to_light) < light.range && glm::dot(normal, to_light) > 0.0f;
}

}  // namespace

float spot_cone_factor(const Light& light, const glm::vec3& point) {
    if (light.type != LightType::Spot) return 1.0f;
    const float cos_outer = std::cos(glm::radians(light.outer_angle_degrees));
    const float cos_inner = std::cos(glm::radians(light.inner_angle_degrees));
    const float cos_angle = glm::dot(glm::normalize(point - light.position), glm::normalize(light.direction));
    return smoothstep(cos_outer, std::max(cos_inner, cos_outer + 1e-4f), cos_angle);
}

float light_reach(const Light& light, const glm::vec4& position, const glm::vec4& normal) {
    if (position.w <= 0.5f || !in_range_and_facing(light, glm::vec3(position), glm::vec3(normal))) return 0.0f;
    return spot_cone_factor(light, glm::vec3(position));
}

ReferenceImages trace_local_light_reference(const ShadowRayTracer& tracer, const SurfaceImage& surfaces,
                                            const Light& light, uint32_t rays, const RowProgress& progress) {
    const size_t pixels = size_t{surfaces.width} * surfaces.height;
    ReferenceImages images;
    images.hard.assign(pixels, 1);
    if (rays > 0) images.soft.assign(pixels, 1.0f);
    const bool area_light = rays > 1 && light.radius > 0.0f;
    const float offset = end_offset(light.position);
    parallel_rows(
        surfaces.height,
        [&](uint32_t row) {
            for (uint32_t x = 0; x < surfaces.width; ++x) {
                const size_t pixel = size_t{row} * surfaces.width + x;
                const glm::vec4& position = surfaces.positions[pixel];
                const glm::vec4& normal = surfaces.normals[pixel];
                if (position.w <= 0.5f) continue;
                if (!in_range_and_facing(light, glm::vec3(position), glm::vec3(normal))) {
                    images.hard[pixel] = 0;
                    if (rays > 0) images.soft[pixel] = 0.0f;
                    continue;
                }
                const glm::vec3 origin = shadow_ray_origin(glm::vec3(position), glm::vec3(normal));
                images.hard[pixel] = segment_occluded(tracer, origin, light.position, offset) ? 0 : 1;
                if (rays == 0) continue;
                images.soft[pixel] =
                    area_light ? soft_visibility(tracer, light, origin, rays, static_cast<uint32_t>(pixel), offset)
                               : static_cast<float>(images.hard[pixel]);
            }
        },
        progress);
    return images;
}

}  // namespace penumbra::quality
