#pragma once
// The penumbra tools' renderer: renders frames of a Scene headlessly with a lighting pass
// of its own and Penumbra's ShadowSystem for every shadow, as any renderer that adopts the
// library would (docs/library.md). It uploads the scene into its own buffers, gives the
// ShadowSystem those buffers, the instances and the lights, and per frame calls prepare(),
// records the shadow maps and its lighting (forward; or deferred: a depth and normal
// pre-pass, the ShadowSystem's compute resolve, lighting over the pre-pass's depth; see
// RenderSettings::resolve) into one command buffer, submits it, waits and reads the
// results back.
//
//   Renderer renderer(context, scene, settings);
//   FrameImages images = renderer.render(scene.camera);
//
// The scene's lights are read each frame, so a caller that owns the Scene may move the
// sun between frames (the benchmark's light paths do).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/gpu/resources.hpp"
#include "penumbra/gpu/timestamps.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/scene.hpp"
#include "penumbra/shadow_system.hpp"
#include "renderer/app_context.hpp"

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
    // Per layer, the layer texel of the cascade's texel (0, 0) (CascadeInfo::layer_origin_x/y:
    // per-cascade passes wrap each cascade around its layer).
    std::vector<glm::uvec2> shadow_map_layer_origins;
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
    double cascade_setup_ms = 0.0;  // ShadowSystem::prepare(): fitting of cascades and local lights
    double culling_ms = 0.0;        // ShadowSystem::prepare(): caster culling of every map
    double settings_ms = 0.0;       // ShadowSystem::prepare(): applying changed settings
    double recording_ms = 0.0;      // command recording
    double submit_wait_ms = 0.0;    // from submission until the fence signals
};

struct FrameInfo {
    std::vector<CascadeInfo> cascades;             // the sun's (0 draws when it casts no shadow)
    std::optional<VirtualShadowInfo> virtual_map;  // the sun's virtual shadow map (technique virtual)
    float shadow_distance = 0.0f;                  // where the last cascade ends
    std::vector<LocalShadowInfo> local_shadows;    // shadowed local lights, in light order
    std::vector<uint32_t> unshadowed_lights;       // shadow-casting local lights beyond the budget
    // GPU time of each timed scope, in recording order: "frame", then "shadow_cascade_<i>"
    // (or "shadow_multiview", or "shadow_moments" for the moment filters), "shadow_local"
    // (only with shadowed spot/point lights), "visibility" (the compute resolve, deferred
    // only), then the renderer's "prepass" (deferred only; recorded before "visibility") and
    // "lighting". Empty without timestamps.
    std::vector<gpu::ScopeTime> gpu_times;
    CpuTimes cpu_times;
};

// The first kMaxLocalLights spot and point lights of `lights` (indices): the ones lit.
std::vector<uint32_t> lit_local_lights(const std::vector<Light>& lights);

class Renderer {
public:
    Renderer(const AppContext& context, const Scene& scene, const RenderSettings& settings);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Renders one frame from `camera` and returns its images once the GPU is done
    // (no images with ReadbackMode::None).
    FrameImages render(const Camera& camera, ReadbackMode readback = ReadbackMode::Images);
    const FrameInfo& last_frame() const { return last_frame_; }
    const RenderSettings& settings() const { return settings_; }
    // Moves scene instance `instance` (an index into Scene::instances) to `world` from the
    // next frame on: its draw and its shadow caster (flag it dynamic for cached cascades).
    void move_instance(size_t instance, const glm::mat4& world);
    // The path this renderer resolves shadows with: RenderSettings::resolve made effective
    // (effective_resolve()), Forward or Deferred.
    ShadowResolve resolve() const;
    // The last frame's tone-mapped colour target (R8G8B8A8_SRGB, settings().width x
    // height), left in gpu::ImageState::TransferSrc by render(); a presenter copies or
    // blits it (the window viewer) after render() has returned.
    const gpu::Image& color_target() const;
    // Takes new settings for the next frame, the scene kept: every shadow setting (the
    // ShadowSystem rebuilds its maps or pipelines, the lighting pass its pipelines when the
    // filter's specialization changed). What changes the renderer's own targets (the image
    // size, the resolve path, the pre-pass, contact shadows, the shadow-map readback) needs
    // a new Renderer: see needs_new_renderer(); throws std::invalid_argument then.
    void update_settings(const RenderSettings& settings);
    bool needs_new_renderer(const RenderSettings& next) const;
    const gpu::GpuTimer& gpu_timer() const;
    // GPU memory of the shadow maps, in bytes.
    uint64_t shadow_map_bytes() const;
    // Fits the shadows to `camera` instead of the rendered camera from the next frame on
    // (nullopt: the rendered camera again). `penumbra compare` uses it to measure shimmer:
    // the image stays put while the cascades follow a moving camera.
    void fit_cascades_to(const std::optional<Camera>& camera) { cascade_camera_ = camera; }
    // Fixes the Poisson/PCSS sampling rotation (ViewDesc::sampling_frame); nullopt: a new
    // rotation every frame, as by default.
    void fix_sampling_pattern(std::optional<uint32_t> sampling_frame) { sampling_frame_ = sampling_frame; }
    // The one-line warning for shadow-casting lights left unshadowed or unlit; empty when none.
    std::string light_warning() const;
    // The one-line warning for shadow casters that enclose the camera and the scene and
    // shadow what it sees (quality::find_enclosing_casters()); empty when none.
    std::string enclosure_warning(const Camera& camera) const;

private:
    void prepare_frame(const Camera& camera);
    void record_frame(VkCommandBuffer cmd, ReadbackMode readback);
    FrameImages read_images() const;

    struct Resources;
    const AppContext& context_;
    const Scene& scene_;
    RenderSettings settings_;
    std::unique_ptr<Resources> resources_;
    FrameInfo last_frame_;
    uint64_t shadow_frame_ = 0;                    // the ShadowSystem's FrameInfo of the frame being rendered:
    VkDescriptorSet shadow_set_ = VK_NULL_HANDLE;  // its number and descriptor set
    std::optional<Camera> cascade_camera_;         // fit_cascades_to()
    std::optional<uint32_t> sampling_frame_;       // fix_sampling_pattern()
};

}  // namespace penumbra::renderer
