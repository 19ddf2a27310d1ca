#pragma once
// Everything the renderer owns for spot and point light shadows (docs/local-lights.md):
// the plan of which lights are shadowed (fixed at construction), the local shadow pass,
// the moments pass for the moment filters, the local-light uniform block, and this
// frame's culled casters per layer. The Renderer calls prepare() each frame, then record().
#include <optional>
#include <string>
#include <vector>

#include "core/local_lights.hpp"
#include "core/render_settings.hpp"
#include "core/scene.hpp"
#include "gpu/context.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "gpu/timestamps.hpp"
#include "passes/draw_data.hpp"
#include "passes/local_moments_pass.hpp"
#include "passes/local_shadow_pass.hpp"
#include "renderer/renderer.hpp"

namespace penumbra::renderer {

class LocalShadowResources {
public:
    LocalShadowResources(const gpu::Context& context, const Scene& scene, const RenderSettings& settings,
                         VkDescriptorSetLayout material_set_layout);

    // The lighting set's local bindings: the uniform block, the comparison map (with
    // `comparison_sampler`), the raw depth and the moments (or the raw depth again).
    void write_lighting_bindings(VkDescriptorSet lighting_set, VkSampler comparison_sampler) const;

    // Fits the lights' shadow matrices to the scene's current lights, sizes their maps by
    // their coverage of `camera`'s view (coverage sizing), fills the uniform block and culls
    // the casters of every layer; returns the per-light statistics.
    std::vector<LocalShadowStats> prepare(const Scene& scene, const passes::DrawData& data,
                                          const RenderSettings& settings, const CameraView& camera);

    // The local shadow pass (and the moments pass) for the prepared frame, timed as
    // "shadow_local"; without shadowed lights only the placeholder's layout transition.
    void record(VkCommandBuffer cmd, const passes::DrawData& data, const RenderSettings& settings,
                gpu::GpuTimer* timer) const;

    // GPU memory of the local shadow map and its moments (0 without shadowed local lights).
    uint64_t memory_bytes() const;

    // The one-line warning for lights beyond the budget or the light limit; empty when none.
    std::string budget_warning(const LocalShadowSettings& settings) const;

private:
    const gpu::Context& context_;
    LocalShadowPlan plan_;
    passes::LocalShadowPass shadow_pass_;
    gpu::Buffer uniforms_;
    gpu::UniqueSampler depth_sampler_;  // raw depth: PCSS blocker search, moments conversion
    gpu::UniqueDescriptorPool pool_;
    VkDescriptorSet shadow_set_ = VK_NULL_HANDLE;
    std::optional<passes::LocalMomentsPass> moments_pass_;  // moment filters with shadowed lights only
    std::vector<passes::LocalShadowLayer> layers_;          // this frame's culled casters per layer
};

}  // namespace penumbra::renderer
