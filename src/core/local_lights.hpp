#pragma once
// Shadow maps of spot and point lights ("local" lights), as pure math: which lights get
// a shadow map within the budget, where their layers lie in the shared layered map, their
// light-space matrices and per-light caster culling. No Vulkan (docs/local-lights.md).
//
// A spot light up to kMaxPerspectiveSpotAngle gets one layer: a reverse-Z perspective
// projection fitted to its cone (fov = 2 * outer angle, near from the nearest caster,
// far = range). A point light, and a spot wider than that, gets six consecutive layers,
// one per cube face, in the order +X, -X, +Y, -Y, +Z, -Z, each a 90-degree reverse-Z
// perspective projection; the lighting shader selects the face by the major axis of
// (receiver - light) and applies a spot's cone on top.
#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "core/camera_math.hpp"
#include "core/glm_config.hpp"
#include "core/shadow_inputs.hpp"
#include "penumbra/settings.hpp"

namespace penumbra {

inline constexpr float kMinLocalShadowNear = 0.05f;  // metres
// The widest spot (outer half-angle, degrees) shadowed by one perspective layer. Past it a
// perspective texel at the cone's edge covers more than 1 / cos^2(60) = 4 times the
// footprint of one on the axis (and 90 degrees cannot be projected at all), while a cube
// face's corner texel covers at most 3 times its centre's: wider spots use a cube.
inline constexpr float kMaxPerspectiveSpotAngle = 60.0f;

// Where one local light's shadow lives and how it was fitted.
struct LocalShadowSlot {
    uint32_t light = 0;             // index into the light list
    uint32_t first_layer = 0;       // 1 layer, or 6 for a cube (faces +X, -X, +Y, -Y, +Z, -Z)
    uint32_t resolution = 0;        // texels per side actually used in each of its layers (this frame)
    bool fixed_resolution = false;  // set by the light's shadow_resolution or fixed sizing
    float near_plane = kMinLocalShadowNear;
    float far_plane = 0.0f;                  // the light's range
    std::vector<glm::mat4> view_projection;  // world -> reverse-Z clip, one per layer
};

struct LocalShadowPlan {
    std::vector<LocalShadowSlot> slots;  // shadowed lights, in light order, within the budget
    uint32_t layer_count = 0;            // layers of the shared map
    uint32_t atlas_resolution = 0;       // the shared map's texels per side (the largest a slot may use)
    // Shadow-casting spot/point lights left unshadowed by the budget or the layer limit.
    std::vector<uint32_t> unshadowed;
};

// Whether a local light's shadow is a cube of six faces: a point light, or a spot wider
// than kMaxPerspectiveSpotAngle. Otherwise a spot's shadow is one perspective layer.
bool local_shadow_is_cube(const core::Light& light);

// Shadow-map layers a light takes: 1 for a perspective spot, 6 for a cube, 0 for a
// directional light.
uint32_t local_shadow_layers(const core::Light& light);

// Half the field of view of each of a local light's shadow layers: a perspective spot's
// outer angle, 45 degrees for a cube face (radians).
float local_shadow_half_fov(const core::Light& light);

// The camera-independent part: which spot and point lights are shadowed (the first
// `budget` shadow-casting ones, in list order, within kMaxLocalShadowLayers), their layers
// and resolutions. Matrices are filled by fit_local_shadows().
LocalShadowPlan plan_local_shadows(std::span<const core::Light> lights, const LocalShadowSettings& settings);

// Distance from `point` to the nearest of `boxes` (0 inside one), clamped to [min_near, max_far).
float nearest_caster_distance(const glm::vec3& point, const std::vector<core::Aabb>& boxes, float max_far);

// The near plane of a local light's layers: the nearest caster's distance times the cosine
// of the angle between a layer's axis and its frustum's corner ray. A caster at distance d
// seen at angle t off the axis lies at view depth d cos t, so the nearest caster's distance
// alone would clip casters off the axis (a table beside a point light, under its -Y face);
// the corner ray has the largest angle in the frustum: tan t = sqrt(2) tan(fov / 2)
// (1 / sqrt(3) for a 90-degree cube face). Never below kMinLocalShadowNear.
float local_shadow_near_plane(const core::Light& light, float nearest_caster);

// Reverse-Z perspective of a spot's cone: fov = 2 * outer angle, near, far = range
// (for spots up to kMaxPerspectiveSpotAngle).
glm::mat4 spot_shadow_view_projection(const core::Light& spot, float near_plane);

// The six cube faces around a light (+X, -X, +Y, -Y, +Z, -Z), 90-degree reverse-Z perspectives.
std::array<glm::mat4, 6> point_shadow_view_projections(const glm::vec3& position, float near_plane, float far_plane);

// Whether cube face `face` (+X, -X, +Y, -Y, +Z, -Z) of a local light can hold anything the
// light reaches: always for a point light; for a wide spot, unless every direction of the
// face lies outside the cone. A face's directions are within atan(sqrt(2)) = 54.74 degrees
// (its corner ray) of its axis, so a face whose axis is farther than outer + 54.74 degrees
// from the spot's axis is dark and need not be rendered.
bool cube_face_reaches_cone(const core::Light& light, size_t face);

// Fills each slot's near plane (nearest caster within range) and matrices for the scene's
// current light positions; `caster_boxes` are the world bounds of every draw.
void fit_local_shadows(LocalShadowPlan& plan, std::span<const core::Light> lights,
                       const std::vector<core::Aabb>& caster_boxes);

// The smallest sphere around what a local light can reach: its range around a point light;
// for a spot, the sphere through the apex and the cone's rim at the range (centre on the
// axis at range / (2 cos outer)), or the range sphere when that is smaller (outer > 60 deg).
struct Sphere {
    glm::vec3 center{0.0f};
    float radius = 0.0f;
};
Sphere local_light_bounds(const core::Light& light);

// Texels per side a light's map needs for `camera` (rendering `viewport_height` pixels):
// one texel per pixel across the light's bounds as seen on the screen (halved per cube
// face of a cube, whose six faces share the view around the light), rounded up to a power
// of two and clamped to [kMinCoverageShadowResolution, max_resolution]. The camera inside
// the bounds gets max_resolution; bounds outside the view frustum the minimum.
uint32_t coverage_shadow_resolution(const core::Light& light, const CameraView& camera, uint32_t viewport_height,
                                    uint32_t max_resolution);

// Sets this frame's resolution of every slot without a fixed one (coverage sizing, up to
// `max_resolution`, the settings' resolution).
void size_local_shadows(LocalShadowPlan& plan, std::span<const core::Light> lights, const CameraView& camera,
                        uint32_t viewport_height, uint32_t max_resolution);

// A view the maps serve: its camera and the height of its image in pixels.
struct SizedCamera {
    CameraView camera;
    uint32_t viewport_height = 0;
};

// The same for maps that several views share: each slot the largest resolution a view needs.
void size_local_shadows(LocalShadowPlan& plan, std::span<const core::Light> lights, std::span<const SizedCamera> views,
                        uint32_t max_resolution);

// Conservative culling: false only when the box cannot cast into the layer: outside a plane
// of its frustum (Gribb-Hartmann planes of the view projection), or, for a cube face,
// farther than the range from the light.
bool caster_may_shadow_frustum(const glm::mat4& view_projection, const core::Aabb& box);
bool caster_may_shadow_sphere(const glm::vec3& center, float radius, const core::Aabb& box);

}  // namespace penumbra
