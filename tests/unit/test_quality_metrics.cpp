// The metric math of `penumbra compare` (src/quality/shadow_metrics.hpp) on small
// hand-made images, and the sampling helpers of the soft reference.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "quality/camera_jitter.hpp"
#include "quality/error_images.hpp"
#include "quality/shadow_metrics.hpp"
#include "quality/sun_disk_sampling.hpp"

namespace penumbra::quality {
namespace {

// A width x height frame whose left `shadow_columns` columns are shadowed in truth.
VisibilityComparison split_frame(uint32_t width, uint32_t height, uint32_t shadow_columns) {
    VisibilityComparison frame{width, height, {}, {}, {}, {}};
    const size_t pixels = size_t{width} * height;
    frame.evaluated.assign(pixels, 1);
    frame.hard.resize(pixels);
    frame.soft.resize(pixels);
    frame.rendered.resize(pixels);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const size_t i = size_t{y} * width + x;
            frame.hard[i] = x >= shadow_columns;
            frame.soft[i] = frame.hard[i];
            frame.rendered[i] = frame.hard[i];
        }
    }
    return frame;
}

struct Masks {
    std::vector<uint8_t> boundary;
    std::vector<uint8_t> band;
};

Masks masks_of(const VisibilityComparison& frame, uint32_t band_px) {
    Masks masks{shadow_boundary(frame.width, frame.height, frame.hard, frame.evaluated), {}};
    masks.band = edge_band(frame.width, frame.height, masks.boundary, band_px);
    return masks;
}

TEST(QualityMetrics, BoundaryMarksBothSidesOfTheEdge) {
    const VisibilityComparison frame = split_frame(10, 4, 5);
    const Masks masks = masks_of(frame, 2);
    for (uint32_t x = 0; x < 10; ++x) {
        EXPECT_EQ(masks.boundary[x], x == 4 || x == 5) << x;
        EXPECT_EQ(masks.band[x], x >= 3 && x <= 6) << x;  // distance < 2 from columns 4 and 5
    }
}

TEST(QualityMetrics, UnevaluatedNeighboursAreNoBoundary) {
    VisibilityComparison frame = split_frame(10, 1, 5);
    frame.evaluated[5] = 0;
    const Masks masks = masks_of(frame, 1);
    EXPECT_EQ(masks.boundary[4], 0);
    EXPECT_EQ(masks.boundary[6], 0);
}

TEST(QualityMetrics, ChessboardDistanceCountsDiagonalsAsOne) {
    std::vector<uint8_t> seeds(25, 0);
    seeds[12] = 1;  // the centre of 5x5
    const std::vector<uint32_t> distance = chessboard_distance(5, 5, seeds);
    EXPECT_EQ(distance[12], 0u);
    EXPECT_EQ(distance[6], 1u);
    EXPECT_EQ(distance[0], 2u);
    EXPECT_EQ(distance[24], 2u);
    EXPECT_EQ(chessboard_distance(2, 2, std::vector<uint8_t>(4, 0))[3], UINT32_MAX);
}

TEST(QualityMetrics, PerfectRenderHasNoError) {
    const VisibilityComparison frame = split_frame(20, 10, 8);
    const Masks masks = masks_of(frame, 2);
    const HardShadowMetrics hard = hard_shadow_metrics(frame, masks.boundary, masks.band);
    EXPECT_EQ(hard.evaluated_pixels, 200u);
    EXPECT_EQ(hard.false_shadow.truth_pixels, 120u);
    EXPECT_EQ(hard.false_lit.truth_pixels, 80u);
    EXPECT_EQ(hard.false_shadow.percent(), 0.0);
    EXPECT_EQ(hard.false_lit.percent(), 0.0);
    const SoftShadowMetrics soft = soft_shadow_metrics(frame, masks.boundary, masks.band);
    EXPECT_EQ(soft.mean_abs_error, 0.0);
    EXPECT_EQ(soft.edge_length_px, 10.0);
    EXPECT_EQ(soft.penumbra_width_error_px, 0.0);
}

TEST(QualityMetrics, AcneCountsAsFalseShadowOutsideEdges) {
    VisibilityComparison frame = split_frame(20, 10, 8);
    frame.rendered[5 * 20 + 15] = 0.2f;  // a dark speck on the lit side, far from the edge
    frame.rendered[5 * 20 + 8] = 0.3f;   // and one right at the edge
    const Masks masks = masks_of(frame, 2);
    const HardShadowMetrics hard = hard_shadow_metrics(frame, masks.boundary, masks.band);
    EXPECT_EQ(hard.false_shadow.wrong_pixels, 2u);
    EXPECT_NEAR(hard.false_shadow.percent(), 100.0 * 2.0 / 120.0, 1e-9);
    EXPECT_EQ(hard.false_shadow_outside_edges.wrong_pixels, 1u);
    EXPECT_EQ(hard.false_shadow_outside_edges.truth_pixels, 100u);  // 2 lit columns in the band
    EXPECT_EQ(hard.false_lit.wrong_pixels, 0u);
}

TEST(QualityMetrics, LeakCountsAsFalseLit) {
    VisibilityComparison frame = split_frame(20, 10, 8);
    frame.rendered[0] = 0.9f;
    const Masks masks = masks_of(frame, 2);
    const HardShadowMetrics hard = hard_shadow_metrics(frame, masks.boundary, masks.band);
    EXPECT_EQ(hard.false_lit.wrong_pixels, 1u);
    EXPECT_NEAR(hard.false_lit.percent(), 100.0 / 80.0, 1e-9);
}

// Columns 0-7 shadowed in truth; column 0 is the contact (its occluder within reach). The
// band of 2 px covers columns 0-2; a render that loses the shadow in columns 0-1 (and in
// column 6, outside the band) is wrong in 2 of the band's 3 columns.
TEST(QualityMetrics, ContactBandCountsOnlyThePixelsNearAContact) {
    VisibilityComparison frame = split_frame(20, 10, 8);
    std::vector<uint8_t> contact(frame.hard.size(), 0);
    for (uint32_t y = 0; y < frame.height; ++y) {
        contact[size_t{y} * frame.width] = 1;
        frame.rendered[size_t{y} * frame.width] = 1.0f;      // lost at the contact
        frame.rendered[size_t{y} * frame.width + 1] = 1.0f;  // and beside it
        frame.rendered[size_t{y} * frame.width + 6] = 1.0f;  // far from it: not in the band
    }
    const ContactMetrics metrics = contact_metrics(frame, contact, 2);
    EXPECT_EQ(metrics.contact_pixels, 10u);
    EXPECT_EQ(metrics.band_pixels, 30u);
    EXPECT_EQ(metrics.false_lit.truth_pixels, 30u);
    EXPECT_EQ(metrics.false_lit.wrong_pixels, 20u);
    EXPECT_EQ(metrics.false_shadow.truth_pixels, 0u);

    // A contact beside lit ground (column 8 is lit): the band reaches across the line.
    std::fill(contact.begin(), contact.end(), 0);
    for (uint32_t y = 0; y < frame.height; ++y) contact[size_t{y} * frame.width + 7] = 1;
    frame.rendered[9] = 0.0f;  // lit in truth, darkened, 2 px from the contact
    const ContactMetrics across = contact_metrics(frame, contact, 2);
    EXPECT_EQ(across.false_shadow.truth_pixels, 20u);
    EXPECT_EQ(across.false_shadow.wrong_pixels, 1u);
    EXPECT_TRUE(contact_metrics(frame, {}, 2).band_pixels == 0) << "no contact image (a spot light): nothing";
}

TEST(QualityMetrics, PenumbraWidthIsAreaOverEdgeLength) {
    VisibilityComparison frame = split_frame(20, 10, 8);
    for (uint32_t y = 0; y < 10; ++y) {
        for (uint32_t x = 6; x < 10; ++x) frame.rendered[y * 20 + x] = 0.5f;  // a 4-pixel-wide soft edge
        frame.soft[y * 20 + 8] = 0.5f;                                        // truth: 1 pixel wide
    }
    const Masks masks = masks_of(frame, 2);
    const SoftShadowMetrics soft = soft_shadow_metrics(frame, masks.boundary, masks.band);
    EXPECT_EQ(soft.penumbra_pixels_render, 40u);
    EXPECT_EQ(soft.penumbra_pixels_reference, 10u);
    EXPECT_DOUBLE_EQ(soft.penumbra_width_render_px, 4.0);
    EXPECT_DOUBLE_EQ(soft.penumbra_width_reference_px, 1.0);
    EXPECT_DOUBLE_EQ(soft.penumbra_width_error_px, 3.0);
    EXPECT_GT(soft.edge_mean_abs_error, soft.mean_abs_error);
}

TEST(QualityMetrics, PercentileIsNearestRank) {
    std::vector<float> values;
    for (int i = 1; i <= 100; ++i) values.push_back(static_cast<float>(i));
    EXPECT_EQ(percentile(values, 0.95), 95.0);
    EXPECT_EQ(percentile(values, 1.0), 100.0);
    EXPECT_EQ(percentile(values, 0.0), 1.0);
    EXPECT_EQ(percentile({}, 0.5), 0.0);
}

// Four pixels in a row whose world positions are their own clip coordinates (identity
// view-projection), so every pixel reprojects onto itself.
std::vector<glm::vec4> row_positions() {
    std::vector<glm::vec4> positions;
    for (int i = 0; i < 4; ++i) positions.emplace_back((i + 0.5f) / 4.0f * 2.0f - 1.0f, 0.0f, 0.5f, 1.0f);
    return positions;
}

TEST(QualityMetrics, StabilityComparesTheSameSurfacePointAcrossFrames) {
    const std::vector<uint8_t> evaluated(4, 1);
    const std::vector<uint8_t> hard_a{1, 1, 0, 0};
    const std::vector<uint8_t> hard_b{1, 1, 0, 1};  // pixel 3's truth changes: not compared
    const std::vector<float> rendered_a{1.0f, 1.0f, 0.0f, 0.0f};
    const std::vector<float> rendered_b{1.0f, 0.4f, 0.1f, 1.0f};
    const std::vector<glm::vec4> positions = row_positions();
    const glm::vec3 eye(0.0f, 0.0f, -1.0f);
    const StabilityFrame frames[] = {{rendered_a, hard_a, evaluated, positions, glm::mat4(1.0f), eye},
                                     {rendered_b, hard_b, evaluated, positions, glm::mat4(1.0f), eye}};
    const StabilityMetrics stability = stability_metrics(frames, {4, 1, 1.0f, 2.0f});
    EXPECT_EQ(stability.frames, 2u);
    EXPECT_EQ(stability.compared_pixels, 3u);
    EXPECT_NEAR(stability.mean_change, (0.0 + 0.6 + 0.1) / 3.0, 1e-6);
    EXPECT_NEAR(stability.max_change, 0.6, 1e-6);
    EXPECT_NEAR(stability.flicker_percent, 100.0 / 3.0, 1e-9);
}

TEST(QualityMetrics, StabilityFollowsTheSurfaceWhenTheCameraMoves) {
    // Frame 1's camera moved one pixel to the left: its pixel i shows frame 0's pixel i + 1.
    const std::vector<uint8_t> evaluated(4, 1);
    const std::vector<uint8_t> hard(4, 1);
    const std::vector<float> rendered_a{0.1f, 0.2f, 0.3f, 0.4f};
    const std::vector<float> rendered_b{0.2f, 0.3f, 0.4f, 0.9f};
    const std::vector<glm::vec4> positions_a = row_positions();
    std::vector<glm::vec4> positions_b(positions_a.begin() + 1, positions_a.end());
    positions_b.emplace_back(5.0f, 0.0f, 0.5f, 1.0f);  // off frame 0's screen
    const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f, 0.0f, 0.0f));
    const glm::vec3 eye(0.0f, 0.0f, -1.0f);
    const StabilityFrame frames[] = {{rendered_a, hard, evaluated, positions_a, glm::mat4(1.0f), eye},
                                     {rendered_b, hard, evaluated, positions_b, moved, eye}};
    const StabilityMetrics stability = stability_metrics(frames, {4, 1, 1.0f, 2.0f});
    EXPECT_EQ(stability.compared_pixels, 3u);
    EXPECT_NEAR(stability.max_change, 0.0, 1e-6);
}

TEST(QualityMetrics, ErrorImageColoursEachKindOfError) {
    VisibilityComparison frame = split_frame(4, 1, 2);
    frame.rendered = {0.0f, 1.0f, 0.0f, 1.0f};  // pixel 1: false lit, pixel 2: false shadow
    const std::vector<uint8_t> color(16, 128);
    const RgbaImage image = hard_error_image(frame, color);
    EXPECT_EQ(image.pixels[1 * 4 + 0], kFalseLitColor[0]);
    EXPECT_EQ(image.pixels[1 * 4 + 2], kFalseLitColor[2]);
    EXPECT_EQ(image.pixels[2 * 4 + 0], kFalseShadowColor[0]);
    EXPECT_EQ(image.pixels[0 * 4 + 0], image.pixels[0 * 4 + 1]);  // correct pixels stay grey
    const RgbaImage panels[] = {image, image};
    EXPECT_EQ(side_by_side(panels, 2).width, 10u);
}

TEST(SunDiskSampling, ConcentricMapFillsTheUnitDiskEvenly) {
    int inner = 0;
    const int n = 64;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const glm::vec2 p = concentric_disk({(i + 0.5f) / n, (j + 0.5f) / n});
            EXPECT_LE(glm::length(p), 1.0f + 1e-5f);
            inner += glm::length(p) < std::sqrt(0.5f);
        }
    }
    EXPECT_NEAR(static_cast<double>(inner) / (n * n), 0.5, 0.02);  // area-preserving
}

TEST(SunDiskSampling, LatticeIsStratifiedAndDirectionsStayInTheCone) {
    const glm::vec3 to_sun = glm::normalize(glm::vec3(0.3f, 1.0f, -0.2f));
    const SunDisk sun(to_sun, 0.53f);
    const float half_angle = glm::radians(0.53f) * 0.5f;
    for (uint32_t i = 0; i < 64; ++i) {
        const glm::vec2 square = fibonacci_lattice(i, 64, {0.3f, 0.7f});
        EXPECT_GE(square.x, 0.0f);
        EXPECT_LT(square.y, 1.0f);
        const glm::vec3 direction = sun.direction(concentric_disk(square));
        EXPECT_LE(std::acos(std::min(1.0f, glm::dot(direction, to_sun))), half_angle * 1.01f);
    }
    const TangentBasis basis = orthonormal_basis(to_sun);
    EXPECT_NEAR(glm::dot(basis.tangent, to_sun), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(basis.bitangent, basis.tangent), 0.0f, 1e-6f);
}

TEST(CameraJitter, MovesByFractionsToAFewTexels) {
    Camera camera;
    EXPECT_EQ(jittered_camera(camera, 0, 0.01f).eye, camera.eye);
    for (uint32_t frame = 1; frame < 16; ++frame) {
        const Camera moved = jittered_camera(camera, frame, 0.01f);
        const float distance = glm::length(moved.eye - camera.eye);
        EXPECT_GT(distance, 0.0015f);
        EXPECT_LT(distance, 0.04f);
        const float turn = std::acos(std::min(
            1.0f, glm::dot(glm::normalize(moved.target - moved.eye), glm::normalize(camera.target - camera.eye))));
        EXPECT_LT(turn * glm::length(camera.target - camera.eye), 0.05f);
    }
}

}  // namespace
}  // namespace penumbra::quality
