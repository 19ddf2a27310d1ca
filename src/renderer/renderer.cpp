#include "renderer/renderer.hpp"

#include <array>
#include <cstring>

#include "gpu/barriers.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "passes/lighting_pass.hpp"
#include "passes/shadow_pass.hpp"
#include "renderer/gpu_scene.hpp"

namespace penumbra::renderer {
namespace {

struct Readback {
    gpu::Buffer color;
    gpu::Buffer visibility;
    gpu::Buffer cascade;
    gpu::Buffer shadow_map;  // only with DebugView::ShadowMap
};

gpu::Buffer create_readback_buffer(const gpu::Context& context, VkDeviceSize bytes) {
    return gpu::create_buffer(context, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryKind::HostReadback);
}

Readback create_readback(const gpu::Context& context, const RenderSettings& settings) {
    const VkDeviceSize pixels = VkDeviceSize{settings.width} * settings.height;
    Readback readback{create_readback_buffer(context, pixels * 4),
                      create_readback_buffer(context, pixels * 2),
                      create_readback_buffer(context, pixels),
                      {}};
    if (settings.debug == DebugView::ShadowMap) {
        const VkDeviceSize texels = VkDeviceSize{settings.shadow.cascades.resolution} *
                                    settings.shadow.cascades.resolution * settings.shadow.cascades.count;
        readback.shadow_map = create_readback_buffer(context, texels * sizeof(float));
    }
    return readback;
}

// Copies every layer of `image` (tightly packed, layer after layer) into `buffer`.
void copy_image_to_buffer(VkCommandBuffer cmd, const gpu::Image& image, const gpu::Buffer& buffer) {
    VkBufferImageCopy region{};
    region.imageSubresource = {image.desc.aspect, 0, 0, image.desc.layers};
    region.imageExtent = {image.desc.width, image.desc.height, 1};
    vkCmdCopyImageToBuffer(cmd, image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.get(), 1, &region);
}

template <typename T>
std::vector<T> read_buffer(const gpu::Buffer& buffer, size_t count) {
    std::vector<T> values(count);
    std::memcpy(values.data(), buffer.mapped, count * sizeof(T));
    return values;
}

}  // namespace

struct Renderer::Resources {
    GpuScene gpu_scene;
    passes::ShadowPass shadow_pass;
    passes::LightingPass lighting_pass;
    gpu::Buffer frame_uniforms;
    gpu::UniqueSampler shadow_sampler;
    gpu::UniqueDescriptorPool descriptor_pool;
    VkDescriptorSet shadow_frame_set = VK_NULL_HANDLE;
    VkDescriptorSet lighting_frame_set = VK_NULL_HANDLE;
    Readback readback;

    Resources(const gpu::Context& context, const Scene& scene, const RenderSettings& settings)
        : gpu_scene(context, scene),
          shadow_pass(context, gpu_scene.draw_data().material_set_layout, settings.shadow.cascades.resolution,
                      static_cast<uint32_t>(settings.shadow.cascades.count)),
          lighting_pass(context, gpu_scene.draw_data().material_set_layout, settings.width, settings.height),
          frame_uniforms(gpu::create_buffer(context, sizeof(shader::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                            gpu::MemoryKind::HostUpload)),
          readback(create_readback(context, settings)) {
        // Hardware depth comparison with bilinear filtering. Clamp-to-edge rather than a
        // border: the shader already treats lookups outside the map as lit, and lavapipe
        // (Mesa 22.3) returns the border colour for in-range taps of linear-compare array
        // lookups, which halves the visibility of every pixel.
        gpu::SamplerDesc sampler;
        sampler.filter = VK_FILTER_LINEAR;
        sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        sampler.compare = true;
        sampler.compare_op = VK_COMPARE_OP_GREATER_OR_EQUAL;
        shadow_sampler = gpu::create_sampler(context, sampler);

        const std::array<VkDescriptorPoolSize, 2> sizes{
            {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2}, {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}}};
        descriptor_pool = gpu::create_descriptor_pool(context, 2, sizes);
        shadow_frame_set = gpu::allocate_descriptor_set(context, descriptor_pool, shadow_pass.frame_set_layout());
        lighting_frame_set = gpu::allocate_descriptor_set(context, descriptor_pool, lighting_pass.frame_set_layout());
        for (VkDescriptorSet set : {shadow_frame_set, lighting_frame_set}) {
            gpu::write_uniform_buffer(context, set, PENUMBRA_BINDING_FRAME_UNIFORMS, frame_uniforms.get(),
                                      sizeof(shader::FrameUniforms));
        }
        gpu::write_combined_image_sampler(context, lighting_frame_set, PENUMBRA_BINDING_SHADOW_MAP,
                                          shadow_pass.shadow_map().view, shadow_sampler);
    }
};

Renderer::Renderer(const gpu::Context& context, const Scene& scene, const RenderSettings& settings)
    : context_(context),
      scene_(scene),
      settings_(settings),
      resources_(std::make_unique<Resources>(context, scene, settings)) {}

Renderer::~Renderer() {
    // Nothing may be destroyed while the GPU still uses it.
    if (context_.device()) vkDeviceWaitIdle(context_.device());
}

FrameImages Renderer::render(const Camera& camera) {
    const float aspect = static_cast<float>(settings_.width) / static_cast<float>(settings_.height);
    const CameraView view = make_camera_view(camera, aspect);
    last_frame_.cascades =
        compute_cascades(view, sun_travel_direction(scene_), settings_.shadow.cascades, scene_.world_bounds());
    const passes::DrawData& draw_data = resources_->gpu_scene.draw_data();
    CulledCasters casters = cull_casters(last_frame_.cascades, draw_data, settings_.shadow.cull_casters);
    last_frame_.cascade_stats = casters.stats;

    const shader::FrameUniforms uniforms = build_frame_uniforms(view, scene_, last_frame_.cascades, settings_);
    std::memcpy(resources_->frame_uniforms.mapped, &uniforms, sizeof(uniforms));

    const passes::LightingTargets& targets = resources_->lighting_pass.targets();
    context_.submit_and_wait([&](VkCommandBuffer cmd) {
        resources_->shadow_pass.record(cmd, resources_->shadow_frame_set, draw_data, casters.lists,
                                       settings_.shadow.bias, settings_.shadow.strategy);
        resources_->lighting_pass.record(cmd, resources_->lighting_frame_set, draw_data);
        copy_image_to_buffer(cmd, targets.color, resources_->readback.color);
        copy_image_to_buffer(cmd, targets.visibility, resources_->readback.visibility);
        copy_image_to_buffer(cmd, targets.cascade, resources_->readback.cascade);
        if (settings_.debug == DebugView::ShadowMap) {
            const gpu::Image& shadow_map = resources_->shadow_pass.shadow_map();
            gpu::transition(cmd, shadow_map, gpu::ImageState::FragmentSampled, gpu::ImageState::TransferSrc);
            copy_image_to_buffer(cmd, shadow_map, resources_->readback.shadow_map);
        }
        gpu::transfer_to_host_barrier(cmd);
    });

    FrameImages images;
    images.width = settings_.width;
    images.height = settings_.height;
    const size_t pixels = size_t{settings_.width} * settings_.height;
    images.color_rgba8 = read_buffer<uint8_t>(resources_->readback.color, pixels * 4);
    images.visibility = read_buffer<uint16_t>(resources_->readback.visibility, pixels);
    images.cascade = read_buffer<uint8_t>(resources_->readback.cascade, pixels);
    if (settings_.debug == DebugView::ShadowMap) {
        images.shadow_map_resolution = settings_.shadow.cascades.resolution;
        images.shadow_map_layers = static_cast<uint32_t>(settings_.shadow.cascades.count);
        images.shadow_map =
            read_buffer<float>(resources_->readback.shadow_map, resources_->readback.shadow_map.size / sizeof(float));
    }
    return images;
}

}  // namespace penumbra::renderer
