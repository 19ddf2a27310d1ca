#pragma once
// A penumbra::Scene uploaded to the GPU: one vertex and one index buffer for every
// mesh, a texture per scene texture (plus a white fallback), a descriptor set per
// material, and the draw list the passes consume.
#include <vector>

#include "core/scene.hpp"
#include "gpu/context.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "passes/draw_data.hpp"

namespace penumbra::renderer {

class GpuScene {
public:
    GpuScene(const gpu::Context& context, const Scene& scene);

    const passes::DrawData& draw_data() const { return draw_data_; }

private:
    void upload_geometry(const gpu::Context& context, const Scene& scene);
    void create_materials(const gpu::Context& context, const Scene& scene);

    gpu::Buffer vertices_;
    gpu::Buffer indices_;
    std::vector<gpu::Image> textures_;  // scene textures, then the white fallback last
    gpu::UniqueSampler texture_sampler_;
    gpu::UniqueDescriptorSetLayout material_set_layout_;
    gpu::UniqueDescriptorPool descriptor_pool_;
    passes::DrawData draw_data_;
};

}  // namespace penumbra::renderer
