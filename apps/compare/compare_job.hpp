#pragma once
// The library entry point behind `penumbra compare` (docs/QUALITY.md): render a scene's
// sun visibility together with each pixel's world position and normal, trace the same
// pixels' shadow rays against an Embree BVH of the scene (one ray to the sun's centre for
// the hard reference, `rays` over its disk for the soft one), and measure the difference:
// false shadow / false lit (hard), visibility error and penumbra width (soft), and the
// shimmer of K frames under small camera motions (temporal stability).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/scene/render_settings.hpp"
#include "quality/shadow_metrics.hpp"
#include "renderer/render_job.hpp"

namespace penumbra::compare {

constexpr uint32_t kMaxRays = 4096;
constexpr uint32_t kMaxStabilityFrames = 64;
constexpr uint32_t kMaxEdgeBand = 64;
// The contact metrics (quality::ContactMetrics, sun only): a shadowed pixel is beside a
// contact when its occluder lies within kContactReachMetres along the ray to the sun (the
// scale that shadow maps' biases and texels lose and Settings::contact's default length),
// and the band counts the pixels within kContactBandPixels of one.
constexpr float kContactReachMetres = 0.25f;
constexpr uint32_t kContactBandPixels = 4;

// A spot light's pixels count where its cone factor exceeds this: the render's shadow term
// is the AOV divided by the cone (docs/QUALITY.md), which the faintest rim would amplify.
constexpr float kMinConeFactor = 0.05f;

struct CompareJob {
    RenderJob render;               // scene, config, overrides, device, validation; output and aov unused
    uint32_t rays = 64;             // soft reference rays per pixel, 1..kMaxRays
    int32_t light = -1;             // --light N: index into the scene's [[lights]]; -1 = the sun
    uint32_t edge_band = 2;         // pixels around true shadow edges left out of the *_outside_edges numbers
    uint32_t stability_frames = 8;  // frames under camera motion (1 = no stability measurement)
    std::filesystem::path out_dir = "compare";
    std::optional<std::filesystem::path> json;  // default: out_dir / "compare.json"
    // Optional: called while the reference of frame `frame` (0-based, of `frames`) is traced,
    // with its rows traced so far; on the calling thread.
    std::function<void(uint32_t frame, uint32_t frames, uint32_t rows_done, uint32_t rows)> progress;
};

struct PixelCounts {
    uint64_t total = 0;
    uint64_t geometry = 0;
    uint64_t facing_away = 0;             // geometry with N.L <= 0 (L toward the sun or the light point)
    uint64_t beyond_shadow_distance = 0;  // facing the sun, but no cascade covers it
    uint64_t outside_light = 0;  // spot/point: facing it, but beyond its range or cone (cone <= kMinConeFactor)
    uint64_t not_receiving = 0;  // geometry of instances with receive_shadows = false
    uint64_t evaluated = 0;      // what the metrics count
    uint64_t shadowed = 0;       // evaluated pixels the hard reference puts in shadow
    double shadowed_percent() const { return evaluated ? 100.0 * static_cast<double>(shadowed) / evaluated : 0.0; }
};

// Above this share of evaluated pixels in shadow, compare warns: something (a sky box, a
// dome, a ceiling) most likely blocks the light from the whole view.
inline constexpr double kMostlyShadowedPercent = 95.0;

struct CompareTimings {
    double render_ms = 0.0;  // every frame, readback included
    double bvh_ms = 0.0;
    double trace_ms = 0.0;  // the references of every frame
};

// Frame 0's images, kept for the output files.
struct CompareImages {
    quality::VisibilityComparison frame;    // rendered, hard, soft, evaluated
    std::vector<uint8_t> color_rgba8;       // the render's colour image
    std::vector<glm::vec4> world_position;  // the geometry AOV (w = 1 where geometry)
};

struct CompareResult {
    std::string version;
    std::string device_name;
    std::string scene;
    RenderSettings settings;
    CompareJob job;
    int32_t light_index = -1;          // the compared light in the scene's [[lights]]
    std::optional<Light> local_light;  // set when it is a spot or point light (not the sun)
    std::string stability_note;        // why stability was not measured (spot/point lights), or empty
    glm::vec3 to_sun{0.0f};
    float sun_angular_diameter_degrees = 0.0f;
    uint64_t triangles = 0;                 // traced (every instance)
    float nearest_texel_world_size = 0.0f;  // cascade 0 under the stable fit: the unit of the camera motions
    PixelCounts pixels;
    quality::HardShadowMetrics hard;
    quality::ContactMetrics contact;  // sun only (zero for a spot or point light)
    quality::SoftShadowMetrics soft;
    quality::StabilityMetrics stability;
    quality::SamplingNoise sampling_noise;  // frame 0 rendered again with its pattern rotated
    CompareTimings timings;
    CompareImages images;
};

// Throws InputError (bad job, a scene without a directional light for the sun, or a
// --light that is out of range or casts no rendered shadow), DeviceError or
// ValidationFailure. Writes nothing.
CompareResult run_compare_job(const CompareJob& job);

// The same for a scene and settings already merged (job.render supplies only the device
// options); `scene_name` names the scene in messages and the report.
CompareResult compare_prepared(const CompareJob& job, PreparedJob prepared, const std::string& scene_name);

// Throws InputError for out-of-range job values (checked before anything is rendered).
void validate_compare_job(const CompareJob& job);

}  // namespace penumbra::compare
