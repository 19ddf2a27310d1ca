// Penumbra's engine example: the parts of an engine's frame loop that the minimal and
// deferred examples leave out.
//
//   - Two views in one ShadowSystem (prepare() with a list): view 0 is shaded forward by an
//     HLSL pixel shader (forward.frag.hlsl, Penumbra's HLSL library) through its own
//     descriptor set, view 1 only renders depth and gets Penumbra's screen-space resolve.
//     Each view has its own cascades; the scene is given once.
//   - TAA: both views render with a projection jittered by a sub-pixel offset per frame
//     (ViewDesc::projection takes it; the stable cascades stay where they are).
//   - A live filter change: after two frames the filter goes from PCF to PCSS with
//     update_settings(); the meshes, instances and lights stay, and the application rebuilds
//     its forward pipeline only because SettingsChange says the specialization changed.
//   - View 1's visibility goes into the application's own image (VisibilityTarget), so its
//     descriptors never change.
//   - That resolve runs on an async compute queue when the device has a compute-only queue
//     family (record_visibility_async(): the depth and the target change queue families
//     with release/acquire barriers, the queues are ordered by semaphores), and on the
//     graphics queue otherwise (lavapipe has one family).
//   - Two frames in flight, each with its own application images, command buffers,
//     semaphores and fence, and (ShadowSystemDesc::maps_per_frame_in_flight) its own set of
//     Penumbra's maps: frame F + 1's shadow passes on the graphics queue do not wait for
//     frame F's resolve on the compute queue, which still samples frame F's maps.
//   - With --validate the instance has VK_EXT_debug_utils: Penumbra names its objects and
//     labels its passes, as RenderDoc or Nsight would show them.
//
// Scene: the examples' box over a plane, sun along (-0.4, -1, -0.3). View 0 is the other
// examples' camera (eye (0, 6, 12)), view 1 looks from (-9, 7, 6) at the origin; both 640 x
// 360, 60 degrees vertically. Four frames; the last one, at the jitter pattern's centre, is
// written: the sun's visibility of each view as a 16-bit PNG (65535 lit).
//
//   penumbra_engine VIEW0.png VIEW1.png [--validate]
#include <penumbra/penumbra.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "example_vulkan.hpp"
#include "scene_geometry.hpp"

namespace {

constexpr uint32_t kWidth = 640;
constexpr uint32_t kHeight = 360;
constexpr int kFrames = 4;
constexpr int kFilterChangeFrame = 2;
constexpr uint32_t kFramesInFlight = 2;
// The sub-pixel jitter of each frame (pixels); the last frame, the one written, at the centre.
constexpr std::array<std::array<float, 2>, kFrames> kJitter{
    {{0.25f, -0.25f}, {-0.25f, 0.25f}, {0.375f, 0.125f}, {0.0f, 0.0f}}};

const uint32_t kVertexShader[] =
#include "forward.vert.inc"
    ;
const uint32_t kPixelShader[] =
#include "forward.frag.hlsl.inc"
    ;
const uint32_t kDepthShader[] =
#include "depth.vert.inc"
    ;

struct PushConstants {
    penumbra::Mat4 view_projection;
    penumbra::Mat4 model;
};

// `projection` moved by `pixels` across the image: clip x and y shifted by 2 * pixels / size.
penumbra::Mat4 jittered(const penumbra::Mat4& projection, const std::array<float, 2>& pixels) {
    penumbra::Mat4 shift;
    shift(0, 3) = 2.0f * pixels[0] / static_cast<float>(kWidth);
    shift(1, 3) = 2.0f * pixels[1] / static_cast<float>(kHeight);
    return example::multiply(shift, projection);
}

// The frame's two cameras, each with its jittered projection.
std::array<penumbra::ViewDesc, 2> frame_views(int frame) {
    std::array<penumbra::ViewDesc, 2> views{
        example::camera_view(kWidth, kHeight),
        penumbra::look_at_view({-9.0f, 7.0f, 6.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                               60.0f * 3.14159265f / 180.0f, 0.1f, 200.0f, kWidth, kHeight)};
    for (penumbra::ViewDesc& view : views) {
        view.projection = jittered(penumbra::reverse_z_projection(view), kJitter[frame]);
        view.sampling_frame = 0;  // a still Poisson/PCSS pattern: the images are compared with the truth
    }
    return views;
}

penumbra::Mat4 view_projection_of(const penumbra::ViewDesc& view) {
    return example::multiply(*view.projection, view.view);
}

VkShaderModule module_of(const example::Device& device, const uint32_t* code, size_t bytes) {
    return example::shader_module(device, code, bytes);
}

// A pipeline over the scene's vertices with push constants and, for the forward pass,
// Penumbra's set at 0 and its specialization constants (the configured filter).
struct Pipeline {
    VkDevice device = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;

    // The forward pass: forward.vert and the HLSL pixel shader, writing R16 visibility.
    Pipeline(const example::Device& owner, const penumbra::ShadowSystem& shadows) : device(owner.device) {
        const VkDescriptorSetLayout set_layout = shadows.descriptor_set_layout();
        create_layout(&set_layout);
        const penumbra::ShaderSpecialization specialization = shadows.shader_specialization(0);
        const VkSpecializationInfo specialization_info = specialization.info();
        std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
        stages[0] = stage(VK_SHADER_STAGE_VERTEX_BIT, module_of(owner, kVertexShader, sizeof(kVertexShader)));
        stages[1] = stage(VK_SHADER_STAGE_FRAGMENT_BIT, module_of(owner, kPixelShader, sizeof(kPixelShader)));
        stages[1].pSpecializationInfo = &specialization_info;
        pipeline = example::create_scene_pipeline(owner, layout, stages, VK_FORMAT_R16_UNORM, VK_COMPARE_OP_GREATER);
        for (const VkPipelineShaderStageCreateInfo& created : stages)
            vkDestroyShaderModule(device, created.module, nullptr);
    }
    // The depth-only pass of the resolved view (reverse Z).
    explicit Pipeline(const example::Device& owner) : device(owner.device) {
        create_layout(nullptr);
        std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
        stages[0] = stage(VK_SHADER_STAGE_VERTEX_BIT, module_of(owner, kDepthShader, sizeof(kDepthShader)));
        pipeline = example::create_scene_pipeline(owner, layout, stages, VK_FORMAT_UNDEFINED, VK_COMPARE_OP_GREATER, 1);
        vkDestroyShaderModule(device, stages[0].module, nullptr);
    }
    ~Pipeline() {
        vkDestroyPipeline(device, pipeline, nullptr);
        vkDestroyPipelineLayout(device, layout, nullptr);
    }
    Pipeline(const Pipeline&) = delete;
    Pipeline& operator=(const Pipeline&) = delete;

private:
    void create_layout(const VkDescriptorSetLayout* set_layout) {
        const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(PushConstants)};
        VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        info.setLayoutCount = set_layout ? 1 : 0;
        info.pSetLayouts = set_layout;
        info.pushConstantRangeCount = 1;
        info.pPushConstantRanges = &push;
        EXAMPLE_CHECK(vkCreatePipelineLayout(device, &info, nullptr, &layout));
    }
    static VkPipelineShaderStageCreateInfo stage(VkShaderStageFlagBits flag, VkShaderModule module) {
        VkPipelineShaderStageCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        info.stage = flag;
        info.module = module;
        info.pName = "main";
        return info;
    }
};

// A queue family ownership transfer's half for one image (Vulkan spec, "Queue Family
// Ownership Transfer"): the release on the giving queue (`stage`/`access` its last use), or
// the acquire on the taking queue (`stage`/`access` its next use), with the same layouts
// and families in both.
enum class Half { Release, Acquire };
void transfer(VkCommandBuffer cmd, Half half, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
              VkImageLayout to, uint32_t from_family, uint32_t to_family, VkPipelineStageFlags2 stage,
              VkAccessFlags2 access) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    const bool release = half == Half::Release;
    barrier.srcStageMask = release ? stage : VK_PIPELINE_STAGE_2_NONE;
    barrier.srcAccessMask = release ? access : VK_ACCESS_2_NONE;
    barrier.dstStageMask = release ? VK_PIPELINE_STAGE_2_NONE : stage;
    barrier.dstAccessMask = release ? VK_ACCESS_2_NONE : access;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = from_family;
    barrier.dstQueueFamilyIndex = to_family;
    barrier.image = image;
    barrier.subresourceRange = {aspect, 0, 1, 0, 1};
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

// The submissions of the frames in flight: each frame slot has two semaphores (graphics ->
// compute -> graphics), a fence its last submission signals, and the command buffers it
// recorded, freed when the slot is next begun (its fence has signalled by then).
class FrameSubmissions {
public:
    explicit FrameSubmissions(const example::Device& device) : device_(device) {
        for (Slot& slot : slots_) {
            for (VkSemaphore& semaphore : slot.semaphores) {
                const VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
                EXAMPLE_CHECK(vkCreateSemaphore(device.device, &info, nullptr, &semaphore));
            }
            VkFenceCreateInfo info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
            info.flags = VK_FENCE_CREATE_SIGNALED_BIT;
            EXAMPLE_CHECK(vkCreateFence(device.device, &info, nullptr, &slot.fence));
        }
    }
    ~FrameSubmissions() {
        wait_idle();
        for (Slot& slot : slots_) {
            for (VkSemaphore semaphore : slot.semaphores) vkDestroySemaphore(device_.device, semaphore, nullptr);
            vkDestroyFence(device_.device, slot.fence, nullptr);
        }
    }
    FrameSubmissions(const FrameSubmissions&) = delete;
    FrameSubmissions& operator=(const FrameSubmissions&) = delete;

    // Waits for the frame that last used `slot` (kFramesInFlight frames ago) and frees its
    // command buffers: what it used may be written again.
    void begin(uint32_t slot) {
        Slot& begun = slots_[slot];
        EXAMPLE_CHECK(vkWaitForFences(device_.device, 1, &begun.fence, VK_TRUE, UINT64_MAX));
        EXAMPLE_CHECK(vkResetFences(device_.device, 1, &begun.fence));
        free_recorded(begun);
    }

    VkSemaphore semaphore(uint32_t slot, int index) const { return slots_[slot].semaphores[index]; }

    // Records into a new command buffer of `pool` and submits it on `queue`, waiting for
    // `wait` (at `wait_stage`) and signalling `signal` (either VK_NULL_HANDLE); the frame's
    // last submission signals the slot's fence (`last`).
    void submit(uint32_t slot, VkQueue queue, VkCommandPool pool, VkSemaphore wait, VkPipelineStageFlags2 wait_stage,
                VkSemaphore signal, bool last, const std::function<void(VkCommandBuffer)>& record) {
        VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        allocate.commandPool = pool;
        allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        allocate.commandBufferCount = 1;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        EXAMPLE_CHECK(vkAllocateCommandBuffers(device_.device, &allocate, &cmd));
        slots_[slot].recorded.push_back({pool, cmd});
        VkCommandBufferBeginInfo begin_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin_info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        EXAMPLE_CHECK(vkBeginCommandBuffer(cmd, &begin_info));
        record(cmd);
        EXAMPLE_CHECK(vkEndCommandBuffer(cmd));
        VkCommandBufferSubmitInfo command{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
        command.commandBuffer = cmd;
        VkSemaphoreSubmitInfo wait_info{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
        wait_info.semaphore = wait;
        wait_info.stageMask = wait_stage;
        VkSemaphoreSubmitInfo signal_info{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
        signal_info.semaphore = signal;
        signal_info.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        VkSubmitInfo2 info{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
        info.waitSemaphoreInfoCount = wait ? 1 : 0;
        info.pWaitSemaphoreInfos = &wait_info;
        info.commandBufferInfoCount = 1;
        info.pCommandBufferInfos = &command;
        info.signalSemaphoreInfoCount = signal ? 1 : 0;
        info.pSignalSemaphoreInfos = &signal_info;
        EXAMPLE_CHECK(vkQueueSubmit2(queue, 1, &info, last ? slots_[slot].fence : VK_NULL_HANDLE));
    }

    void wait_idle() {
        vkDeviceWaitIdle(device_.device);
        for (Slot& slot : slots_) free_recorded(slot);
    }

private:
    struct Slot {
        std::array<VkSemaphore, 2> semaphores{};
        VkFence fence = VK_NULL_HANDLE;
        std::vector<std::pair<VkCommandPool, VkCommandBuffer>> recorded;
    };

    void free_recorded(Slot& slot) {
        for (const auto& [pool, cmd] : slot.recorded) vkFreeCommandBuffers(device_.device, pool, 1, &cmd);
        slot.recorded.clear();
    }

    const example::Device& device_;
    std::array<Slot, kFramesInFlight> slots_{};
};

// The application's visibility image for view 1 (VisibilityTarget): RGBA8, one layer, a
// 2D array view as the resolve writes it.
struct VisibilityTargetImage {
    example::Image image;
    VkImageView array_view = VK_NULL_HANDLE;

    explicit VisibilityTargetImage(const example::Device& device)
        : image(device, VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight,
                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                VK_IMAGE_ASPECT_COLOR_BIT) {
        VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        info.image = image.image;
        info.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
        info.format = VK_FORMAT_R8G8B8A8_UNORM;
        info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        EXAMPLE_CHECK(vkCreateImageView(device.device, &info, nullptr, &array_view));
    }
    ~VisibilityTargetImage() { vkDestroyImageView(image.device->device, array_view, nullptr); }
    VisibilityTargetImage(const VisibilityTargetImage&) = delete;
    VisibilityTargetImage& operator=(const VisibilityTargetImage&) = delete;

    penumbra::VisibilityTarget target() const {
        return {image.image, array_view, VK_FORMAT_R8G8B8A8_UNORM, kWidth, kHeight, 1};
    }
};

// The application's images and readbacks of one frame in flight.
struct FrameImages {
    example::Image color0;  // view 0's forward-shaded visibility
    example::Image depth0;
    example::Image depth1;  // view 1's depth, resolved by Penumbra
    VisibilityTargetImage target1;
    example::Buffer readback0;
    example::Buffer readback1;

    explicit FrameImages(const example::Device& device)
        : color0(device, VK_FORMAT_R16_UNORM, kWidth, kHeight,
                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT),
          depth0(device, VK_FORMAT_D32_SFLOAT, kWidth, kHeight, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                 VK_IMAGE_ASPECT_DEPTH_BIT),
          depth1(device, VK_FORMAT_D32_SFLOAT, kWidth, kHeight,
                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_DEPTH_BIT),
          target1(device),
          readback0(device, size_t{kWidth} * kHeight * sizeof(uint16_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT),
          readback1(device, size_t{kWidth} * kHeight * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT) {}
};

class EngineFrames {
public:
    explicit EngineFrames(const example::Device& device)
        : device_(device),
          scene_(device),
          shadows_(system_desc(device)),
          depth_pipeline_(device),
          images_{FrameImages(device), FrameImages(device)},
          submissions_(device) {
        // The application's own buffers, given once for both views.
        const penumbra::MeshId box = shadows_.add_mesh(scene_.box_mesh());
        const penumbra::MeshId plane = shadows_.add_mesh(scene_.plane_mesh());
        shadows_.add_instance({box, example::translation(example::kBoxCentre)});
        shadows_.add_instance({plane, penumbra::Mat4{}});
        const penumbra::LightDesc sun{penumbra::LightType::Directional, example::kSunDirection};
        shadows_.set_lights({&sun, 1});
        penumbra::Settings settings = shadows_.settings();
        settings.shadow.filter.mode = penumbra::ShadowFilter::Pcf;
        shadows_.update_settings(settings);
        forward_pipeline_ = std::make_unique<Pipeline>(device, shadows_);
        std::printf("penumbra_engine: view 1 resolves on %s\n",
                    async() ? "an async compute queue (a compute-only queue family)"
                            : "the graphics queue (the device has no compute-only queue family)");
    }

    // Frame `frame` in slot frame % kFramesInFlight, once the slot's previous frame is done;
    // the frame before it may still run (its resolve on the compute queue sampling its own
    // set of Penumbra's maps) while this one's shadow passes draw theirs.
    void run_frame(int frame) {
        const uint32_t slot = static_cast<uint32_t>(frame) % kFramesInFlight;
        submissions_.begin(slot);  // the frame kFramesInFlight earlier is complete
        if (retired_pipeline_ && frame >= retired_at_ + static_cast<int>(kFramesInFlight)) retired_pipeline_.reset();
        if (frame == kFilterChangeFrame) change_filter(frame);
        FrameImages& images = images_[slot];
        const std::array<penumbra::ViewDesc, 2> views = frame_views(frame);
        const penumbra::FrameInfo& info = shadows_.prepare(views);
        const penumbra::ScreenInputs screen = view1_screen(images, view_projection_of(views[1]));
        const uint32_t graphics = device_.queue_family;
        const uint32_t compute = device_.compute_family;
        submissions_.submit(
            slot, device_.queue, device_.pool, VK_NULL_HANDLE, VK_PIPELINE_STAGE_2_NONE,
            async() ? submissions_.semaphore(slot, 0) : VK_NULL_HANDLE, !async(), [&](VkCommandBuffer cmd) {
                shadows_.record_shadow_maps(cmd);
                record_forward_view0(cmd, images, info.views[0].descriptor_set, view_projection_of(views[0]));
                record_depth_view1(cmd, images, view_projection_of(views[1]));
                if (async()) {
                    // The depth's writes go to the compute family, in the resolve's layout.
                    transfer(cmd, Half::Release, images.depth1.image, VK_IMAGE_ASPECT_DEPTH_BIT,
                             VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                             graphics, compute, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                             VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
                    return;
                }
                make_depth1_readable(cmd, images);
                shadows_.record_visibility(cmd, screen, images.target1.target(), 1);
                record_copy_view1(cmd, images, /*acquired_for_copy=*/false);
            });
        if (!async()) return;
        submissions_.submit(
            slot, device_.compute_queue, device_.compute_pool, submissions_.semaphore(slot, 0),
            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, submissions_.semaphore(slot, 1), false, [&](VkCommandBuffer cmd) {
                transfer(cmd, Half::Acquire, images.depth1.image, VK_IMAGE_ASPECT_DEPTH_BIT,
                         VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, graphics,
                         compute, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
                shadows_.record_visibility_async(cmd, screen, images.target1.target(), 1);
                // The visibility goes back to the graphics family, for the copy there.
                transfer(cmd, Half::Release, images.target1.image.image, VK_IMAGE_ASPECT_COLOR_BIT,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, compute,
                         graphics, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_NONE);
            });
        submissions_.submit(slot, device_.queue, device_.pool, submissions_.semaphore(slot, 1),
                            VK_PIPELINE_STAGE_2_COPY_BIT, VK_NULL_HANDLE, true, [&](VkCommandBuffer cmd) {
                                transfer(cmd, Half::Acquire, images.target1.image.image, VK_IMAGE_ASPECT_COLOR_BIT,
                                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                         compute, graphics, VK_PIPELINE_STAGE_2_COPY_BIT,
                                         VK_ACCESS_2_TRANSFER_READ_BIT);
                                record_copy_view1(cmd, images, /*acquired_for_copy=*/true);
                            });
    }

    // Waits for every frame in flight (before the images are read).
    void finish() { submissions_.wait_idle(); }

    // Frame `frame`'s sun visibility of each view, 16 bits (65535 lit), after finish().
    std::vector<uint16_t> view0(int frame) const {
        std::vector<uint16_t> pixels(size_t{kWidth} * kHeight);
        std::memcpy(pixels.data(), images_[static_cast<uint32_t>(frame) % kFramesInFlight].readback0.mapped,
                    pixels.size() * sizeof(uint16_t));
        return pixels;
    }
    std::vector<uint16_t> view1(int frame) const {
        // Slot 0 (the sun) is the red channel of the target's layer 0.
        std::vector<uint16_t> pixels(size_t{kWidth} * kHeight);
        const auto* rgba =
            static_cast<const uint8_t*>(images_[static_cast<uint32_t>(frame) % kFramesInFlight].readback1.mapped);
        for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<uint16_t>(rgba[4 * i] * 257u);
        return pixels;
    }

    void print_times(uint64_t frame) const {
        const std::optional<penumbra::GpuTimes> times = shadows_.gpu_times(frame);
        if (!times) return;
        std::printf("penumbra_engine: frame %llu on the GPU:", static_cast<unsigned long long>(frame));
        for (const penumbra::PassTime& pass : times->passes)
            std::printf(" %s %.3f ms", pass.name.c_str(), pass.milliseconds);
        std::printf("\n");
    }

private:
    static penumbra::ShadowSystemDesc system_desc(const example::Device& device) {
        penumbra::ShadowSystemDesc desc;
        desc.device = device.penumbra_desc();     // with the compute family, when there is one
        desc.frames_in_flight = kFramesInFlight;  // prepare() of frame F: frame F - 2 is complete
        // Frame F draws its own maps while frame F - 1's resolve may still sample its set.
        desc.maps_per_frame_in_flight = true;
        return desc;
    }

    bool async() const { return device_.compute_family != VK_QUEUE_FAMILY_IGNORED; }

    // PCF to PCSS between frames: the scene stays in the system; the application's own
    // pipeline follows the new specialization constants (the old one is kept until the
    // frames in flight that use it are done).
    void change_filter(int frame) {
        penumbra::Settings settings = shadows_.settings();
        settings.shadow.filter.mode = penumbra::ShadowFilter::Pcss;
        const penumbra::SettingsChange change = shadows_.update_settings(settings);
        if (change.shader_specialization_changed) {
            retired_pipeline_ = std::exchange(forward_pipeline_, std::make_unique<Pipeline>(device_, shadows_));
            retired_at_ = frame;
        }
        std::printf("penumbra_engine: filter pcf -> pcss (a %s change; the scene kept; the forward pipeline %s)\n",
                    change.effect == penumbra::SettingEffect::Live       ? "live"
                    : change.effect == penumbra::SettingEffect::Pipeline ? "pipeline"
                                                                         : "resource",
                    change.shader_specialization_changed ? "rebuilt" : "kept");
    }

    void draw_scene(VkCommandBuffer cmd, VkPipelineLayout layout, const penumbra::Mat4& view_projection) const {
        for (const auto& [mesh, model] : {std::pair{example::SceneMesh::Box, example::translation(example::kBoxCentre)},
                                          std::pair{example::SceneMesh::Plane, penumbra::Mat4{}}}) {
            const PushConstants constants{view_projection, model};
            vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(constants), &constants);
            scene_.draw(cmd, mesh);
        }
    }

    // View 0: forward shading with the HLSL pixel shader and the view's own descriptor set.
    void record_forward_view0(VkCommandBuffer cmd, FrameImages& images, VkDescriptorSet set,
                              const penumbra::Mat4& view_projection) {
        example::begin_scene_pass(cmd, &images.color0, images.depth0, kWidth, kHeight, 1.0f, 0.0f);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, forward_pipeline_->pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, forward_pipeline_->layout, 0, 1, &set, 0,
                                nullptr);
        draw_scene(cmd, forward_pipeline_->layout, view_projection);
        vkCmdEndRendering(cmd);
        example::copy_to_buffer(cmd, images.color0, kWidth, kHeight, images.readback0);
    }

    // View 1: depth only (reverse Z, cleared to 0), for the resolve.
    void record_depth_view1(VkCommandBuffer cmd, FrameImages& images, const penumbra::Mat4& view_projection) {
        example::begin_scene_pass(cmd, nullptr, images.depth1, kWidth, kHeight, 0.0f, 0.0f);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, depth_pipeline_.pipeline);
        draw_scene(cmd, depth_pipeline_.layout, view_projection);
        vkCmdEndRendering(cmd);
    }

    static void make_depth1_readable(VkCommandBuffer cmd, FrameImages& images) {
        example::barrier(cmd, images.depth1.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                         VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                         VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }

    static penumbra::ScreenInputs view1_screen(const FrameImages& images, const penumbra::Mat4& view_projection) {
        penumbra::ScreenInputs screen;
        screen.depth = images.depth1.view;
        screen.width = kWidth;
        screen.height = kHeight;
        screen.view_projection = view_projection;
        screen.background_depth = 0.0f;  // reverse Z: the cleared far plane
        return screen;
    }

    // The target after the resolve (SHADER_READ_ONLY, writes visible to compute reads; or
    // already TRANSFER_SRC, acquired from the compute queue for the copy) into readback1_, and
    // back to SHADER_READ_ONLY for the next frame's resolve.
    static void record_copy_view1(VkCommandBuffer cmd, FrameImages& images, bool acquired_for_copy) {
        const VkImage image = images.target1.image.image;
        if (!acquired_for_copy) {
            example::barrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                             VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                             VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                             VK_ACCESS_2_TRANSFER_READ_BIT);
        }
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {kWidth, kHeight, 1};
        vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, images.readback1.buffer, 1, &region);
        example::barrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_NONE);
        example::host_read_barrier(cmd);
    }

    const example::Device& device_;
    example::SceneBuffers scene_;
    penumbra::ShadowSystem shadows_;
    std::unique_ptr<Pipeline> forward_pipeline_;
    std::unique_ptr<Pipeline> retired_pipeline_;  // replaced at frame retired_at_, maybe still in use
    int retired_at_ = 0;
    Pipeline depth_pipeline_;
    std::array<FrameImages, kFramesInFlight> images_;
    FrameSubmissions submissions_;
};

int run(const std::string& view0_path, const std::string& view1_path, bool validate) {
    std::vector<uint16_t> view0;
    std::vector<uint16_t> view1;
    {
        const example::Device device(validate, /*async_compute=*/true);
        EngineFrames frames(device);
        for (int frame = 0; frame < kFrames; ++frame) frames.run_frame(frame);
        frames.finish();
        frames.print_times(kFrames);
        view0 = frames.view0(kFrames - 1);
        view1 = frames.view1(kFrames - 1);
    }
    if (example::validation_message_count() > 0) {
        std::fprintf(stderr, "penumbra_engine: the validation layer reported %u message(s)\n",
                     example::validation_message_count());
        return 3;
    }
    example::write_png16(view0_path, kWidth, kHeight, view0);
    example::write_png16(view1_path, kWidth, kHeight, view1);
    std::printf("penumbra_engine: wrote %s and %s\n", view0_path.c_str(), view1_path.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const bool validate = argc == 4 && std::string(argv[3]) == "--validate";
    if (argc < 3 || (argc == 4 && !validate) || argc > 4) {
        std::fprintf(stderr, "usage: penumbra_engine VIEW0.png VIEW1.png [--validate]\n");
        return 2;
    }
    try {
        return run(argv[1], argv[2], validate);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "penumbra_engine: %s\n", error.what());
        return 1;
    }
}
