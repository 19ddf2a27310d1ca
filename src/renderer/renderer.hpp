#pragma once
// Renders frames of a scene headlessly: orders the shadow and lighting passes, owns
// the frame's uniform buffer and descriptor sets, and reads the results back.
//
//   Renderer renderer(context, scene, settings);
//   FrameImages images = renderer.render(scene.camera);
//
// Pipelines, descriptor sets, the command buffer and the fence are created once and
// reused by every frame. The scene's lights are read each frame, so a caller that owns
// the Scene may move the sun between frames (the benchmark's light paths do).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/cascades.hpp"
#include "core/render_settings.hpp"
#include "core/scene.hpp"
#include "gpu/context.hpp"
#include "gpu/timestamps.hpp"
#include "renderer/frame_setup.hpp"

namespace penumbra::renderer {

struct FrameImages {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> color_rgba8;  // sRGB, row 0 at the top
    std::vector<uint16_t> visibility;  // sun visibility, 65535 = fully lit
    std::vector<uint8_t> cascade;      // cascade index, 255 = none
    // With DebugView::ShadowMap: the reverse-Z depth of every layer, layer after layer.
    std::vector<float> shadow_map;
    uint32_t shadow_map_resolution = 0;
    uint32_t shadow_map_layers = 0;
    // With RenderSettings::geometry_aovs: per pixel, the world position (w = 1 where
    // geometry, 0 none) and the shading normal the shadow lookup used.
    std::vector<glm::vec4> world_position;
    std::vector<glm::vec4> world_normal;
};

enum class ReadbackMode {
    Images,  // read the colour, visibility and cascade images back (and the shadow map with DebugView::ShadowMap)
    None,    // render only (benchmarks): FrameImages comes back empty
};

// CPU time of the frame's steps, in milliseconds.
struct CpuTimes {
    double cascade_setup_ms = 0.0;  // cascade splits and fitting, frame uniforms
    double culling_ms = 0.0;        // per-cascade caster culling
    double recording_ms = 0.0;      // command recording
    double submit_wait_ms = 0.0;    // from submission until the fence signals
};

// One shadowed spot or point light of the frame (docs/local-lights.md).
struct LocalShadowStats {
    uint32_t light = 0;       // index into Scene::lights
    uint32_t layers = 0;      // 1 for a spot, 6 for a cube (point lights, spots wider than 60 degrees)
    uint32_t resolution = 0;  // texels per side of each of its layers
    float near_plane = 0.0f;  // metres (the nearest caster)
    uint32_t draws = 0;       // submitted over all its layers, after culling
    uint64_t triangles = 0;
};

struct FrameInfo {
    CascadeSet cascades;
    std::vector<CascadeStats> cascade_stats;
    std::vector<LocalShadowStats> local_shadow_stats;  // shadowed local lights, in light order
    // GPU time of each timed scope, in recording order: "frame", then "shadow_cascade_<i>"
    // (or "shadow_multiview", or "shadow_moments" for the moment filters), "shadow_local"
    // (only with shadowed spot/point lights) and "lighting".
    // Empty when the queue has no timestamps.
    std::vector<gpu::ScopeTime> gpu_times;
    CpuTimes cpu_times;
};

class Renderer;

// True when going from `current` to `next` changes a resource the Renderer creates once:
// the image size, the cascade count or resolution, the filter (pipelines and moments
// maps), the shadow strategy, or the shadow-map debug readback.
bool requires_new_renderer(const RenderSettings& current, const RenderSettings& next);

class Renderer {
public:
    Renderer(const gpu::Context& context, const Scene& scene, const RenderSettings& settings);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Renders one frame from `camera` and returns its images once the GPU is done
    // (no images with ReadbackMode::None).
    FrameImages render(const Camera& camera, ReadbackMode readback = ReadbackMode::Images);
    const FrameInfo& last_frame() const { return last_frame_; }
    const RenderSettings& settings() const { return settings_; }
    // The last frame's tone-mapped colour target (R8G8B8A8_SRGB, settings().width x
    // height), left in gpu::ImageState::TransferSrc by render(); a presenter copies or
    // blits it (the window viewer) after render() has returned.
    const gpu::Image& color_target() const;
    // Replaces the settings read while recording a frame (splits, fitting, bias, blend
    // width, culling, the cascade debug tint). Settings that size or specialise resources
    // need a new Renderer: see requires_new_renderer(); throws std::invalid_argument then.
    void update_settings(const RenderSettings& settings);
    const gpu::GpuTimer& gpu_timer() const;
    // GPU memory of the shadow map(s), in bytes.
    uint64_t shadow_map_bytes() const;
    // Fits the cascades to `camera` instead of the rendered camera from the next frame on
    // (nullopt: the rendered camera again). `penumbra compare` uses it to measure shimmer:
    // the image stays put while the cascades follow a moving camera.
    void fit_cascades_to(const std::optional<Camera>& camera) { cascade_camera_ = camera; }

private:
    CulledCasters prepare_frame(const Camera& camera);
    void record_frame(VkCommandBuffer cmd, const CulledCasters& casters, ReadbackMode readback);
    FrameImages read_images() const;

    struct Resources;
    const gpu::Context& context_;
    const Scene& scene_;
    RenderSettings settings_;
    std::unique_ptr<Resources> resources_;
    FrameInfo last_frame_;
    uint32_t frame_index_ = 0;              // rotates the shadow filters' sampling patterns per frame
    std::optional<Camera> cascade_camera_;  // fit_cascades_to()
};

}  // namespace penumbra::renderer
