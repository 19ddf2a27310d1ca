#include "quality/shadow_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace penumbra::quality {

std::vector<uint8_t> shadow_boundary(uint32_t width, uint32_t height, std::span<const uint8_t> hard,
                                     std::span<const uint8_t> evaluated) {
    std::vector<uint8_t> boundary(size_t{width} * height, 0);
    const auto differs = [&](size_t a, size_t b) { return evaluated[b] && hard[a] != hard[b]; };
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const size_t pixel = size_t{y} * width + x;
            if (!evaluated[pixel]) continue;
            boundary[pixel] = (x > 0 && differs(pixel, pixel - 1)) || (x + 1 < width && differs(pixel, pixel + 1)) ||
                              (y > 0 && differs(pixel, pixel - width)) ||
                              (y + 1 < height && differs(pixel, pixel + width));
        }
    }
    return boundary;
}

std::vector<uint32_t> chessboard_distance(uint32_t width, uint32_t height, std::span<const uint8_t> seeds) {
    constexpr uint32_t kFar = std::numeric_limits<uint32_t>::max();
    std::vector<uint32_t> distance(size_t{width} * height, kFar);
    for (size_t i = 0; i < distance.size(); ++i) {
        if (seeds[i]) distance[i] = 0;
    }
    const auto relax = [&](size_t pixel, int64_t x, int64_t y) {
        if (x < 0 || y < 0 || x >= width || y >= height) return;
        const uint32_t neighbour = distance[static_cast<size_t>(y) * width + static_cast<size_t>(x)];
        if (neighbour != kFar) distance[pixel] = std::min(distance[pixel], neighbour + 1);
    };
    // Forward pass: the neighbours already visited above and to the left; the backward pass
    // mirrors it (below and to the right).
    constexpr int64_t kForward[4][2] = {{-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
    for (int64_t y = 0; y < height; ++y) {
        for (int64_t x = 0; x < width; ++x) {
            const size_t pixel = static_cast<size_t>(y) * width + static_cast<size_t>(x);
            for (const auto& step : kForward) relax(pixel, x + step[0], y + step[1]);
        }
    }
    for (int64_t y = height - 1; y >= 0; --y) {
        for (int64_t x = width - 1; x >= 0; --x) {
            const size_t pixel = static_cast<size_t>(y) * width + static_cast<size_t>(x);
            for (const auto& step : kForward) relax(pixel, x - step[0], y - step[1]);
        }
    }
    return distance;
}

std::vector<uint8_t> edge_band(uint32_t width, uint32_t height, std::span<const uint8_t> boundary, uint32_t band_px) {
    std::vector<uint8_t> band(size_t{width} * height, 0);
    if (band_px == 0) return band;
    const std::vector<uint32_t> distance = chessboard_distance(width, height, boundary);
    for (size_t i = 0; i < band.size(); ++i) band[i] = distance[i] < band_px;
    return band;
}

double percentile(std::vector<float> values, double fraction) {
    if (values.empty()) return 0.0;
    const auto rank = static_cast<size_t>(std::ceil(std::clamp(fraction, 0.0, 1.0) * values.size()));
    const size_t index = rank == 0 ? 0 : rank - 1;
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index), values.end());
    return values[index];
}

namespace {

void count_class(ClassError& all, ClassError& outside, bool wrong, bool in_band) {
    all.truth_pixels += 1;
    all.wrong_pixels += wrong;
    if (in_band) return;
    outside.truth_pixels += 1;
    outside.wrong_pixels += wrong;
}

}  // namespace

HardShadowMetrics hard_shadow_metrics(const VisibilityComparison& frame, std::span<const uint8_t> boundary,
                                      std::span<const uint8_t> band) {
    HardShadowMetrics metrics;
    for (size_t i = 0; i < frame.evaluated.size(); ++i) {
        if (!frame.evaluated[i]) continue;
        metrics.evaluated_pixels += 1;
        metrics.boundary_pixels += boundary[i];
        const bool rendered_lit = frame.rendered[i] >= kShadowedBelow;
        if (frame.hard[i]) {
            count_class(metrics.false_shadow, metrics.false_shadow_outside_edges, !rendered_lit, band[i]);
        } else {
            count_class(metrics.false_lit, metrics.false_lit_outside_edges, rendered_lit, band[i]);
        }
    }
    return metrics;
}

ContactMetrics contact_metrics(const VisibilityComparison& frame, std::span<const uint8_t> contact, uint32_t band_px) {
    ContactMetrics metrics;
    if (contact.empty()) return metrics;
    const std::vector<uint32_t> distance = chessboard_distance(frame.width, frame.height, contact);
    for (size_t i = 0; i < frame.evaluated.size(); ++i) {
        if (!frame.evaluated[i]) continue;
        metrics.contact_pixels += contact[i];
        if (distance[i] > band_px) continue;
        metrics.band_pixels += 1;
        const bool rendered_lit = frame.rendered[i] >= kShadowedBelow;
        ClassError& error = frame.hard[i] ? metrics.false_shadow : metrics.false_lit;
        error.truth_pixels += 1;
        error.wrong_pixels += frame.hard[i] ? !rendered_lit : rendered_lit;
    }
    return metrics;
}

namespace {

bool in_penumbra(float visibility) { return visibility > kPenumbraLow && visibility < kPenumbraHigh; }

}  // namespace

SoftShadowMetrics soft_shadow_metrics(const VisibilityComparison& frame, std::span<const uint8_t> boundary,
                                      std::span<const uint8_t> band) {
    SoftShadowMetrics metrics;
    std::vector<float> errors;
    double edge_error_sum = 0.0;
    uint64_t edge_pixels = 0;
    uint64_t boundary_pixels = 0;
    for (size_t i = 0; i < frame.evaluated.size(); ++i) {
        if (!frame.evaluated[i]) continue;
        const float error = std::abs(frame.rendered[i] - frame.soft[i]);
        errors.push_back(error);
        if (band[i]) {
            edge_error_sum += error;
            ++edge_pixels;
        }
        boundary_pixels += boundary[i];
        metrics.penumbra_pixels_render += in_penumbra(frame.rendered[i]);
        metrics.penumbra_pixels_reference += in_penumbra(frame.soft[i]);
    }
    if (errors.empty()) return metrics;
    double sum = 0.0;
    for (const float error : errors) sum += error;
    metrics.mean_abs_error = sum / static_cast<double>(errors.size());
    metrics.p95_abs_error = percentile(std::move(errors), 0.95);
    metrics.edge_mean_abs_error = edge_pixels ? edge_error_sum / static_cast<double>(edge_pixels) : 0.0;
    metrics.edge_length_px = static_cast<double>(boundary_pixels) / 2.0;
    if (metrics.edge_length_px > 0.0) {
        metrics.penumbra_width_render_px = static_cast<double>(metrics.penumbra_pixels_render) / metrics.edge_length_px;
        metrics.penumbra_width_reference_px =
            static_cast<double>(metrics.penumbra_pixels_reference) / metrics.edge_length_px;
        metrics.penumbra_width_error_px = metrics.penumbra_width_render_px - metrics.penumbra_width_reference_px;
    }
    return metrics;
}

namespace {

// The pixel of `frame` that shows `world`, if on screen.
std::optional<size_t> project_to_pixel(const StabilityFrame& frame, const StabilityGeometry& geometry,
                                       const glm::vec3& world) {
    const glm::vec4 clip = frame.view_projection * glm::vec4(world, 1.0f);
    if (clip.w <= 0.0f) return std::nullopt;
    // Vulkan clip space: x and y in [-1, 1], +y down the image (row 0 at the top).
    const float x = (clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(geometry.width);
    const float y = (clip.y / clip.w * 0.5f + 0.5f) * static_cast<float>(geometry.height);
    if (x < 0.0f || y < 0.0f || x >= static_cast<float>(geometry.width) || y >= static_cast<float>(geometry.height)) {
        return std::nullopt;
    }
    return static_cast<size_t>(y) * geometry.width + static_cast<size_t>(x);
}

// The change at pixel `pixel` of `frame` against the same surface point in `first`, or
// nullopt when they cannot be compared.
std::optional<float> change_against_first(const StabilityFrame& first, const StabilityFrame& frame,
                                          const StabilityGeometry& geometry, size_t pixel) {
    if (!frame.evaluated[pixel]) return std::nullopt;
    const glm::vec3 world(frame.positions[pixel]);
    const std::optional<size_t> matched = project_to_pixel(first, geometry, world);
    if (!matched || !first.evaluated[*matched] || first.hard[*matched] != frame.hard[pixel]) return std::nullopt;
    const float footprint = glm::length(world - first.eye) * geometry.pixel_angle;
    if (glm::length(glm::vec3(first.positions[*matched]) - world) > geometry.same_surface_pixels * footprint) {
        return std::nullopt;
    }
    return std::abs(frame.rendered[pixel] - first.rendered[*matched]);
}

// Mean, 99th percentile and maximum of per-pixel changes (not empty).
void summarize_changes(std::vector<float> changes, double& mean, double& p99, double& max) {
    double sum = 0.0;
    max = 0.0;
    for (const float change : changes) {
        sum += change;
        max = std::max(max, static_cast<double>(change));
    }
    mean = sum / static_cast<double>(changes.size());
    p99 = percentile(std::move(changes), 0.99);
}

}  // namespace

StabilityMetrics stability_metrics(std::span<const StabilityFrame> frames, const StabilityGeometry& geometry) {
    StabilityMetrics metrics;
    metrics.frames = static_cast<uint32_t>(frames.size());
    std::vector<float> changes;
    uint64_t flickering = 0;
    for (size_t k = 1; k < frames.size(); ++k) {
        for (size_t pixel = 0; pixel < frames[k].rendered.size(); ++pixel) {
            const std::optional<float> change = change_against_first(frames[0], frames[k], geometry, pixel);
            if (!change) continue;
            changes.push_back(*change);
            flickering += *change > 0.5f;
        }
    }
    metrics.compared_pixels = changes.size();
    if (changes.empty()) return metrics;
    metrics.flicker_percent = 100.0 * static_cast<double>(flickering) / static_cast<double>(changes.size());
    summarize_changes(std::move(changes), metrics.mean_change, metrics.p99_change, metrics.max_change);
    return metrics;
}

SamplingNoise sampling_noise(std::span<const float> first, std::span<const float> rotated,
                             std::span<const uint8_t> evaluated) {
    SamplingNoise noise;
    std::vector<float> changes;
    for (size_t pixel = 0; pixel < first.size() && pixel < rotated.size() && pixel < evaluated.size(); ++pixel) {
        if (evaluated[pixel]) changes.push_back(std::abs(first[pixel] - rotated[pixel]));
    }
    noise.compared_pixels = changes.size();
    if (!changes.empty()) summarize_changes(std::move(changes), noise.mean_change, noise.p99_change, noise.max_change);
    return noise;
}

}  // namespace penumbra::quality
