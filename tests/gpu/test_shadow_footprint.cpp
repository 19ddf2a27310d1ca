// A box floating above a ground plane: the shadow in the visibility AOV must match the
// analytic footprint (the box projected along the light onto the plane), and the lit
// ground must be free of acne.
#include <gtest/gtest.h>

#include <cmath>

#include "analytic_shadow.hpp"
#include "render_fixture.hpp"

namespace penumbra::testing {
namespace {

struct FootprintResult {
    double iou = 0.0;
    double lit_exact_fraction = 0.0;    // lit ground pixels (away from the edge) with visibility exactly 1
    double umbra_exact_fraction = 0.0;  // shadowed ground pixels (away from the edge) with visibility exactly 0
    size_t ground_pixels = 0;
};

// World size of a shadow texel at a point `distance` metres along a primary ray (the
// cascades are selected by view depth, which is at most that distance).
float texel_size_at(const std::vector<CascadeInfo>& cascades, float distance) {
    for (const CascadeInfo& cascade : cascades) {
        if (distance <= cascade.split_far) return cascade.texel_world_size;
    }
    return cascades.back().texel_world_size;
}

FootprintResult measure_footprint(const glm::vec3& light_direction) {
    const Scene scene = scene_from_toml(ground_scene_toml(light_direction, kFloatingBoxToml));
    const RenderSettings settings = small_settings(320, 240);
    const RenderedFrame frame = render_with_validation(scene, settings);
    EXPECT_TRUE(frame.validation_messages.empty()) << frame.validation_messages.front();

    const testing::Box& box = kFloatingBoxBounds;
    const glm::vec3 light = glm::normalize(light_direction);
    const auto polygon = shadow_polygon(box, light);
    size_t intersection = 0, union_count = 0, lit = 0, lit_exact = 0, umbra = 0, umbra_exact = 0;
    FootprintResult result;
    for (uint32_t y = 0; y < settings.height; ++y) {
        for (uint32_t x = 0; x < settings.width; ++x) {
            const PixelRay ray = pixel_ray(scene.camera, settings.width, settings.height, x, y);
            const auto ground = intersect_ground(ray, kGroundSceneHalfSize);
            const auto box_hit = intersect_box(ray, box);
            if (!ground || (box_hit && *box_hit < *ground)) continue;
            ++result.ground_pixels;
            const glm::vec3 point = ray.origin + ray.direction * *ground;
            const glm::vec2 ground_xz(point.x, point.z);
            const bool truth = inside_convex_polygon(polygon, ground_xz);
            const float visibility = visibility_at(frame.images, x, y);
            const bool rendered = visibility < 0.5f;
            intersection += truth && rendered;
            union_count += truth || rendered;
            // Away from the edge the answer must be exact. The edge band is 3 texels of the
            // cascade that shades the pixel (bilinear comparison and the normal offset blur
            // the edge over about that width), stretched by 1 / cos(angle of incidence) as a
            // texel's footprint on the ground is.
            const float edge_band = 3.0f * texel_size_at(frame.info.cascades, *ground) / std::abs(light.y);
            if (distance_to_polygon_edge(polygon, ground_xz) < edge_band) continue;
            if (truth) {
                ++umbra;
                umbra_exact += visibility == 0.0f;
            } else {
                ++lit;
                lit_exact += visibility == 1.0f;
            }
        }
    }
    result.iou = union_count ? static_cast<double>(intersection) / union_count : 0.0;
    result.lit_exact_fraction = lit ? static_cast<double>(lit_exact) / lit : 0.0;
    result.umbra_exact_fraction = umbra ? static_cast<double>(umbra_exact) / umbra : 0.0;
    return result;
}

void expect_footprint(const glm::vec3& light_direction) {
    const FootprintResult result = measure_footprint(light_direction);
    EXPECT_GT(result.ground_pixels, 20000u);
    EXPECT_GE(result.iou, 0.97) << "shadow footprint differs from the analytic projection";
    EXPECT_GE(result.lit_exact_fraction, 0.999) << "acne on the lit ground";
    EXPECT_GE(result.umbra_exact_fraction, 0.999) << "light leaks inside the shadow";
}

TEST(ShadowFootprint, BoxAbovePlaneWithLightStraightDown) { expect_footprint({0.0f, -1.0f, 0.0f}); }

TEST(ShadowFootprint, BoxAbovePlaneWithSlantedLight) { expect_footprint({-0.6f, -1.0f, 0.35f}); }

TEST(ShadowFootprint, BoxAbovePlaneWithGrazingLight) { expect_footprint({0.9f, -0.5f, -0.4f}); }

}  // namespace
}  // namespace penumbra::testing
