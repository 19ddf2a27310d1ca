#pragma once
// Renders frames of a scene headlessly: orders the shadow and lighting passes, owns
// the frame's uniform buffer and descriptor sets, and reads the results back.
//
//   Renderer renderer(context, scene, settings);
//   FrameImages images = renderer.render(scene.camera);
#include <cstdint>
#include <memory>
#include <vector>

#include "core/cascades.hpp"
#include "core/render_settings.hpp"
#include "core/scene.hpp"
#include "gpu/context.hpp"
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
};

struct FrameInfo {
    CascadeSet cascades;
    std::vector<CascadeStats> cascade_stats;
};

class Renderer {
public:
    Renderer(const gpu::Context& context, const Scene& scene, const RenderSettings& settings);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Renders one frame from `camera` and returns its images once the GPU is done.
    FrameImages render(const Camera& camera);
    const FrameInfo& last_frame() const { return last_frame_; }

private:
    struct Resources;
    const gpu::Context& context_;
    const Scene& scene_;
    RenderSettings settings_;
    std::unique_ptr<Resources> resources_;
    FrameInfo last_frame_;
};

}  // namespace penumbra::renderer
