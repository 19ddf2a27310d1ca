// Cascaded shadow maps for a directional light: one orthographic shadow volume per
// slice of the camera frustum.
//
// Steps (per frame, a pure function of its inputs):
//   1. shadow distance = min(camera far, max_distance); split it (PSSM, Zhang et al. 2006);
//   2. light view: a rotation looking along the light (light_view_matrix);
//   3. per slice, fit the light-space XY window: stable (bounding sphere + texel snap,
//      Valient 2008) or tight (AABB of the slice corners);
//   4. the depth range is the scene bounds' along the light, so no caster toward the light
//      is clipped ("Z extended to scene bounds", Microsoft, Common Techniques to Improve
//      Shadow Depth Maps) and the depth mapping stays put while the camera moves (cached
//      cascades keep their depths);
//   5. reverse-Z orthographic projection: near the light -> depth 1.
#include "core/cascades.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/cascade_fitting.hpp"
#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

float shadow_distance_for(const CameraView& camera, const CascadeSettings& settings) {
    const float distance = std::min(camera.far_plane, settings.max_distance);
    if (!(distance > camera.near_plane)) {
        std::ostringstream message;
        message << "max_distance: " << settings.max_distance << " must exceed the camera near plane "
                << camera.near_plane;
        throw InputError(message.str());
    }
    return distance;
}

// Step 3 of the header comment: the light-space window of one slice.
LightOrthoBox fit_slice(const CameraView& camera, const glm::mat4& light_view, const CascadeSettings& settings,
                        float split_near, float split_far) {
    if (settings.fit == FitMode::Stable) {
        BoundingSphere sphere = frustum_slice_bounding_sphere(camera, split_near, split_far);
        sphere.center = glm::vec3(light_view * glm::vec4(sphere.center, 1.0f));
        return fit_stable_box(sphere, settings.resolution);
    }
    std::array<glm::vec3, 8> corners = frustum_slice_corners(camera, split_near, split_far);
    for (glm::vec3& corner : corners) corner = glm::vec3(light_view * glm::vec4(corner, 1.0f));
    return fit_tight_box(corners, settings.resolution, settings.filter_padding_texels);
}

Cascade make_cascade(const glm::mat4& light_view, const LightOrthoBox& box, uint32_t resolution, float split_near,
                     float split_far) {
    Cascade cascade;
    cascade.view = light_view;
    cascade.projection = light_projection(box);
    cascade.view_projection = cascade.projection * cascade.view;
    cascade.split_near = split_near;
    cascade.split_far = split_far;
    cascade.light_extent = box.extent();
    cascade.texel_world_size =
        std::max(cascade.light_extent.x, cascade.light_extent.y) / static_cast<float>(resolution);
    // The window's first texel in the world's grid of its texel size: both fits place the
    // window on that grid, so the quotient is a whole number up to rounding.
    const glm::vec2 texel = 2.0f * box.half_size / static_cast<float>(resolution);
    cascade.texels_per_metre = 1.0f / texel;
    cascade.texel_origin = glm::round((box.center - box.half_size) / texel);
    cascade.depth_scale = cascade.projection[2][2];
    cascade.depth_offset = cascade.projection[3][2];
    return cascade;
}

}  // namespace

CascadeSet compute_cascades(const CameraView& camera, const glm::vec3& light_direction, const CascadeSettings& settings,
                            const core::Aabb& scene_bounds) {
    CascadeSet set;
    // 1. Splits over [near, shadow distance].
    set.shadow_distance = shadow_distance_for(camera, settings);
    const std::vector<float> splits =
        compute_split_distances(camera.near_plane, set.shadow_distance, settings.count, settings.scheme,
                                settings.split_lambda, settings.manual_splits);
    // 2. One light view for every cascade.
    const glm::mat4 light_view = light_view_matrix(light_direction);
    set.light_direction = glm::normalize(light_direction);
    const core::Aabb light_space_scene = core::transform_aabb(scene_bounds, light_view);
    // 3.-5. Fit, take the scene's depth range, project.
    for (int i = 0; i < settings.count; ++i) {
        const LightOrthoBox slice_box = fit_slice(camera, light_view, settings, splits[i], splits[i + 1]);
        const LightOrthoBox box = depth_range_of_scene(slice_box, light_space_scene);
        set.cascades.push_back(make_cascade(light_view, box, settings.resolution, splits[i], splits[i + 1]));
    }
    return set;
}

bool caster_may_shadow_cascade(const Cascade& cascade, const core::Aabb& world_box) {
    if (world_box.empty()) return false;
    // The projection is affine, so Arvo's method bounds the box in clip space directly:
    // x, y in [-1, 1] is the cascade's rectangle, depth 0 its far side (reverse-Z).
    const core::Aabb clip_box = core::transform_aabb(world_box, cascade.view_projection);
    const bool overlaps_x = clip_box.min.x <= 1.0f && clip_box.max.x >= -1.0f;
    const bool overlaps_y = clip_box.min.y <= 1.0f && clip_box.max.y >= -1.0f;
    // Only the far side culls: boxes nearer the light than the near plane (depth > 1)
    // still cast into the cascade; the shadow pass flattens them with depth clamp.
    const bool before_far_side = clip_box.max.z >= 0.0f;
    return overlaps_x && overlaps_y && before_far_side;
}

}  // namespace penumbra
