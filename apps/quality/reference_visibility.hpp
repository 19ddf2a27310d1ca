#pragma once
// The ray-traced reference of the sun's visibility at the surface points a rasterizer
// produced (one world position and normal per pixel):
//   hard: one shadow ray toward the sun's centre, 1 = lit, 0 = shadowed;
//   soft: the unoccluded fraction of `rays` shadow rays over the sun's disk (a stratified
//         Fibonacci lattice mapped by the concentric map, rotated per pixel).
// Pixels without geometry read 1 and pixels facing away from the sun (N.L <= 0) read 0,
// as in the renderer's visibility AOV.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include "quality/parallel_rows.hpp"
#include "quality/shadow_ray_tracer.hpp"

namespace penumbra::quality {

// Per-pixel surface points, row 0 at the top.
struct SurfaceImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<glm::vec4> positions;  // xyz world position, w = 1 where geometry, 0 none
    std::vector<glm::vec4> normals;    // xyz unit shading normal (facing the camera)
};

struct ReferenceOptions {
    glm::vec3 to_sun{0.0f, 1.0f, 0.0f};  // unit direction toward the sun
    float angular_diameter_degrees = 0.53f;
    uint32_t rays = 64;  // soft reference rays per pixel; 0 = hard reference only
    // Metres: pixels the hard ray finds shadowed by an occluder nearer than this are also
    // marked as contact pixels (ReferenceImages::contact); 0 = none.
    float contact_reach = 0.0f;
    RowProgress progress;  // optional: rows traced so far (on the calling thread)
};

struct ReferenceImages {
    std::vector<uint8_t> hard;  // 1 lit, 0 shadowed
    std::vector<float> soft;    // [0, 1]; empty with rays = 0
    // 1 where the occluder of the hard ray lies within ReferenceOptions::contact_reach: the
    // shadow right beside a contact between caster and receiver. Empty with no reach.
    std::vector<uint8_t> contact;
};

// True where the pixel has geometry and its normal faces the sun.
bool faces_sun(const glm::vec4& position, const glm::vec4& normal, const glm::vec3& to_sun);

// Where a shadow ray starts: the surface point moved off the surface along its normal by
// a distance relative to the point's magnitude (float spacing of the rasterized position),
// so the ray does not hit the surface it starts on.
glm::vec3 shadow_ray_origin(const glm::vec3& position, const glm::vec3& normal);

ReferenceImages trace_reference(const ShadowRayTracer& tracer, const SurfaceImage& surfaces,
                                const ReferenceOptions& options);

}  // namespace penumbra::quality
