#include "renderer/renderer.hpp"

#include <array>
#include <chrono>
#include <cstring>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "gpu/barriers.hpp"
#include "gpu/frame_commands.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "passes/geometry_aov_pass.hpp"
#include "passes/lighting_pass.hpp"
#include "passes/shadow_pass.hpp"
#include "renderer/gpu_scene.hpp"
#include "renderer/local_shadow_resources.hpp"
#include "renderer/shadow_filter_resources.hpp"

namespace penumbra::renderer {
namespace {

struct Readback {
    gpu::Buffer color;
    gpu::Buffer visibility;
    gpu::Buffer cascade;
    gpu::Buffer shadow_map;      // only with DebugView::ShadowMap
    gpu::Buffer world_position;  // only with RenderSettings::geometry_aovs
    gpu::Buffer world_normal;
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
    if (settings.geometry_aovs) {
        readback.world_position = create_readback_buffer(context, pixels * sizeof(glm::vec4));
        readback.world_normal = create_readback_buffer(context, pixels * sizeof(glm::vec4));
    }
    return readback;
}

// Copies every layer of `image` (tightly packed, layer after layer) into `buffer`.
void copy_image_to_buffer(const gpu::Device& device, VkCommandBuffer cmd, const gpu::Image& image,
                          const gpu::Buffer& buffer) {
    VkBufferImageCopy region{};
    region.imageSubresource = {image.desc.aspect, 0, 0, image.desc.layers};
    region.imageExtent = {image.desc.width, image.desc.height, 1};
    device->vkCmdCopyImageToBuffer(cmd, image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.get(), 1, &region);
}

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Scopes a frame can open: the frame, one per cascade, lighting and room for more passes.
constexpr uint32_t kMaxTimedScopes = 32;

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
    ShadowFilterResources filters;  // raw-depth sampler, moments pass (moment filters)
    gpu::UniqueDescriptorPool descriptor_pool;
    VkDescriptorSet shadow_frame_set = VK_NULL_HANDLE;
    VkDescriptorSet lighting_frame_set = VK_NULL_HANDLE;
    Readback readback;
    std::optional<passes::GeometryAovPass> geometry_aovs;  // only with RenderSettings::geometry_aovs
    gpu::FrameCommands commands;
    gpu::GpuTimer timer;
    // Spot and point lights (docs/local-lights.md): which lights are shadowed is fixed at
    // construction; their matrices follow the scene's lights every frame.
    LocalShadowResources local_shadows;

    Resources(const gpu::Context& context, const Scene& scene, const RenderSettings& settings)
        : gpu_scene(context, scene),
          shadow_pass(context, gpu_scene.draw_data().material_set_layout, settings.shadow.cascades.resolution,
                      static_cast<uint32_t>(settings.shadow.cascades.count), settings.shadow.strategy),
          lighting_pass(context, gpu_scene.draw_data().material_set_layout, settings.width, settings.height,
                        settings.shadow.filter),
          frame_uniforms(gpu::create_buffer(context, sizeof(shader::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                            gpu::MemoryKind::HostUpload)),
          filters(context, gpu_scene.draw_data().material_set_layout, settings, frame_uniforms.get(),
                  sizeof(shader::FrameUniforms)),
          readback(create_readback(context, settings)),
          commands(context),
          timer(context, kMaxTimedScopes),
          local_shadows(context, scene, settings, gpu_scene.draw_data().material_set_layout) {
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

        const std::array<VkDescriptorPoolSize, 3> sizes{{{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2},
                                                         {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
                                                         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 6}}};
        descriptor_pool = gpu::create_descriptor_pool(context, 2, sizes);
        shadow_frame_set = gpu::allocate_descriptor_set(context, descriptor_pool, shadow_pass.frame_set_layout());
        lighting_frame_set = gpu::allocate_descriptor_set(context, descriptor_pool, lighting_pass.frame_set_layout());
        for (VkDescriptorSet set : {shadow_frame_set, lighting_frame_set}) {
            gpu::write_uniform_buffer(context, set, PENUMBRA_BINDING_FRAME_UNIFORMS, frame_uniforms.get(),
                                      sizeof(shader::FrameUniforms));
        }
        filters.write_lighting_bindings(lighting_frame_set, shadow_pass.shadow_map(), shadow_sampler);
        local_shadows.write_lighting_bindings(lighting_frame_set, shadow_sampler);
        if (settings.geometry_aovs) {
            geometry_aovs.emplace(context, gpu_scene.draw_data().material_set_layout, settings.width, settings.height,
                                  frame_uniforms.get(), sizeof(shader::FrameUniforms));
        }
    }
};

Renderer::Renderer(const gpu::Context& context, const Scene& scene, const RenderSettings& settings)
    : context_(context),
      scene_(scene),
      settings_(settings),
      resources_(std::make_unique<Resources>(context, scene, settings)) {
    const std::string warning = resources_->local_shadows.budget_warning(settings.local_shadows);
    if (!warning.empty()) std::cerr << warning << std::endl;
}

Renderer::~Renderer() {
    // Nothing may be destroyed while the GPU still uses it.
    if (context_.device()) context_->vkDeviceWaitIdle(context_);
}

const gpu::GpuTimer& Renderer::gpu_timer() const { return resources_->timer; }

const gpu::Image& Renderer::color_target() const { return resources_->lighting_pass.targets().color; }

bool requires_new_renderer(const RenderSettings& current, const RenderSettings& next) {
    const auto is_shadow_map = [](DebugView view) { return view == DebugView::ShadowMap; };
    return current.width != next.width || current.height != next.height ||
           requires_recreation({current.shadow, current.local_shadows}, {next.shadow, next.local_shadows}) ||
           is_shadow_map(current.debug) != is_shadow_map(next.debug);
}

void Renderer::update_settings(const RenderSettings& settings) {
    if (requires_new_renderer(settings_, settings)) {
        throw std::invalid_argument("Renderer::update_settings: the new settings need a new Renderer");
    }
    settings_ = settings;
}

uint64_t Renderer::shadow_map_bytes() const {
    return resources_->shadow_pass.shadow_map().memory_size + resources_->filters.memory_bytes() +
           resources_->local_shadows.memory_bytes();
}

FrameImages Renderer::render(const Camera& camera, ReadbackMode readback) {
    const CulledCasters casters = prepare_frame(camera);
    const Clock::time_point submit_start = Clock::now();
    resources_->commands.submit_and_wait([&](VkCommandBuffer cmd) {
        const Clock::time_point record_start = Clock::now();
        record_frame(cmd, casters, readback);
        last_frame_.cpu_times.recording_ms = milliseconds_since(record_start);
    });
    last_frame_.cpu_times.submit_wait_ms = milliseconds_since(submit_start) - last_frame_.cpu_times.recording_ms;
    // The fence has signalled, so every timestamp is available; nullopt only without support.
    last_frame_.gpu_times = resources_->timer.read().value_or(std::vector<gpu::ScopeTime>{});
    return readback == ReadbackMode::Images ? read_images() : FrameImages{};
}

CulledCasters Renderer::prepare_frame(const Camera& camera) {
    Clock::time_point start = Clock::now();
    const float aspect = static_cast<float>(settings_.width) / static_cast<float>(settings_.height);
    const CameraView view = make_camera_view(camera, aspect);
    const CameraView fit_view = cascade_camera_ ? make_camera_view(*cascade_camera_, aspect) : view;
    last_frame_.cascades =
        compute_cascades(fit_view, sun_travel_direction(scene_), settings_.shadow.cascades, scene_.world_bounds());
    const shader::FrameUniforms uniforms =
        build_frame_uniforms(view, scene_, last_frame_.cascades, settings_, frame_index_++);
    std::memcpy(resources_->frame_uniforms.mapped, &uniforms, sizeof(uniforms));
    last_frame_.cpu_times.cascade_setup_ms = milliseconds_since(start);

    start = Clock::now();
    CulledCasters casters =
        cull_casters(scene_, last_frame_.cascades, resources_->gpu_scene.draw_data(), settings_.shadow.cull_casters);
    last_frame_.cascade_stats = casters.stats;
    last_frame_.local_shadow_stats =
        resources_->local_shadows.prepare(scene_, resources_->gpu_scene.draw_data(), settings_, view);
    last_frame_.cpu_times.culling_ms = milliseconds_since(start);
    return casters;
}

void Renderer::record_frame(VkCommandBuffer cmd, const CulledCasters& casters, ReadbackMode readback) {
    const passes::DrawData& draw_data = resources_->gpu_scene.draw_data();
    gpu::GpuTimer& timer = resources_->timer;
    timer.begin_frame(cmd);
    {
        gpu::TimedScope frame_scope(&timer, cmd, "frame");
        if (resources_->filters.uses_moments()) {
            gpu::TimedScope moments_scope(&timer, cmd, "shadow_moments");
            resources_->filters.record_moments(cmd, draw_data, casters.lists);
        } else {
            resources_->shadow_pass.record(cmd, resources_->shadow_frame_set, draw_data, casters.lists,
                                           settings_.shadow.bias, &timer);
        }
        resources_->local_shadows.record(cmd, draw_data, settings_, &timer);
        gpu::TimedScope lighting_scope(&timer, cmd, "lighting");
        resources_->lighting_pass.record(cmd, resources_->lighting_frame_set, draw_data);
        if (resources_->geometry_aovs) resources_->geometry_aovs->record(cmd, draw_data);
    }
    if (readback == ReadbackMode::None) return;

    const passes::LightingTargets& targets = resources_->lighting_pass.targets();
    copy_image_to_buffer(context_, cmd, targets.color, resources_->readback.color);
    copy_image_to_buffer(context_, cmd, targets.visibility, resources_->readback.visibility);
    copy_image_to_buffer(context_, cmd, targets.cascade, resources_->readback.cascade);
    if (settings_.debug == DebugView::ShadowMap) {
        const gpu::Image& shadow_map = resources_->filters.depth_map(resources_->shadow_pass.shadow_map());
        gpu::transition(context_, cmd, shadow_map, gpu::ImageState::FragmentSampled, gpu::ImageState::TransferSrc);
        copy_image_to_buffer(context_, cmd, shadow_map, resources_->readback.shadow_map);
    }
    if (resources_->geometry_aovs) {
        const passes::GeometryAovTargets& geometry = resources_->geometry_aovs->targets();
        copy_image_to_buffer(context_, cmd, geometry.world_position, resources_->readback.world_position);
        copy_image_to_buffer(context_, cmd, geometry.world_normal, resources_->readback.world_normal);
    }
    gpu::transfer_to_host_barrier(context_, cmd);
}

FrameImages Renderer::read_images() const {
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
    if (resources_->geometry_aovs) {
        images.world_position = read_buffer<glm::vec4>(resources_->readback.world_position, pixels);
        images.world_normal = read_buffer<glm::vec4>(resources_->readback.world_normal, pixels);
    }
    return images;
}

}  // namespace penumbra::renderer
