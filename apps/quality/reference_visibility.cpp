#include "quality/reference_visibility.hpp"

#include <algorithm>
#include <cmath>

#include "quality/parallel_rows.hpp"
#include "quality/sun_disk_sampling.hpp"

namespace penumbra::quality {
namespace {

// 1e-4 of the point's largest coordinate (at least 0.1 mm): above the rasterizer's
// interpolation error of the position and far below any caster-receiver distance a
// shadow map resolves.
constexpr float kRelativeOffset = 1e-4f;

float soft_visibility(const ShadowRayTracer& tracer, const SunDisk& sun, const glm::vec3& origin, uint32_t rays,
                      uint32_t pixel) {
    const glm::vec2 shift = hash_to_unit_square(pixel);
    uint32_t unoccluded = 0;
    for (uint32_t i = 0; i < rays; ++i) {
        const glm::vec2 disk_point = concentric_disk(fibonacci_lattice(i, rays, shift));
        unoccluded += tracer.occluded(origin, sun.direction(disk_point)) ? 0u : 1u;
    }
    return static_cast<float>(unoccluded) / static_cast<float>(rays);
}

}  // namespace

bool faces_sun(const glm::vec4& position, const glm::vec4& normal, const glm::vec3& to_sun) {
    return position.w > 0.5f && glm::dot(glm::vec3(normal), to_sun) > 0.0f;
}

glm::vec3 shadow_ray_origin(const glm::vec3& position, const glm::vec3& normal) {
    const float magnitude = std::max({std::abs(position.x), std::abs(position.y), std::abs(position.z), 1.0f});
    return position + normal * (kRelativeOffset * magnitude);
}

ReferenceImages trace_reference(const ShadowRayTracer& tracer, const SurfaceImage& surfaces,
                                const ReferenceOptions& options) {
    const size_t pixels = size_t{surfaces.width} * surfaces.height;
    ReferenceImages images;
    images.hard.assign(pixels, 1);
    if (options.rays > 0) images.soft.assign(pixels, 1.0f);
    if (options.contact_reach > 0.0f) images.contact.assign(pixels, 0);
    const SunDisk sun(options.to_sun, options.angular_diameter_degrees);
    parallel_rows(
        surfaces.height,
        [&](uint32_t row) {
            for (uint32_t x = 0; x < surfaces.width; ++x) {
                const size_t pixel = size_t{row} * surfaces.width + x;
                const glm::vec4& position = surfaces.positions[pixel];
                const glm::vec4& normal = surfaces.normals[pixel];
                if (position.w <= 0.5f) continue;
                if (!faces_sun(position, normal, sun.center())) {
                    images.hard[pixel] = 0;
                    if (options.rays > 0) images.soft[pixel] = 0.0f;
                    continue;
                }
                const glm::vec3 origin = shadow_ray_origin(glm::vec3(position), glm::vec3(normal));
                images.hard[pixel] = tracer.occluded(origin, sun.center()) ? 0 : 1;
                if (images.hard[pixel] == 0 && options.contact_reach > 0.0f) {
                    images.contact[pixel] = tracer.occluded(origin, sun.center(), options.contact_reach) ? 1 : 0;
                }
                if (options.rays > 0) {
                    images.soft[pixel] =
                        soft_visibility(tracer, sun, origin, options.rays, static_cast<uint32_t>(pixel));
                }
            }
        },
        options.progress);
    return images;
}

}  // namespace penumbra::quality
