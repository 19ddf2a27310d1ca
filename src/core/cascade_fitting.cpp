// Stable and tight fitting of cascade shadow volumes.
//
// Stable fitting follows Valient, "Stable Rendering of Cascaded Shadow Maps" (ShaderX6,
// 2008) and the Microsoft "Common Techniques to Improve Shadow Depth Maps" article: a
// rotation-invariant bounding sphere fixes the size of the shadow map footprint, and
// snapping its origin to whole texels makes camera translation move the footprint by
// whole texels only, so rasterised shadow edges do not shimmer.
#include "core/cascade_fitting.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace penumbra {
namespace {

float round_up_to_sixteenth(float metres) { return std::ceil(metres * 16.0f) / 16.0f; }

}  // namespace

namespace {

// Half the frustum's extent per metre of view distance, when it is a perspective centred on
// the view axis (within the jitter allowance, which pads it): the closed-form sphere's input.
std::optional<glm::dvec2> symmetric_half_tangents(const CameraView& camera) {
    for (const glm::vec2& origin : camera.edge_origin) {
        if (origin != glm::vec2(0.0f)) return std::nullopt;  // orthographic
    }
    if (camera.jitter_allowance == glm::vec2(0.0f)) {  // Penumbra's own symmetric perspective
        const double tan_half_y = std::tan(static_cast<double>(camera.fov_y_radians) * 0.5);
        return glm::dvec2(tan_half_y * camera.aspect, tan_half_y);
    }
    const std::array<glm::vec2, 4>& s = camera.edge_slope;
    const glm::dvec2 half_span(0.5 * std::abs(s[1].x - s[0].x), 0.5 * std::abs(s[2].y - s[0].y));
    const glm::dvec2 shift(0.5 * (s[0].x + s[1].x), 0.5 * (s[0].y + s[2].y));
    const glm::dvec2 allowance(camera.jitter_allowance);
    if (std::abs(shift.x) > allowance.x || std::abs(shift.y) > allowance.y) return std::nullopt;
    return half_span + allowance;  // holds the frustum at any shift within the allowance
}

// A frustum slice of any shape: the centre on the segment between its near and far faces'
// centres that minimises the farthest corner (a convex function of the position along it:
// golden-section search), in view space, so that it moves with the camera rigidly.
BoundingSphere generic_slice_sphere(const CameraView& camera, float slice_near, float slice_far) {
    std::array<glm::dvec3, 8> corners{};
    glm::dvec3 near_centre(0.0), far_centre(0.0);
    for (int i = 0; i < 4; ++i) {
        const glm::dvec2 slope(camera.edge_slope[i]);
        const glm::dvec2 origin(camera.edge_origin[i]);
        corners[i] = glm::dvec3(origin + slope * static_cast<double>(slice_near), -static_cast<double>(slice_near));
        corners[4 + i] = glm::dvec3(origin + slope * static_cast<double>(slice_far), -static_cast<double>(slice_far));
        near_centre += corners[i] * 0.25;
        far_centre += corners[4 + i] * 0.25;
    }
    const auto farthest = [&](double t) {
        const glm::dvec3 centre = glm::mix(near_centre, far_centre, t);
        double largest = 0.0;
        for (const glm::dvec3& corner : corners)
            largest = std::max(largest, glm::dot(corner - centre, corner - centre));
        return largest;
    };
    const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
    double low = 0.0, high = 1.0;
    for (int step = 0; step < 80; ++step) {
        const double a = high - ratio * (high - low);
        const double b = low + ratio * (high - low);
        if (farthest(a) <= farthest(b)) {
            high = b;
        } else {
            low = a;
        }
    }
    const double t = 0.5 * (low + high);
    BoundingSphere sphere;
    sphere.center =
        glm::vec3(glm::inverse(camera.view) * glm::vec4(glm::vec3(glm::mix(near_centre, far_centre, t)), 1.0f));
    sphere.radius = static_cast<float>(std::sqrt(farthest(t)));
    return sphere;
}

}  // namespace

BoundingSphere frustum_slice_bounding_sphere(const CameraView& camera, float slice_near, float slice_far) {
    const std::optional<glm::dvec2> half_tangents = symmetric_half_tangents(camera);
    if (!half_tangents) return generic_slice_sphere(camera, slice_near, slice_far);
    // 1. In view space the slice is symmetric about the view axis: the corners at view
    //    distance d lie at squared distance d^2 * k from the axis, k = tan_x^2 + tan_y^2.
    const double k = glm::dot(*half_tangents, *half_tangents);
    const double n = slice_near;
    const double f = slice_far;
    // 2. A centre at distance z on the axis needs radius^2 = max((z - n)^2 + k n^2,
    //    (f - z)^2 + k f^2). The two terms are equal at z = (f + n)(1 + k) / 2; past the far
    //    plane (wide or thin slices) the far term alone rules, minimal at z = f.
    const double center_distance = std::min((f + n) * (1.0 + k) * 0.5, f);
    const double radius_squared = std::max((center_distance - n) * (center_distance - n) + k * n * n,
                                           (f - center_distance) * (f - center_distance) + k * f * f);
    // 3. Back to the world through the same inverse view that frustum_slice_corners uses.
    const glm::vec4 view_center(0.0f, 0.0f, -static_cast<float>(center_distance), 1.0f);
    BoundingSphere sphere;
    sphere.center = glm::vec3(glm::inverse(camera.view) * view_center);
    sphere.radius = static_cast<float>(std::sqrt(radius_squared));
    return sphere;
}

LightOrthoBox fit_stable_box(const BoundingSphere& light_space_sphere, uint32_t resolution) {
    const float texels = static_cast<float>(resolution);
    // 1. Snapping moves the square by at most half a texel (radius / resolution) per
    //    axis; pad for it before rounding up to 1/16 m. The rounding keeps the footprint
    //    size constant while the sphere's radius wobbles in the last float bits.
    const float radius = round_up_to_sixteenth(light_space_sphere.radius * texels / (texels - 1.0f));
    const float texel = 2.0f * radius / texels;
    // 2. Snap the light-space origin of the square to whole texels of the world-fixed grid
    //    (the light view is a pure rotation, so the grid does not move with the camera).
    //    With an even resolution the square's edges then lie on the grid as well.
    LightOrthoBox box;
    box.center = glm::round(glm::vec2(light_space_sphere.center) / texel) * texel;
    box.half_size = glm::vec2(radius);
    // 3. The sphere's own depth range; extend_depth_to_scene adds the casters.
    const float center_distance = -light_space_sphere.center.z;
    box.near_distance = center_distance - radius;
    box.far_distance = center_distance + radius;
    return box;
}

LightOrthoBox fit_tight_box(const std::array<glm::vec3, 8>& light_space_points, uint32_t resolution,
                            float padding_texels) {
    // 1. Light-space bounds of the points.
    core::Aabb bounds;
    for (const glm::vec3& point : light_space_points) bounds.expand(point);
    // 2. Texel size such that the bounds, the padding on both sides and one texel of
    //    snapping slack fill the map exactly: resolution * texel = size + (2 p + 1) texel.
    const float usable_texels = static_cast<float>(resolution) - 2.0f * padding_texels - 1.0f;
    const glm::vec2 size(bounds.extent());
    const glm::vec2 texel = glm::max(size, glm::vec2(1e-4f)) / usable_texels;
    // 3. Snap the padded minimum down to the texel grid; the maximum follows at exactly
    //    resolution texels, which covers the padded maximum thanks to the slack texel.
    const glm::vec2 padded_min = glm::vec2(bounds.min) - padding_texels * texel;
    LightOrthoBox box;
    box.half_size = 0.5f * static_cast<float>(resolution) * texel;
    box.center = glm::floor(padded_min / texel) * texel + box.half_size;
    box.near_distance = -bounds.max.z;
    box.far_distance = -bounds.min.z;
    return box;
}

LightOrthoBox depth_range_of_scene(const LightOrthoBox& box, const core::Aabb& light_space_scene_bounds) {
    if (light_space_scene_bounds.empty()) return box;
    // The scene's extent along the light, whatever the slice: every caster and every
    // receiver lies inside it, and a cascade that moves keeps its depth mapping, so that
    // depths rendered in an earlier frame stay valid (cached cascades). A margin keeps the
    // range open for a scene flat across the light (a ground plane lit from straight above).
    const float near_distance = -light_space_scene_bounds.max.z;
    const float far_distance = -light_space_scene_bounds.min.z;
    const float margin = std::max(kMinDepthMargin, 1e-3f * (far_distance - near_distance));
    // At least as deep as the cascade is wide, centred on the scene: the depth biases and
    // their clamp are in depth units, so a range much shallower than the window (a flat
    // scene under a wide cascade) would shrink them in metres and bring back acne. The
    // window's width does not change while the stable fit follows the camera.
    const float half_depth =
        std::max(0.5f * (far_distance - near_distance) + margin, std::max(box.half_size.x, box.half_size.y));
    const float centre = 0.5f * (near_distance + far_distance);
    LightOrthoBox ranged = box;
    ranged.near_distance = centre - half_depth;
    ranged.far_distance = centre + half_depth;
    return ranged;
}

glm::mat4 light_projection(const LightOrthoBox& box) {
    const glm::vec2 low = box.center - box.half_size;
    const glm::vec2 high = box.center + box.half_size;
    return orthographic_reverse_z(low.x, high.x, low.y, high.y, box.near_distance, box.far_distance);
}

}  // namespace penumbra
