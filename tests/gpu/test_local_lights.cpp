// Spot and point lights with shadows (docs/local-lights.md), checked against geometry:
// a spot's box shadow against the box projected from the light point, a point light's
// six cube faces in a closed room, and the shadow budget with more lights than it holds.
// Pixels are located through the geometry AOVs (world position per pixel).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../unit/scene_to_core.hpp"
#include "analytic_shadow.hpp"
#include "core/shadow_filters.hpp"
#include "library/frame_setup.hpp"
#include "render_fixture.hpp"

namespace penumbra::testing {
namespace {

// Convex hull (Andrew's monotone chain), counter-clockwise.
std::vector<glm::vec2> convex_hull(std::vector<glm::vec2> points) {
    std::sort(points.begin(), points.end(),
              [](glm::vec2 a, glm::vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    const auto cross = [](glm::vec2 o, glm::vec2 a, glm::vec2 b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    std::vector<glm::vec2> hull(2 * points.size());
    size_t k = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0f) --k;
        hull[k++] = points[i];
    }
    for (size_t i = points.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross(hull[k - 2], hull[k - 1], points[i - 1]) <= 0.0f) --k;
        hull[k++] = points[i - 1];
    }
    hull.resize(k - 1);
    return hull;
}

// The box's shadow on y = 0 cast from the point `light` (above the box): its corners
// projected from the light onto the plane, as a convex polygon in (x, z).
std::vector<glm::vec2> point_shadow_polygon(const Aabb& box, const glm::vec3& light) {
    std::vector<glm::vec2> projected;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                               (i & 4) ? box.max.z : box.min.z);
        const float t = light.y / (light.y - corner.y);
        const glm::vec3 hit = light + (corner - light) * t;
        projected.emplace_back(hit.x, hit.z);
    }
    return convex_hull(projected);
}

RenderedFrame render_light(const Scene& scene, RenderSettings settings, int32_t light_index) {
    settings.geometry_aovs = true;
    settings.visibility_light = light_index;
    RenderedFrame frame = render_with_validation(scene, settings);
    EXPECT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();
    return frame;
}

const char* kSpotScene = R"(
[camera]
eye = [0.0, 12.0, 6.0]
target = [0.0, 0.0, 0.0]
fov = 55.0
far = 60.0

[[lights]]
type = "spot"
position = [0.8, 6.0, 0.5]
direction = [-0.1, -1.0, 0.05]
inner_angle = 33.0
outer_angle = 35.0
range = 25.0
radius = 0.0
intensity = 40.0

[[objects]]
type = "plane"
size = [30.0, 30.0]

[[objects]]
type = "box"
size = [1.5, 0.5, 1.0]
translation = [0.0, 2.0, 0.0]
)";

struct SpotFootprint {
    double iou = 0.0;
    size_t union_pixels = 0;
    size_t outside_cone = 0;      // ground pixels outside the outer cone
    size_t lit_outside_cone = 0;  // of those, with any visibility
    double umbra_mean = 0.0;      // mean visibility inside the shadow, >= 10 cm from its edge
    double lit_mean = 0.0;        // mean visibility outside it, >= 10 cm from its edge, inside the inner cone
};

SpotFootprint measure_spot_footprint(ShadowFilter filter) {
    const Scene scene = scene_from_toml(kSpotScene);
    RenderSettings settings = small_settings(320, 240);
    settings.shadow.filter.mode = filter;
    const RenderedFrame frame = render_light(scene, settings, 0);
    const Light& spot = scene.lights[0];
    const Aabb box{{-0.75f, 1.75f, -0.5f}, {0.75f, 2.25f, 0.5f}};
    const auto polygon = point_shadow_polygon(box, spot.position);
    const float cos_inner = std::cos(glm::radians(spot.inner_angle_degrees));
    const float cos_outer = std::cos(glm::radians(spot.outer_angle_degrees));
    SpotFootprint result;
    size_t intersection = 0, umbra = 0, lit = 0;
    for (size_t i = 0; i < frame.images.world_position.size(); ++i) {
        const glm::vec4 p = frame.images.world_position[i];
        if (p.w == 0.0f || std::abs(p.y) > 1e-3f) continue;  // ground pixels only
        const glm::vec3 point(p);
        const float cos_angle = glm::dot(glm::normalize(point - spot.position), glm::normalize(spot.direction));
        const float visibility = frame.images.visibility[i] / 65535.0f;
        if (cos_angle < cos_outer) {
            ++result.outside_cone;
            if (visibility > 0.0f) ++result.lit_outside_cone;
            continue;
        }
        if (cos_angle < cos_inner) continue;  // the smooth cone edge
        const glm::vec2 xz(point.x, point.z);
        const float edge_distance = distance_to_polygon_edge(polygon, xz);
        if (edge_distance < 0.02f) continue;
        const bool truth = inside_convex_polygon(polygon, xz);
        const bool shadowed = visibility < 0.5f;
        intersection += truth && shadowed;
        result.union_pixels += truth || shadowed;
        if (edge_distance < 0.1f) continue;
        (truth ? result.umbra_mean : result.lit_mean) += visibility;
        ++(truth ? umbra : lit);
    }
    result.iou = result.union_pixels ? double(intersection) / double(result.union_pixels) : 0.0;
    result.umbra_mean /= double(std::max<size_t>(umbra, 1));
    result.lit_mean /= double(std::max<size_t>(lit, 1));
    EXPECT_GT(umbra, 100u);
    EXPECT_GT(lit, 1000u);
    return result;
}

// Every filter mode on a spot light: the footprint of the box is the perspective
// projection of the box from the light, dark inside and lit outside, nothing beyond the cone.
class SpotFilters : public ::testing::TestWithParam<ShadowFilter> {};

TEST_P(SpotFilters, ShadowMatchesThePerspectiveProjectionOfTheBox) {
    const SpotFootprint footprint = measure_spot_footprint(GetParam());
    std::printf(
        "spot footprint IoU %.4f (%zu px), umbra mean %.4f, lit mean %.4f, ground outside the cone %zu px, "
        "lit there %zu\n",
        footprint.iou, footprint.union_pixels, footprint.umbra_mean, footprint.lit_mean, footprint.outside_cone,
        footprint.lit_outside_cone);
    EXPECT_GT(footprint.union_pixels, 500u);
    EXPECT_GE(footprint.iou, 0.95);
    EXPECT_LE(footprint.umbra_mean, 0.02);
    EXPECT_GE(footprint.lit_mean, 0.98);
    EXPECT_GT(footprint.outside_cone, 1000u);
    EXPECT_EQ(footprint.lit_outside_cone, 0u);
}

std::string filter_test_name(const ::testing::TestParamInfo<ShadowFilter>& info) {
    for (const auto& [name, filter] : shadow_filter_names()) {
        if (filter == info.param) return name;
    }
    return "unknown";
}

INSTANTIATE_TEST_SUITE_P(LocalLights, SpotFilters,
                         ::testing::Values(ShadowFilter::Hard, ShadowFilter::Pcf, ShadowFilter::Poisson,
                                           ShadowFilter::Pcss, ShadowFilter::Vsm, ShadowFilter::Evsm,
                                           ShadowFilter::Msm),
                         filter_test_name);

// A closed room (8 x 6 x 8 m, walls 0.2 m thick) with a point light in the middle and a
// 0.6 m cube between the light and each of the six surfaces.
const char* kRoomScene = R"(
[[lights]]
type = "point"
position = [0.0, 3.0, 0.0]
range = 15.0
radius = 0.0
intensity = 30.0

[[objects]]
type = "box"
size = [8.4, 0.2, 8.4]
translation = [0.0, -0.1, 0.0]
[[objects]]
type = "box"
size = [8.4, 0.2, 8.4]
translation = [0.0, 6.1, 0.0]
[[objects]]
type = "box"
size = [0.2, 6.0, 8.0]
translation = [4.1, 3.0, 0.0]
[[objects]]
type = "box"
size = [0.2, 6.0, 8.0]
translation = [-4.1, 3.0, 0.0]
[[objects]]
type = "box"
size = [8.0, 6.0, 0.2]
translation = [0.0, 3.0, 4.1]
[[objects]]
type = "box"
size = [8.0, 6.0, 0.2]
translation = [0.0, 3.0, -4.1]

[[objects]]
type = "box"
size = 0.6
translation = [2.5, 3.3, 0.4]
[[objects]]
type = "box"
size = 0.6
translation = [-2.5, 2.6, -0.5]
[[objects]]
type = "box"
size = 0.6
translation = [0.5, 5.0, -0.3]
[[objects]]
type = "box"
size = 0.6
translation = [-0.4, 1.2, 0.6]
[[objects]]
type = "box"
size = 0.6
translation = [0.3, 2.7, 2.5]
[[objects]]
type = "box"
size = 0.6
translation = [-0.6, 3.4, -2.5]
)";

const glm::vec3 kCubeCenters[6] = {{2.5f, 3.3f, 0.4f},  {-2.5f, 2.6f, -0.5f}, {0.5f, 5.0f, -0.3f},
                                   {-0.4f, 1.2f, 0.6f}, {0.3f, 2.7f, 2.5f},   {-0.6f, 3.4f, -2.5f}};

// Wall of a room point: 0..5 = +X, -X, +Y (ceiling), -Y (floor), +Z, -Z; -1 for a cube.
int room_wall(const glm::vec3& p) {
    const float e = 1e-3f;
    if (std::abs(p.x - 4.0f) < e) return 0;
    if (std::abs(p.x + 4.0f) < e) return 1;
    if (std::abs(p.y - 6.0f) < e) return 2;
    if (std::abs(p.y) < e) return 3;
    if (std::abs(p.z - 4.0f) < e) return 4;
    if (std::abs(p.z + 4.0f) < e) return 5;
    return -1;
}

// Whether the segment from the light to `point` passes through a cube grown by `margin`.
bool room_point_shadowed(const glm::vec3& light, const glm::vec3& point, float margin) {
    const glm::vec3 to_point = point - light;
    const PixelRay ray{light, glm::normalize(to_point)};
    for (const glm::vec3& center : kCubeCenters) {
        const Aabb cube{center - glm::vec3(0.3f + margin), center + glm::vec3(0.3f + margin)};
        const auto hit = intersect_box(ray, cube);
        if (hit && *hit < glm::length(to_point)) return true;
    }
    return false;
}

// Per-wall agreement of the rendered visibility with the ray cast, over the room seen from
// two corners (which see all six walls between them).
struct RoomShadows {
    size_t checked[6] = {}, agree[6] = {}, shadowed[6] = {};  // per wall, outside shadow edges
    size_t seam_pixels = 0, seam_wrong = 0;                   // pixels on cube-face seams
    size_t outside_cone = 0, lit_outside_cone = 0;            // a spot's: beyond its outer angle
    std::vector<uint32_t> layers;                             // each frame's shadow layers
};

// The light is scene.lights[0]. For a spot, pixels within 1 degree of its cone's falloff
// (inner to outer angle) are not checked, and those beyond it count as outside the cone.
RoomShadows measure_room_shadows(Scene scene, ShadowFilter filter) {
    RenderSettings settings = small_settings(240, 180);
    settings.shadow.filter.mode = filter;
    settings.local_shadows.resolution = 512;
    const Light& light = scene.lights[0];
    const bool spot = light.type == LightType::Spot;
    const Camera views[2] = {{{3.6f, 5.6f, 3.6f}, {-4.0f, 0.0f, -4.0f}, {0, 1, 0}, 100.0f, 0.05f, 30.0f},
                             {{-3.6f, 0.4f, -3.6f}, {4.0f, 6.0f, 4.0f}, {0, 1, 0}, 100.0f, 0.05f, 30.0f}};
    RoomShadows room;
    for (const Camera& view : views) {
        scene.camera = view;
        const RenderedFrame frame = render_light(scene, settings, 0);
        if (!frame.info.local_shadows.empty()) room.layers.push_back(frame.info.local_shadows[0].layers);
        for (size_t i = 0; i < frame.images.world_position.size(); ++i) {
            const glm::vec4 p = frame.images.world_position[i];
            if (p.w == 0.0f) continue;
            const int wall = room_wall(glm::vec3(p));
            if (wall < 0) continue;
            const glm::vec3 point(p);
            const glm::vec3 to_point = point - light.position;
            const bool shadowed = frame.images.visibility[i] < 32768;
            if (spot) {
                const float cosine = glm::dot(glm::normalize(to_point), light.direction);
                const float degrees_from_axis = glm::degrees(std::acos(std::clamp(cosine, -1.0f, 1.0f)));
                if (degrees_from_axis > light.outer_angle_degrees + 1.0f) {
                    ++room.outside_cone;
                    room.lit_outside_cone += frame.images.visibility[i] > 0;
                    continue;
                }
                if (degrees_from_axis > light.inner_angle_degrees - 1.0f) continue;
            }
            const bool inner = room_point_shadowed(light.position, point, -0.03f);
            const bool outer = room_point_shadowed(light.position, point, 0.03f);
            if (inner != outer) continue;  // within 3 cm of a shadow edge
            ++room.checked[wall];
            room.agree[wall] += shadowed == inner;
            room.shadowed[wall] += shadowed && inner;
            // Cube-face seams: where two components of (point - light) are nearly equal.
            glm::vec3 a = glm::abs(to_point);
            std::sort(&a[0], &a[0] + 3);
            if (a[2] - a[1] < 0.02f * a[2]) {
                ++room.seam_pixels;
                room.seam_wrong += shadowed != inner;
            }
        }
    }
    return room;
}

// Each of `walls` shows its cube's shadow where the ray cast says, seams included.
void expect_walls_agree_with_the_ray_cast(const RoomShadows& room, std::initializer_list<int> walls) {
    for (int wall : walls) {
        const double agreement = room.checked[wall] ? double(room.agree[wall]) / room.checked[wall] : 0.0;
        std::printf("wall %d: %zu px checked, agreement %.4f, %zu px in the cube's shadow\n", wall, room.checked[wall],
                    agreement, room.shadowed[wall]);
        EXPECT_GT(room.checked[wall], 200u) << "wall " << wall;
        EXPECT_GE(agreement, 0.99) << "wall " << wall;
        EXPECT_GT(room.shadowed[wall], 20u) << "wall " << wall << ": no cube shadow (missing face?)";
    }
    std::printf("seam pixels %zu, wrong %zu\n", room.seam_pixels, room.seam_wrong);
    EXPECT_GT(room.seam_pixels, 50u);
    EXPECT_LE(room.seam_wrong, room.seam_pixels / 100);
}

class PointLightRoom : public ::testing::TestWithParam<ShadowFilter> {};

TEST_P(PointLightRoom, EveryCubeFaceShadowsItsWallWithoutSeams) {
    const RoomShadows room = measure_room_shadows(scene_from_toml(kRoomScene), GetParam());
    expect_walls_agree_with_the_ray_cast(room, {0, 1, 2, 3, 4, 5});
}

INSTANTIATE_TEST_SUITE_P(LocalLights, PointLightRoom,
                         ::testing::Values(ShadowFilter::Hard, ShadowFilter::Pcf, ShadowFilter::Poisson,
                                           ShadowFilter::Pcss, ShadowFilter::Vsm, ShadowFilter::Msm),
                         filter_test_name);

// The room with the point light replaced by a spot wider than one perspective layer can
// hold: outer half-angle 120 degrees (inner 100), pointing down.
Scene wide_spot_room() {
    std::string text = kRoomScene;
    const std::string point = "type = \"point\"";
    text.replace(text.find(point), point.size(),
                 "type = \"spot\"\ndirection = [0.0, -1.0, 0.0]\ninner_angle = 100.0\nouter_angle = 120.0");
    return scene_from_toml(text);
}

// The wide spot's shadow is a cube like a point light's. Inside the inner cone every wall
// but the ceiling shows its cube's shadow where a ray cast says, seams included; outside the
// outer cone nothing is lit (most of the ceiling).
class WideSpotRoom : public ::testing::TestWithParam<ShadowFilter> {};

TEST_P(WideSpotRoom, CubeShadowInsideTheConeNothingLitOutside) {
    const RoomShadows room = measure_room_shadows(wide_spot_room(), GetParam());
    EXPECT_EQ(room.layers, (std::vector<uint32_t>{6, 6})) << "a 120-degree spot is shadowed by a cube";
    expect_walls_agree_with_the_ray_cast(room, {0, 1, 3, 4, 5});
    std::printf("outside the cone %zu px, lit %zu\n", room.outside_cone, room.lit_outside_cone);
    EXPECT_GT(room.outside_cone, 2000u);
    EXPECT_EQ(room.lit_outside_cone, 0u);
}

INSTANTIATE_TEST_SUITE_P(LocalLights, WideSpotRoom,
                         ::testing::Values(ShadowFilter::Hard, ShadowFilter::Pcf, ShadowFilter::Pcss,
                                           ShadowFilter::Msm),
                         filter_test_name);

// Caster culling of a wide spot's cube (CPU only): the +Y face of the room's spot, pointing
// down with 120 degrees, lies wholly outside its cone (corner rays 125.3 degrees from the
// axis) and gets no draws; every other face has casters. Without culling every face gets
// every draw.
TEST(LocalLights, WideSpotFacesOutsideTheConeGetNoDraws) {
    const Scene scene = wide_spot_room();
    passes::CasterScene data;
    for (const Instance& instance : scene.instances) {
        passes::CasterDraw draw;
        draw.world_bounds = to_core(transform_aabb(scene.meshes[instance.mesh].bounds, instance.world));
        data.draws.push_back(draw);
    }
    const std::vector<core::Light> lights = to_core(scene.lights);
    LocalShadowPlan plan = penumbra::plan_local_shadows(lights, {});
    penumbra::fit_local_shadows(plan, lights, library::caster_bounds(data));
    const auto culled = library::cull_local_casters(lights, plan, data, true);
    ASSERT_EQ(culled.size(), 6u);
    for (uint32_t face = 0; face < 6; ++face) {
        EXPECT_EQ(culled[face].layer, face);
        if (face == 2) {
            EXPECT_TRUE(culled[face].draws.empty()) << "the +Y face is outside the cone";
        } else {
            EXPECT_FALSE(culled[face].draws.empty()) << "face " << face;
        }
    }
    for (const auto& layer : library::cull_local_casters(lights, plan, data, false)) {
        EXPECT_EQ(layer.draws.size(), data.draws.size()) << "no culling: face " << layer.layer;
    }
}

// PCSS for a spot: the penumbra of the box grows with the light's radius
// (w = (d_receiver - d_blocker) * radius / d_blocker: 0.5 m here for radius 0.5).
size_t spot_penumbra_pixels(float radius) {
    std::string text = kSpotScene;
    const std::string key = "radius = 0.0";
    text.replace(text.find(key), key.size(), "radius = " + std::to_string(radius));
    const Scene scene = scene_from_toml(text);
    RenderSettings settings = small_settings(320, 240);
    settings.shadow.filter.mode = ShadowFilter::Pcss;
    const RenderedFrame frame = render_light(scene, settings, 0);
    const Light& spot = scene.lights[0];
    const float cos_inner = std::cos(glm::radians(spot.inner_angle_degrees));
    size_t partial = 0;
    for (size_t i = 0; i < frame.images.world_position.size(); ++i) {
        const glm::vec4 p = frame.images.world_position[i];
        if (p.w == 0.0f || std::abs(p.y) > 1e-3f) continue;
        const float cos_angle = glm::dot(glm::normalize(glm::vec3(p) - spot.position), glm::normalize(spot.direction));
        const uint16_t v = frame.images.visibility[i];
        if (cos_angle >= cos_inner && v > 3000 && v < 62535) ++partial;
    }
    return partial;
}

TEST(LocalLights, SpotPcssPenumbraGrowsWithTheLightRadius) {
    const size_t small = spot_penumbra_pixels(0.02f);
    const size_t large = spot_penumbra_pixels(0.5f);
    std::printf("spot pcss penumbra pixels: radius 0.02 m: %zu, radius 0.5 m: %zu\n", small, large);
    EXPECT_GT(large, 3 * std::max<size_t>(small, 20));
}

// A spot of radius 0.5 m over a grate of slats 18 cm wide with 2 cm gaps, 3 m below it.
std::string spot_over_grate_scene() {
    std::string text = R"(
[camera]
eye = [0.0, 12.0, 6.0]
target = [0.0, 0.0, 0.0]
fov = 55.0
far = 60.0

[[lights]]
type = "spot"
position = [0.0, 6.0, 0.0]
direction = [0.0, -1.0, 0.0]
inner_angle = 33.0
outer_angle = 35.0
range = 25.0
radius = 0.5
intensity = 40.0

[[objects]]
type = "plane"
size = [30.0, 30.0]
)";
    char slat[128];
    for (int k = 0; k <= 10; ++k) {
        std::snprintf(slat, sizeof(slat),
                      "\n[[objects]]\ntype = \"box\"\nsize = [0.18, 0.1, 2.0]\ntranslation = [%.2f, 3.0, 0.0]\n",
                      -1.0 + 0.2 * k);
        text += slat;
    }
    return text;
}

// pcss_early_out on a spot, as on the sun (one PCSS for both, penumbra/glsl/filters.glsl):
// where every blocker tap occludes, the receiver is fully shadowed without the filter step.
// Under the grate the 16 search taps often all land on slats while the filter's taps also
// find the gaps, so some pixels turn black; every other pixel keeps its visibility.
TEST(LocalLights, SpotPcssEarlyOutShadowsWhereEveryBlockerTapOccludes) {
    const Scene scene = scene_from_toml(spot_over_grate_scene());
    RenderSettings settings = small_settings(320, 240);
    settings.shadow.filter.mode = ShadowFilter::Pcss;
    const RenderedFrame filtered = render_light(scene, settings, 0);
    settings.shadow.filter.pcss_early_out = true;
    const RenderedFrame early_out = render_light(scene, settings, 0);
    ASSERT_EQ(filtered.images.visibility.size(), early_out.images.visibility.size());
    size_t blackened = 0, changed_otherwise = 0;
    for (size_t i = 0; i < filtered.images.visibility.size(); ++i) {
        const uint16_t before = filtered.images.visibility[i];
        const uint16_t after = early_out.images.visibility[i];
        if (before == after) continue;
        ++(after == 0 ? blackened : changed_otherwise);
    }
    std::printf("spot pcss early out: %zu px turned fully shadowed, %zu changed otherwise\n", blackened,
                changed_otherwise);
    EXPECT_GT(blackened, 100u);
    EXPECT_EQ(changed_otherwise, 0u);
}

// Shadowed spot lights in a grid (5 m apart, `columns` per row), each over its own box.
glm::vec2 grid_light_xz(int index, int count, int columns) {
    const int rows = (count + columns - 1) / columns;
    const float x = 5.0f * (static_cast<float>(index % columns) - 0.5f * static_cast<float>(columns - 1));
    const float z = 5.0f * (static_cast<float>(index / columns) - 0.5f * static_cast<float>(rows - 1));
    return {x, z};
}

std::string spot_grid_scene(int count, int columns, float camera_height) {
    char buffer[512];
    std::snprintf(buffer, sizeof(buffer), R"(
[camera]
eye = [0.0, %f, 0.1]
target = [0.0, 0.0, 0.0]
fov = 60.0
far = 100.0

[[objects]]
type = "plane"
size = [60.0, 40.0]
)",
                  camera_height);
    std::string text = buffer;
    for (int i = 0; i < count; ++i) {
        const glm::vec2 xz = grid_light_xz(i, count, columns);
        std::snprintf(buffer, sizeof(buffer), R"(
[[lights]]
type = "spot"
position = [%f, 5.0, %f]
direction = [0.0, -1.0, 0.0]
inner_angle = 25.0
outer_angle = 28.0
range = 12.0
radius = 0.0
intensity = 20.0

[[objects]]
type = "box"
size = 0.8
translation = [%f, 2.0, %f]
)",
                      xz.x, xz.y, xz.x, xz.y);
        text += buffer;
    }
    return text;
}

struct UnderAndBeside {
    size_t under = 0, under_shadowed = 0;  // ground within 0.3 m of the light's axis
    size_t beside = 0, beside_lit = 0;     // 1 to 1.8 m to the side: past the box shadow, inside the inner cone
};

UnderAndBeside measure_under_and_beside(const RenderedFrame& frame, glm::vec2 light_xz) {
    UnderAndBeside result;
    for (size_t i = 0; i < frame.images.world_position.size(); ++i) {
        const glm::vec4 p = frame.images.world_position[i];
        if (p.w == 0.0f || std::abs(p.y) > 1e-3f) continue;
        const float dx = std::abs(p.x - light_xz.x), dz = std::abs(p.z - light_xz.y);
        const float visibility = frame.images.visibility[i] / 65535.0f;
        if (dx < 0.3f && dz < 0.3f) {
            ++result.under;
            result.under_shadowed += visibility < 0.5f;
        } else if (dx > 1.0f && dx < 1.8f && dz < 0.3f) {
            ++result.beside;
            result.beside_lit += visibility > 0.5f;
        }
    }
    return result;
}

// Renders light `light` of the grid's visibility and checks: one warning line naming
// `beyond` lights over `budget`; the light's box shadow under it exactly when `shadowed`;
// lit beside it.
void expect_grid_light(const Scene& scene, const RenderSettings& settings, int light, int count, int columns,
                       bool shadowed, const std::string& warning) {
    ::testing::internal::CaptureStderr();
    const RenderedFrame frame = render_light(scene, settings, light);
    const std::string errors = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(std::count(errors.begin(), errors.end(), '\n'), 1) << errors;
    EXPECT_NE(errors.find(warning), std::string::npos) << errors;
    const UnderAndBeside counts = measure_under_and_beside(frame, grid_light_xz(light, count, columns));
    std::printf("light %d: %zu/%zu px under the box shadowed, %zu/%zu beside lit\n", light, counts.under_shadowed,
                counts.under, counts.beside_lit, counts.beside);
    ASSERT_GT(counts.under, 10u);
    ASSERT_GT(counts.beside, 10u);
    EXPECT_EQ(counts.beside_lit, counts.beside) << "light " << light;
    EXPECT_EQ(counts.under_shadowed, shadowed ? counts.under : 0u) << "light " << light;
}

// Nine shadowed spot lights in a row: with a budget of 8 the ninth renders unshadowed with
// a one-line warning, and the first eight still shadow correctly.
TEST(LocalLights, LightsBeyondTheBudgetRenderUnshadowedWithOneWarning) {
    const Scene scene = scene_from_toml(spot_grid_scene(9, 9, 28.0f));
    RenderSettings settings = small_settings(480, 200);
    settings.shadow.filter.mode = ShadowFilter::Pcf;
    settings.local_shadows.resolution = 256;
    ASSERT_EQ(settings.local_shadows.budget, 8u);
    for (const int light : {0, 7, 8}) {
        expect_grid_light(scene, settings, light, 9, 9, light < 8,
                          "1 shadow-casting spot/point light(s) beyond the local shadow budget of 8");
    }
}

// Forty spots, the largest budget (32): all forty are lit, the first 32 shadowed.
TEST(LocalLights, FortyLightsWithTheLargestBudget) {
    const Scene scene = scene_from_toml(spot_grid_scene(40, 8, 36.0f));
    RenderSettings settings = small_settings(480, 320);
    settings.shadow.filter.mode = ShadowFilter::Pcf;
    settings.local_shadows.budget = kMaxLocalShadowBudget;
    for (const int light : {0, 31, 32, 39}) {
        expect_grid_light(scene, settings, light, 40, 8, light < 32,
                          "8 shadow-casting spot/point light(s) beyond the local shadow budget of 32");
    }
}

// --- Receiver-plane bias on a spot light: no acne on grazing ground, contact stays. ---

// A low spot light (2 m up, aimed 7 m ahead) over a plane with a 0.6 m cube on it: most of
// the lit ground is seen at 8 to 30 degrees of elevation, a steep slope in the light's
// depth. Depth and normal-offset biases are off, so only the receiver-plane bias stands
// between the ground and acne.
constexpr char kLowSpotScene[] = R"(
[camera]
eye = [5.0, 7.0, -1.0]
target = [0.0, 0.0, 2.5]
fov = 60.0
far = 40.0

[[lights]]
type = "spot"
position = [0.0, 2.0, -6.0]
direction = [0.0, -2.0, 7.0]
inner_angle = 38.0
outer_angle = 40.0
range = 20.0
radius = 0.02
intensity = 40.0

[[objects]]
type = "plane"
size = [16.0, 20.0]

[[objects]]
type = "box"
size = 0.6
translation = [0.0, 0.3, 1.5]
)";

struct LocalAcneAndContact {
    double lit_exact = 0.0;       // lit ground (away from the shadow edge) with visibility >= 0.99
    double contact_shadow = 0.0;  // shadowed ground next to the cube's base with visibility <= 0.02
};

LocalAcneAndContact measure_local_acne(ShadowFilter filter, bool receiver_plane_bias) {
    const Scene scene = scene_from_toml(kLowSpotScene);
    RenderSettings settings = small_settings(320, 240);
    settings.shadow.bias = {0.0f, 0.0f, 0.0f, 0.0f};
    settings.shadow.filter.mode = filter;
    settings.shadow.filter.receiver_plane_bias = receiver_plane_bias;
    const RenderedFrame frame = render_light(scene, settings, 0);
    const Light& spot = scene.lights[0];
    const Aabb cube{{-0.3f, 0.0f, 1.2f}, {0.3f, 0.6f, 1.8f}};
    const auto polygon = point_shadow_polygon(cube, spot.position);
    const float cos_inner = std::cos(glm::radians(spot.inner_angle_degrees));
    size_t lit = 0, lit_exact = 0, contact = 0, contact_dark = 0;
    for (size_t i = 0; i < frame.images.world_position.size(); ++i) {
        const glm::vec4 p = frame.images.world_position[i];
        if (p.w == 0.0f || std::abs(p.y) > 1e-3f) continue;
        const glm::vec3 point(p);
        const glm::vec3 to_point = glm::normalize(point - spot.position);
        if (glm::dot(to_point, glm::normalize(spot.direction)) < cos_inner) continue;
        if (-to_point.y < std::sin(glm::radians(8.0f))) continue;  // beyond the slope clamp (tan 84 degrees)
        const glm::vec2 xz(point.x, point.z);
        if (distance_to_polygon_edge(polygon, xz) < 0.1f) continue;
        const float visibility = frame.images.visibility[i] / 65535.0f;
        if (!inside_convex_polygon(polygon, xz)) {
            ++lit;
            lit_exact += visibility >= 0.99f;
            continue;
        }
        const glm::vec2 outside = glm::abs(xz - glm::vec2(0.0f, 1.5f)) - glm::vec2(0.3f);
        if (glm::length(glm::max(outside, glm::vec2(0.0f))) > 0.5f) continue;  // within 0.5 m of the base
        ++contact;
        contact_dark += visibility <= 0.02f;
    }
    EXPECT_GT(lit, 5000u);
    EXPECT_GT(contact, 40u);
    return {static_cast<double>(lit_exact) / std::max<size_t>(lit, 1),
            static_cast<double>(contact_dark) / std::max<size_t>(contact, 1)};
}

TEST(LocalLights, ReceiverPlaneBiasRemovesAcneOnGrazingGroundWithoutDetachingContactShadows) {
    for (const ShadowFilter filter : {ShadowFilter::Pcf, ShadowFilter::Poisson, ShadowFilter::Pcss}) {
        const LocalAcneAndContact without = measure_local_acne(filter, false);
        const LocalAcneAndContact with = measure_local_acne(filter, true);
        std::printf("spot, filter %d: lit ground exact %.4f without / %.4f with receiver-plane bias; contact %.4f\n",
                    static_cast<int>(filter), without.lit_exact, with.lit_exact, with.contact_shadow);
        EXPECT_LT(without.lit_exact, 0.5) << "without any bias the grazing ground should show acne";
        EXPECT_GE(with.lit_exact, 0.99) << "receiver-plane bias should remove the acne";
        EXPECT_GE(with.contact_shadow, 0.99) << "the shadow next to the cube's base should stay attached";
    }
}

// --- Moment filters on a spot light: vsm bleeds in the classic setup, evsm and msm much less. ---

// The sun's bleeding setup (test_filters.cpp) under a spot light straight above: a 0.5 m
// square 4.5 m up over a 4 m table 0.8 m up; the camera under the table sees only the
// table's umbra (truth: visibility 0), crossed by the small square's shadow edge (0.36 m
// from the centre), where Chebyshev's bound mixes two occluder distances.
constexpr char kSpotBleedingScene[] = R"(
[camera]
eye = [0.0, 0.5, 0.0]
target = [0.0, 0.0, 0.001]
up = [0.0, 0.0, -1.0]
fov = 90.0
near = 0.05
far = 3.0

[[lights]]
type = "spot"
position = [0.0, 14.0, 0.0]
direction = [0.0, -1.0, 0.0]
inner_angle = 28.0
outer_angle = 30.0
range = 20.0
intensity = 40.0

[[objects]]
type = "plane"
size = [12.0, 12.0]

[[objects]]
type = "box"
size = [4.0, 0.2, 4.0]
translation = [0.0, 0.8, 0.0]

[[objects]]
type = "box"
size = [0.5, 0.2, 0.5]
translation = [0.0, 4.5, 0.0]
)";

struct SpotBleeding {
    float max = 0.0f;
    float mean = 0.0f;
};

SpotBleeding measure_spot_bleeding(ShadowFilter filter) {
    const Scene scene = scene_from_toml(kSpotBleedingScene);
    RenderSettings settings = small_settings(160, 120);
    settings.shadow.filter.mode = filter;
    settings.shadow.filter.blur_radius = 4;
    settings.shadow.filter.light_bleeding_reduction = 0.0f;  // the raw bound of each technique
    const RenderedFrame frame = render_light(scene, settings, 0);
    SpotBleeding bleeding;
    double sum = 0.0;
    for (const uint16_t value : frame.images.visibility) {
        bleeding.max = std::max(bleeding.max, value / 65535.0f);
        sum += value / 65535.0;
    }
    bleeding.mean = static_cast<float>(sum / static_cast<double>(frame.images.visibility.size()));
    return bleeding;
}

TEST(LocalLights, SpotEvsmAndMsmBleedLessThanVsm) {
    const SpotBleeding vsm = measure_spot_bleeding(ShadowFilter::Vsm);
    const SpotBleeding evsm = measure_spot_bleeding(ShadowFilter::Evsm);
    const SpotBleeding msm = measure_spot_bleeding(ShadowFilter::Msm);
    const SpotBleeding pcf = measure_spot_bleeding(ShadowFilter::Pcf);
    std::printf(
        "spot light bleeding in the umbra (max / mean): vsm %.3f / %.4f, evsm %.3f / %.4f, msm %.3f / %.4f, "
        "pcf %.3f / %.4f\n",
        vsm.max, vsm.mean, evsm.max, evsm.mean, msm.max, msm.mean, pcf.max, pcf.mean);
    EXPECT_EQ(pcf.max, 0.0f) << "a comparison filter cannot bleed";
    EXPECT_GT(vsm.max, 0.15f) << "the classic setup should make VSM bleed";
    EXPECT_LT(evsm.max, 0.5f * vsm.max);
    EXPECT_LT(msm.max, 0.5f * vsm.max);
    EXPECT_LT(evsm.mean, 0.5f * vsm.mean);
    EXPECT_LT(msm.mean, 0.5f * vsm.mean);
}

// --- Coverage sizing: the spot's map follows its size on the screen; its shadow stays right. ---

TEST(LocalLights, CoverageSizingShrinksTheMapWithDistanceAndKeepsTheShadow) {
    Scene scene = scene_from_toml(kSpotScene);
    RenderSettings settings = small_settings(320, 240);
    settings.shadow.filter.mode = ShadowFilter::Pcf;
    uint32_t previous = 1u << 30;
    for (const float distance : {14.0f, 40.0f, 120.0f}) {
        scene.camera.eye = glm::normalize(glm::vec3(0.0f, 12.0f, 6.0f)) * distance;
        scene.camera.far_plane = distance + 40.0f;
        const RenderedFrame frame = render_light(scene, settings, 0);
        ASSERT_EQ(frame.info.local_shadows.size(), 1u);
        const uint32_t resolution = frame.info.local_shadows[0].resolution;
        // The box's shadow stays under the box: the ground pixel nearest (0, 0, 0) is dark.
        float best = 1e9f, visibility_at_origin = 1.0f;
        for (size_t i = 0; i < frame.images.world_position.size(); ++i) {
            const glm::vec4 p = frame.images.world_position[i];
            if (p.w == 0.0f || std::abs(p.y) > 1e-3f) continue;
            const float d = glm::length(glm::vec2(p.x, p.z));
            if (d < best) {
                best = d;
                visibility_at_origin = frame.images.visibility[i] / 65535.0f;
            }
        }
        std::printf("camera %.0f m away: spot map %u texels, visibility under the box %.3f\n", distance, resolution,
                    visibility_at_origin);
        EXPECT_LT(resolution, previous) << "farther away, the spot covers fewer pixels";
        EXPECT_LE(resolution, settings.local_shadows.resolution);
        EXPECT_LT(visibility_at_origin, 0.05f);
        previous = resolution;
    }
    settings.local_shadows.sizing = LocalShadowSizing::Fixed;
    const RenderedFrame fixed = render_light(scene, settings, 0);
    EXPECT_EQ(fixed.info.local_shadows[0].resolution, settings.local_shadows.resolution);
}

}  // namespace
}  // namespace penumbra::testing

namespace penumbra::testing {
namespace {

// KHR_lights_punctual (issue 19): the spot, point and directional lights of
// tests/data/gltf/lights.gltf, imported with `import_lights = true`, render the very image
// of the same lights written in the scene file (the mapping of docs/scene-format.md:
// -Z of the node, radians to degrees, range 20 m for 4 cd without a range, radius 0).
TEST(LocalLights, PunctualLightsFromGltfRenderAsTheSameSceneFileLights) {
    const std::string base = R"(
[camera]
eye = [6.0, 9.0, 10.0]
target = [0.0, 0.0, 0.0]

[[objects]]
type = "plane"
size = [30.0, 30.0]

[[objects]]
type = "box"
size = [1.0, 1.0, 1.0]
translation = [0.3, 1.0, 0.2]
)";
    const std::string model =
        "\n[[objects]]\ntype = \"gltf\"\nfile = \"" PENUMBRA_TEST_DATA_DIR "/gltf/lights.gltf\"\n";
    char lights[1024];
    std::snprintf(lights, sizeof(lights), R"(
[[lights]]
type = "spot"
position = [0.0, 5.0, 0.0]
direction = [0.0, -1.0, 0.0]
color = [1.0, 0.5, 0.25]
intensity = 40.0
range = 12.0
inner_angle = %.9g
outer_angle = %.9g
radius = 0.0

[[lights]]
type = "point"
position = [2.0, 3.0, 0.0]
intensity = 4.0
range = 20.0
radius = 0.0

[[lights]]
type = "directional"
direction = [0.0, -1.0, 0.0]
intensity = 2.5
)",
                  static_cast<double>(static_cast<float>(glm::degrees(0.2))),
                  static_cast<double>(static_cast<float>(glm::degrees(0.6))));
    const RenderSettings settings = small_settings(160, 120);
    const RenderedFrame imported =
        render_with_validation(scene_from_toml(base + model + "import_lights = true\n"), settings);
    const RenderedFrame written = render_with_validation(scene_from_toml(base + lights + model), settings);
    ASSERT_EQ(imported.images.color_rgba8.size(), written.images.color_rgba8.size());
    EXPECT_TRUE(imported.images.color_rgba8 == written.images.color_rgba8) << "the imported lights render differently";
    EXPECT_EQ(imported.info.local_shadows.size(), 2u) << "both local lights are shadowed";
}

}  // namespace
}  // namespace penumbra::testing
