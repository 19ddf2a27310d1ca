#pragma once
// How far a rendered sun-visibility image is from the ray-traced reference (docs/QUALITY.md
// defines every number). Pure functions over images, row 0 at the top; no Vulkan.
//
// Only "evaluated" pixels count: geometry present, facing the sun (N.L > 0) and inside
// the shadow distance. A rendered pixel is "shadowed" when its visibility is below 0.5.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace penumbra::quality {

// One frame's images, all width * height.
struct VisibilityComparison {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> rendered;     // [0, 1]
    std::vector<uint8_t> hard;       // reference: 1 lit, 0 shadowed
    std::vector<float> soft;         // reference over the sun's disk, [0, 1]
    std::vector<uint8_t> evaluated;  // 1 where the pixel counts
};

constexpr float kShadowedBelow = 0.5f;
// A pixel is in the penumbra when its visibility lies strictly inside this range.
constexpr float kPenumbraLow = 0.05f;
constexpr float kPenumbraHigh = 0.95f;

// Evaluated pixels with an evaluated 4-neighbour of the other hard-reference value: both
// sides of every true shadow boundary.
std::vector<uint8_t> shadow_boundary(uint32_t width, uint32_t height, std::span<const uint8_t> hard,
                                     std::span<const uint8_t> evaluated);

// Chessboard distance from every pixel to the nearest seed pixel (two-pass chamfer
// transform, Rosenfeld & Pfaltz 1966); UINT32_MAX everywhere when there is no seed.
std::vector<uint32_t> chessboard_distance(uint32_t width, uint32_t height, std::span<const uint8_t> seeds);

// 1 for pixels within `band_px` pixels of a true shadow boundary (boundary pixels are at
// distance 0, so band 2 covers two pixels on each side); all 0 for band 0.
std::vector<uint8_t> edge_band(uint32_t width, uint32_t height, std::span<const uint8_t> boundary, uint32_t band_px);

// The value at `fraction` (0..1) of the sorted values, nearest rank; 0 when empty.
double percentile(std::vector<float> values, double fraction);

struct ClassError {
    uint64_t truth_pixels = 0;  // evaluated pixels of this reference class
    uint64_t wrong_pixels = 0;  // of which the render disagrees
    double percent() const { return truth_pixels ? 100.0 * static_cast<double>(wrong_pixels) / truth_pixels : 0.0; }
};

struct HardShadowMetrics {
    uint64_t evaluated_pixels = 0;
    uint64_t boundary_pixels = 0;
    ClassError false_shadow;                // lit in truth, shadowed in the render (acne, over-bias)
    ClassError false_lit;                   // shadowed in truth, lit in the render (leaks, peter-panning)
    ClassError false_shadow_outside_edges;  // the same, excluding the edge band
    ClassError false_lit_outside_edges;
};

HardShadowMetrics hard_shadow_metrics(const VisibilityComparison& frame, std::span<const uint8_t> boundary,
                                      std::span<const uint8_t> band);

// The shadows beside contacts, which shadow maps' biases and texels lose first and contact
// shadows are for: "contact pixels" are evaluated pixels the hard reference shadows with an
// occluder within a short reach (ReferenceImages::contact); the band is every evaluated
// pixel within `band_px` (chessboard) of one, on both sides of the contact line.
struct ContactMetrics {
    uint64_t contact_pixels = 0;
    uint64_t band_pixels = 0;
    ClassError false_lit;     // shadowed in truth, lit in the render, in the band
    ClassError false_shadow;  // lit in truth, shadowed in the render, in the band
};

ContactMetrics contact_metrics(const VisibilityComparison& frame, std::span<const uint8_t> contact, uint32_t band_px);

struct SoftShadowMetrics {
    double mean_abs_error = 0.0;       // |rendered - soft reference| over evaluated pixels
    double p95_abs_error = 0.0;        // its 95th percentile
    double edge_mean_abs_error = 0.0;  // over the evaluated pixels of the edge band
    uint64_t penumbra_pixels_render = 0;
    uint64_t penumbra_pixels_reference = 0;
    // Penumbra width along the edges, estimated as area / length: penumbra pixels divided by
    // the boundary length (boundary pixels / 2, as both sides are marked), in pixels.
    double edge_length_px = 0.0;
    double penumbra_width_render_px = 0.0;
    double penumbra_width_reference_px = 0.0;
    double penumbra_width_error_px = 0.0;  // render - reference
};

SoftShadowMetrics soft_shadow_metrics(const VisibilityComparison& frame, std::span<const uint8_t> boundary,
                                      std::span<const uint8_t> band);

// Temporal stability: K frames of the same view under small camera motions. Shimmer is a
// change of the shadow at a fixed place in the world, so each pixel of frame k is matched
// with the pixel of frame 0 that shows the same surface point (reprojection): the change
// is |visibility_k - visibility_0| there. A pixel is compared only when both are evaluated,
// show the same surface (positions closer than `same_surface_pixels` pixel footprints)
// and their hard references agree (the truth did not change).
struct StabilityFrame {
    std::span<const float> rendered;
    std::span<const uint8_t> hard;
    std::span<const uint8_t> evaluated;
    std::span<const glm::vec4> positions;  // world position per pixel (w = 1 where geometry)
    glm::mat4 view_projection{1.0f};       // world -> Vulkan clip of the frame's camera
    glm::vec3 eye{0.0f};
};

struct StabilityGeometry {
    uint32_t width = 0;
    uint32_t height = 0;
    float pixel_angle = 0.0f;  // 2 tan(fov_y / 2) / height: a pixel's footprint per metre of distance
    float same_surface_pixels = 2.0f;
};

struct StabilityMetrics {
    uint32_t frames = 0;
    uint64_t compared_pixels = 0;  // matched pixel pairs over frames 1..K-1
    double mean_change = 0.0;
    double p99_change = 0.0;
    double max_change = 0.0;
    double flicker_percent = 0.0;  // compared pixels whose change exceeds 0.5 (lit <-> shadowed)
};

StabilityMetrics stability_metrics(std::span<const StabilityFrame> frames, const StabilityGeometry& geometry);

// The grain of filters that rotate their sampling pattern per frame (Poisson, PCSS): the
// per-pixel change between two renders of the same frame whose patterns differ only in
// rotation. 0 for filters that do not rotate; a temporal filter (TAA) averages it away.
struct SamplingNoise {
    uint64_t compared_pixels = 0;  // evaluated pixels
    double mean_change = 0.0;
    double p99_change = 0.0;
    double max_change = 0.0;
};

SamplingNoise sampling_noise(std::span<const float> first, std::span<const float> rotated,
                             std::span<const uint8_t> evaluated);

}  // namespace penumbra::quality
