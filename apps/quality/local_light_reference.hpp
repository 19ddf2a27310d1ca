#pragma once
// The ray-traced reference of a spot or point light's shadow at the surface points a
// rasterizer produced (docs/QUALITY.md, "Spot and point lights"):
//   hard: one segment from the receiver to the light's centre, 1 = lit, 0 = shadowed;
//   soft: the unoccluded fraction of `rays` segments to points of the light's disk of
//         `radius` facing the receiver (the silhouette of its sphere), sampled like the
//         sun's disk (a Fibonacci lattice through the concentric map, rotated per pixel).
// Segments end just short of the light point, so that nothing behind the light occludes.
// The reference is the shadow term alone: it does not include the spot cone, which the
// caller factors out of the render instead (see light_reach()).
#include <cstdint>

#include "penumbra/scene/scene.hpp"
#include "quality/reference_visibility.hpp"

namespace penumbra::quality {

// The spot cone of apps/renderer/shaders/include/local_lighting.glsl, spot_cone(): smoothstep(cos outer,
// max(cos inner, cos outer + 1e-4), cos angle to the axis); 1 for a point light.
float spot_cone_factor(const Light& light, const glm::vec3& point);

// What the renderer multiplies a local light's shadow by in the `--aov shadow:N` image
// (lighting.frag): 0 without geometry, at or beyond the range, or where the normal faces
// away from the light point; otherwise the spot cone factor.
float light_reach(const Light& light, const glm::vec4& position, const glm::vec4& normal);

// Pixels without geometry read 1 and pixels the light does not reach (light_reach() = 0
// from range or facing) read 0, as in the AOV. `rays` <= 1 or a light of radius 0 gives a
// soft image equal to the hard one; rays = 0 leaves the soft image empty.
ReferenceImages trace_local_light_reference(const ShadowRayTracer& tracer, const SurfaceImage& surfaces,
                                            const Light& light, uint32_t rays, const RowProgress& progress = {});

}  // namespace penumbra::quality
