#include "renderer/renderer.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "penumbra/errors.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra/gpu/check.hpp"
#include "penumbra/gpu/frame_commands.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "quality/enclosing_casters.hpp"
#include "renderer/frame_uniforms.hpp"
#include "renderer/geometry_aov_pass.hpp"
#include "renderer/gpu_scene.hpp"
#include "renderer/lighting_pass.hpp"
#include "renderer/screen_prepass.hpp"
#include "renderer/shader_interface.hpp"

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

gpu::Buffer create_readback_buffer(const gpu::Device& device, VkDeviceSize bytes) {
    return gpu::create_buffer(device, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryKind::HostReadback);
}

Readback create_readback(const gpu::Device& device, const RenderSettings& settings) {
    const VkDeviceSize pixels = VkDeviceSize{settings.width} * settings.height;
    Readback readback{create_readback_buffer(device, pixels * 4),
                      create_readback_buffer(device, pixels * 2),
                      create_readback_buffer(device, pixels),
                      {},
                      {},
                      {}};
    if (settings.debug == DebugView::ShadowMap) {
        const VkDeviceSize texels = VkDeviceSize{settings.shadow.cascades.resolution} *
                                    settings.shadow.cascades.resolution * settings.shadow.cascades.count;
        readback.shadow_map = create_readback_buffer(device, texels * sizeof(float));
    }
    if (settings.geometry_aovs) {
        readback.world_position = create_readback_buffer(device, pixels * sizeof(glm::vec4));
        readback.world_normal = create_readback_buffer(device, pixels * sizeof(glm::vec4));
    }
    return readback;
}

// Copies every layer of an image (tightly packed, layer after layer) into `buffer`.
void copy_image_to_buffer(const gpu::Device& device, VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                          VkExtent2D extent, uint32_t layers, const gpu::Buffer& buffer) {
    VkBufferImageCopy region{};
    region.imageSubresource = {aspect, 0, 0, layers};
    region.imageExtent = {extent.width, extent.height, 1};
    device->vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.get(), 1, &region);
}

void copy_image_to_buffer(const gpu::Device& device, VkCommandBuffer cmd, const gpu::Image& image,
                          const gpu::Buffer& buffer) {
    copy_image_to_buffer(device, cmd, image.get(), image.desc.aspect, image.extent(), image.desc.layers, buffer);
}

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Scopes of the renderer's own: the frame, the deferred path's pre-pass and the lighting
// (the shadow passes' and the resolve's are the ShadowSystem's).
constexpr uint32_t kMaxTimedScopes = 4;

template <typename T>
std::vector<T> read_buffer(const gpu::Buffer& buffer, size_t count) {
    std::vector<T> values(count);
    std::memcpy(values.data(), buffer.mapped, count * sizeof(T));
    return values;
}

ShadowSystemDesc shadow_system_desc(const AppContext& context, const RenderSettings& settings) {
    ShadowSystemDesc desc;
    desc.device = context.device_desc();
    desc.settings = static_cast<const Settings&>(settings);
    desc.frames_in_flight = 1;  // render() waits for every frame
    return desc;
}

ViewDesc view_of(const Camera& camera, const RenderSettings& settings) {
    const auto vec = [](const glm::vec3& v) { return Vec3{v.x, v.y, v.z}; };
    return look_at_view(vec(camera.eye), vec(camera.target), vec(camera.up), glm::radians(camera.fov_y_degrees),
                        camera.near_plane, camera.far_plane, settings.width, settings.height);
}

// Whether the lighting pass traces contact shadows itself: forward shading with them, and
// `--aov contact` (deferred, the resolve has traced them into the visibility it reads).
bool lighting_traces_contact(ShadowResolve resolve, const RenderSettings& settings) {
    return settings.contact.enabled &&
           (resolve == ShadowResolve::Forward || settings.visibility_light == kVisibilityContact);
}

// Spot or point lights that cast shadows and are lit (lit_local_lights()).
bool casts_local_shadows(const Scene& scene) {
    for (const uint32_t light : lit_local_lights(scene.lights)) {
        if (scene.lights[light].cast_shadows) return true;
    }
    return false;
}

}  // namespace

std::vector<uint32_t> lit_local_lights(const std::vector<Light>& lights) {
    std::vector<uint32_t> lit;
    for (uint32_t i = 0; i < lights.size() && lit.size() < kMaxLocalLights; ++i) {
        if (lights[i].type != LightType::Directional) lit.push_back(i);
    }
    return lit;
}

struct Renderer::Resources {
    ShadowSystem shadows;
    GpuScene gpu_scene;
    gpu::UniqueDescriptorSetLayout frame_set_layout;
    gpu::Buffer frame_uniforms;
    gpu::Buffer lights;
    gpu::UniqueDescriptorPool descriptor_pool;
    VkDescriptorSet frame_set = VK_NULL_HANDLE;
    ShadowResolve resolve;  // Forward or Deferred: settings.resolve made effective
    // With ShadowResolve::Deferred, with the virtual shadow map (its pages are marked from
    // the frame's depth before the shadow maps are drawn) and with contact shadows (traced
    // through its depth, by the resolve or by the lighting pass).
    std::unique_ptr<ScreenPrepass> prepass;
    bool marks_pages = false;  // Settings::shadow.technique = virtual
    LightingPass lighting_pass;
    glm::mat4 view_projection{1.0f};  // the frame's camera, for the resolve
    Readback readback;
    std::optional<GeometryAovPass> geometry_aovs;  // only with RenderSettings::geometry_aovs
    gpu::FrameCommands commands;
    gpu::GpuTimer timer;
    bool warned = false;

    Resources(const AppContext& context, const Scene& scene, const RenderSettings& settings)
        : shadows(shadow_system_desc(context, settings)),
          gpu_scene(context, scene, shadows),
          frame_set_layout(create_frame_set_layout(context)),
          frame_uniforms(gpu::create_buffer(context, sizeof(shader::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                            gpu::MemoryKind::HostUpload)),
          lights(gpu::create_buffer(context, sizeof(shader::LocalLights), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                    gpu::MemoryKind::HostUpload)),
          resolve(effective_resolve(settings.resolve, settings.shadow.filter.mode, casts_local_shadows(scene),
                                    uint64_t{settings.width} * settings.height, settings.contact.enabled)),
          prepass(resolve == ShadowResolve::Deferred || settings.shadow.technique == ShadowTechnique::Virtual ||
                          settings.contact.enabled
                      ? std::make_unique<ScreenPrepass>(context, frame_set_layout,
                                                        gpu_scene.draw_data().material_set_layout, settings.width,
                                                        settings.height)
                      : nullptr),
          lighting_pass(context, frame_set_layout, gpu_scene.draw_data().material_set_layout, shadows, settings.width,
                        settings.height, resolve, lighting_traces_contact(resolve, settings),
                        prepass ? &prepass->targets().depth : nullptr),
          readback(create_readback(context, settings)),
          commands(context),
          timer(context, kMaxTimedScopes) {
        marks_pages = settings.shadow.technique == ShadowTechnique::Virtual;
        const std::array<VkDescriptorPoolSize, 2> sizes{
            {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3}}};
        descriptor_pool = gpu::create_descriptor_pool(context, 1, sizes);
        frame_set = gpu::allocate_descriptor_set(context, descriptor_pool, frame_set_layout);
        gpu::write_uniform_buffer(context, frame_set, RENDERER_BINDING_FRAME_UNIFORMS, frame_uniforms.get(),
                                  frame_uniforms.size);
        gpu::write_storage_buffer(context, frame_set, RENDERER_BINDING_LIGHTS, lights.get(), lights.size);
        const DrawData& draws = gpu_scene.draw_data();
        gpu::write_storage_buffer(context, frame_set, RENDERER_BINDING_DRAW_MODELS, draws.draw_models, VK_WHOLE_SIZE);
        gpu::write_storage_buffer(context, frame_set, RENDERER_BINDING_INSTANCE_DRAWS, draws.instance_draws,
                                  VK_WHOLE_SIZE);
        if (settings.geometry_aovs) {
            geometry_aovs.emplace(context, frame_set_layout, gpu_scene.draw_data().material_set_layout, settings.width,
                                  settings.height);
        }
    }
};

Renderer::Renderer(const AppContext& context, const Scene& scene, const RenderSettings& settings)
    : context_(context),
      scene_(scene),
      settings_(settings),
      resources_(std::make_unique<Resources>(context, scene, settings)) {}

Renderer::~Renderer() {
    // Nothing may be destroyed while the GPU still uses it.
    if (context_.device()) context_->vkDeviceWaitIdle(context_);
}

const gpu::GpuTimer& Renderer::gpu_timer() const { return resources_->timer; }

ShadowResolve Renderer::resolve() const { return resources_->resolve; }

const gpu::Image& Renderer::color_target() const { return resources_->lighting_pass.targets().color; }

bool Renderer::needs_new_renderer(const RenderSettings& next) const {
    const RenderSettings& current = settings_;
    const auto is_shadow_map = [](DebugView view) { return view == DebugView::ShadowMap; };
    // Contact shadows need the depth pre-pass and the lighting pass's variant that reads it
    // (and make the automatic resolve deferred), as does `--aov contact`.
    const auto contact_aov = [](const RenderSettings& s) { return s.visibility_light == kVisibilityContact; };
    // The filter can change what --resolve auto picks; the virtual shadow map marks its
    // pages from the pre-pass's depth.
    const ShadowResolve resolve = effective_resolve(next.resolve, next.shadow.filter.mode, casts_local_shadows(scene_),
                                                    uint64_t{next.width} * next.height, next.contact.enabled);
    const bool needs_prepass =
        resolve == ShadowResolve::Deferred || next.shadow.technique == ShadowTechnique::Virtual || next.contact.enabled;
    return current.width != next.width || current.height != next.height || current.resolve != next.resolve ||
           resolve != resources_->resolve || (needs_prepass && !resources_->prepass) ||
           current.contact.enabled != next.contact.enabled || contact_aov(current) != contact_aov(next) ||
           is_shadow_map(current.debug) != is_shadow_map(next.debug);
}

void Renderer::update_settings(const RenderSettings& settings) {
    if (needs_new_renderer(settings)) {
        throw std::invalid_argument("Renderer::update_settings: the new settings need a new Renderer");
    }
    // The ShadowSystem keeps the scene through every change; the lighting pass follows its
    // specialization constants. Frames are waited for (render() leaves none in flight
    // beyond the one the caller presents).
    const SettingsChange change = resources_->shadows.update_settings(static_cast<const Settings&>(settings));
    if (change.shader_specialization_changed) {
        PENUMBRA_VK_CHECK(context_->vkDeviceWaitIdle(context_));
        resources_->lighting_pass.respecialize(resources_->shadows);
    }
    resources_->marks_pages = settings.shadow.technique == ShadowTechnique::Virtual;
    settings_ = settings;
}

uint64_t Renderer::shadow_map_bytes() const { return resources_->shadows.memory().shadow_maps(); }

std::string Renderer::light_warning() const {
    std::string warning;
    const size_t unshadowed = last_frame_.unshadowed_lights.size();
    if (unshadowed > 0) {
        warning = "penumbra: warning: " + std::to_string(unshadowed) +
                  " shadow-casting spot/point light(s) beyond the local shadow budget of " +
                  std::to_string(settings_.local_shadows.budget) + " render unshadowed (--local-shadow-budget)";
    }
    size_t local_lights = 0;
    for (const Light& light : scene_.lights) local_lights += light.type != LightType::Directional;
    if (local_lights > kMaxLocalLights) {
        warning += (warning.empty() ? "penumbra: warning: " : "; ") + std::to_string(local_lights - kMaxLocalLights) +
                   " spot/point light(s) beyond the first " + std::to_string(kMaxLocalLights) + " are not rendered";
    }
    return warning;
}

std::string Renderer::enclosure_warning(const Camera& camera) const {
    const float aspect = static_cast<float>(settings_.width) / static_cast<float>(settings_.height);
    return quality::enclosing_casters_warning(quality::find_enclosing_casters(scene_, camera, aspect));
}

FrameImages Renderer::render(const Camera& camera, ReadbackMode readback) {
    prepare_frame(camera);
    if (!resources_->warned) {
        resources_->warned = true;
        for (const std::string& warning : scene_.warnings) {
            std::fprintf(stderr, "penumbra: warning: %s\n", escape_control_characters(warning).c_str());
        }
        for (const std::string& warning : {light_warning(), enclosure_warning(camera)}) {
            if (!warning.empty()) std::fprintf(stderr, "%s\n", warning.c_str());
        }
    }
    const Clock::time_point submit_start = Clock::now();
    resources_->commands.submit_and_wait([&](VkCommandBuffer cmd) {
        const Clock::time_point record_start = Clock::now();
        record_frame(cmd, readback);
        last_frame_.cpu_times.recording_ms = milliseconds_since(record_start);
    });
    last_frame_.cpu_times.submit_wait_ms = milliseconds_since(submit_start) - last_frame_.cpu_times.recording_ms;
    // The fence has signalled, so every timestamp is available; none only without support.
    last_frame_.gpu_times.clear();
    const std::optional<std::vector<gpu::ScopeTime>> own = resources_->timer.read();
    const std::optional<GpuTimes> shadows = resources_->shadows.gpu_times(shadow_frame_);
    if (own && shadows) {
        // The frame encloses every pass: it reads first, then the shadow passes in their order.
        last_frame_.gpu_times.push_back(own->front());
        for (const PassTime& pass : shadows->passes) last_frame_.gpu_times.push_back({pass.name, pass.milliseconds});
        last_frame_.gpu_times.insert(last_frame_.gpu_times.end(), own->begin() + 1, own->end());
    }
    return readback == ReadbackMode::Images ? read_images() : FrameImages{};
}

void Renderer::move_instance(size_t instance, const glm::mat4& world) {
    resources_->gpu_scene.move_instance(instance, world, resources_->shadows);
}

void Renderer::prepare_frame(const Camera& camera) {
    ShadowSystem& shadows = resources_->shadows;
    shadows.set_lights(shadow_lights(scene_.lights));
    const ViewDesc view = view_of(camera, settings_);
    ViewDesc shadow_view = cascade_camera_ ? view_of(*cascade_camera_, settings_) : view;
    shadow_view.sampling_frame = sampling_frame_;
    const penumbra::FrameInfo& frame = shadows.prepare(shadow_view);
    shadow_frame_ = frame.frame;
    shadow_set_ = frame.descriptor_set;
    last_frame_.cascades = frame.cascades;
    last_frame_.virtual_map = frame.virtual_map;
    last_frame_.shadow_distance = frame.shadow_distance;
    last_frame_.local_shadows = frame.local_shadows;
    last_frame_.unshadowed_lights = frame.unshadowed_lights;
    last_frame_.cpu_times.cascade_setup_ms = frame.cpu_fit_ms;
    last_frame_.cpu_times.culling_ms = frame.cpu_cull_ms;
    last_frame_.cpu_times.settings_ms = frame.cpu_settings_ms;

    const shader::FrameUniforms uniforms = build_frame_uniforms(view, scene_, settings_);
    std::memcpy(resources_->frame_uniforms.mapped, &uniforms, sizeof(uniforms));
    resources_->view_projection = uniforms.view_projection;
    resources_->gpu_scene.order_draws_front_to_back(camera.eye);
    const shader::LocalLights lights = build_local_lights(scene_.lights, frame.local_shadows);
    std::memcpy(resources_->lights.mapped, &lights, sizeof(lights));
}

void Renderer::record_frame(VkCommandBuffer cmd, ReadbackMode readback) {
    Resources& r = *resources_;
    const DrawData& draw_data = r.gpu_scene.draw_data();
    r.timer.begin_frame(cmd);
    {
        gpu::TimedScope frame_scope(r.timer, cmd, "frame");
        if (r.prepass) {
            gpu::TimedScope prepass_scope(r.timer, cmd, "prepass");
            r.prepass->record(cmd, r.frame_set, draw_data);
        }
        if (r.marks_pages) r.shadows.record_page_marking(cmd, r.prepass->screen_inputs(r.view_projection));
        r.shadows.record_shadow_maps(cmd);
        if (r.resolve == ShadowResolve::Deferred) {
            r.shadows.record_visibility(cmd, r.prepass->screen_inputs(r.view_projection));
            r.lighting_pass.use_visibility_image(r.shadows.visibility_image());
        }
        gpu::TimedScope lighting_scope(r.timer, cmd, "lighting");
        r.lighting_pass.record(cmd, r.frame_set, shadow_set_, draw_data);
        if (r.geometry_aovs) r.geometry_aovs->record(cmd, r.frame_set, draw_data);
    }
    if (readback == ReadbackMode::None) return;

    const LightingTargets& targets = r.lighting_pass.targets();
    copy_image_to_buffer(context_, cmd, targets.color, r.readback.color);
    copy_image_to_buffer(context_, cmd, targets.visibility, r.readback.visibility);
    copy_image_to_buffer(context_, cmd, targets.cascade, r.readback.cascade);
    if (settings_.debug == DebugView::ShadowMap) {
        // Penumbra's map, borrowed for a copy and returned in the layout it left it in.
        const MapImage map = r.shadows.shadow_maps().cascades;
        gpu::transition(context_, cmd, map.image, map.aspect, map.layers, gpu::ImageState::ShaderSampled,
                        gpu::ImageState::TransferSrc);
        copy_image_to_buffer(context_, cmd, map.image, map.aspect, {map.resolution, map.resolution}, map.layers,
                             r.readback.shadow_map);
        gpu::transition(context_, cmd, map.image, map.aspect, map.layers, gpu::ImageState::TransferSrc,
                        gpu::ImageState::ShaderSampled);
    }
    if (r.geometry_aovs) {
        const GeometryAovTargets& geometry = r.geometry_aovs->targets();
        copy_image_to_buffer(context_, cmd, geometry.world_position, r.readback.world_position);
        copy_image_to_buffer(context_, cmd, geometry.world_normal, r.readback.world_normal);
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
        for (const CascadeInfo& cascade : last_frame_.cascades)
            images.shadow_map_layer_origins.emplace_back(cascade.layer_origin_x, cascade.layer_origin_y);
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
