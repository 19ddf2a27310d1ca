#pragma once
// What the renderer's own shaders read each frame (shaders/include/renderer_shared.h): the
// camera, the sun's light, ambient, the debug view and the spot and point lights it shades;
// and the lights as the ShadowSystem takes them.
#include <vector>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/handle.hpp"
#include "penumbra/lights.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/scene.hpp"
#include "penumbra/shadow_system.hpp"
#include "renderer/shader_interface.hpp"

namespace penumbra::renderer {

// Set 0 of the camera passes: binding 0 the FrameUniforms, 1 the LocalLights.
gpu::UniqueDescriptorSetLayout create_frame_set_layout(const gpu::Device& device);

shader::FrameUniforms build_frame_uniforms(const ViewDesc& view, const Scene& scene, const RenderSettings& settings);

// The lit spot and point lights (lit_local_lights()); each names its index in the
// ShadowSystem's light list, which is the scene's, and its slot in the deferred visibility
// image (from this frame's `local_shadows`; 0 without a shadow map).
shader::LocalLights build_local_lights(const std::vector<Light>& lights,
                                       const std::vector<LocalShadowInfo>& local_shadows);

// The scene's lights for ShadowSystem::set_lights(), in the same order (so that indices
// agree); lights past the lit ones cast no shadow, as nothing lights them.
std::vector<LightDesc> shadow_lights(const std::vector<Light>& lights);

}  // namespace penumbra::renderer
