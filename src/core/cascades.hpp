#pragma once
// Cascaded shadow map math for a directional light: split schemes (PSSM), light
// view basis, stable and tight fitting, reverse-Z orthographic projections. Pure
// functions of camera, light direction, settings and scene bounds; no Vulkan.
#include <array>
#include <vector>

#include "core/camera_math.hpp"
#include "core/shadow_inputs.hpp"
#include "penumbra/settings.hpp"

namespace penumbra {

// Split distances along the view direction: count + 1 values, first == near_plane,
// last == far_plane, strictly increasing.
// Uniform: near + (far - near) * i / count. Logarithmic: near * (far / near)^(i / count).
// Practical (PSSM): lerp(uniform, logarithmic, lambda). Manual: near, manual..., far
// (manual must hold count - 1 strictly increasing values inside (near, far), else
// InputError "splits: ..."; the settings validator cannot know the camera's far plane).
// Throws std::invalid_argument unless 0 < near < far is finite and 1 <= count <= 8.
std::vector<float> compute_split_distances(float near_plane, float far_plane, int count, SplitScheme scheme,
                                           float lambda, const std::vector<float>& manual = {});

// World -> light view matrix looking along light_direction (the direction light travels).
// Valid for every non-zero direction, including straight down (parallel to world up).
// A pure rotation (no translation), so the shadow-map texel grid is fixed in the world;
// each cascade's projection carries its translation. Throws std::invalid_argument for a
// zero or non-finite direction.
glm::mat4 light_view_matrix(const glm::vec3& light_direction);

struct Cascade {
    glm::mat4 view{1.0f};        // world -> light view (light looks down -Z)
    glm::mat4 projection{1.0f};  // light view -> clip, orthographic reverse-Z
    glm::mat4 view_projection{1.0f};
    float split_near = 0.0f;        // camera view distance where this cascade starts
    float split_far = 0.0f;         // ... and ends
    float texel_world_size = 0.0f;  // world metres per shadow-map texel (max of X and Y)
    glm::vec3 light_extent{0.0f};   // light-space width (X), height (Y), depth range (Z), metres
    // The same projection in a texel grid fixed in the world (the caster pass draws with
    // it): map texel = light view (x, y) * texels_per_metre - texel_origin, the origin a
    // whole number; reverse-Z depth = light view z * depth_scale + depth_offset.
    glm::vec2 texels_per_metre{0.0f};
    glm::vec2 texel_origin{0.0f};
    float depth_scale = 0.0f;
    float depth_offset = 0.0f;
    // Where the cascade's window lies in its map layer: the layer texel of window texel 0.
    // Zero: the layer is the window. Toroidal (place_in_layers): texel_origin modulo the
    // layer's side, so that a texel of the world grid keeps its place in the layer however
    // the cascade moves, and the window wraps around the layer's edges.
    glm::ivec2 layer_origin{0};
};

struct CascadeSet {
    std::vector<Cascade> cascades;
    glm::vec3 light_direction{0.0f, -1.0f, 0.0f};  // normalised
    float shadow_distance = 0.0f;                  // min(camera far, max_distance)
};

// Fits every cascade to its slice of the camera frustum.
// Stable: bounding sphere of the slice (radius rounded up to 1/16 m), light-space origin
// snapped to whole texels, so shadows do not shimmer under camera motion.
// Tight: light-space AABB of the slice corners in XY (snapped to texels, padded by
// settings.filter_padding_texels). In both modes Z is scene_bounds' range along the light
// plus a margin, so that casters between the light and the slice are never clipped,
// receivers beyond the slice stay inside, and the depth mapping does not follow the
// camera (cached cascades); an empty scene_bounds leaves Z at the slice (or sphere).
// Requires validated settings (validate_shadow_settings); throws InputError when
// max_distance does not exceed the camera near plane or manual splits do not fit inside
// [near, shadow_distance].
CascadeSet compute_cascades(const CameraView& camera, const glm::vec3& light_direction, const CascadeSettings& settings,
                            const core::Aabb& scene_bounds);

// Caster culling: true when a world-space box can cast a shadow into the cascade, i.e. it
// intersects the cascade's volume extended toward the light (the box is tested in light
// space against the cascade's XY rectangle; its Z is only tested on the far side: boxes
// nearer the light than the near plane pass, the shadow pass flattens them with depth
// clamp). An empty box never casts.
bool caster_may_shadow_cascade(const Cascade& cascade, const core::Aabb& world_box);

}  // namespace penumbra
