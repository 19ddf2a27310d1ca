// The library's behaviour as a caller sees it: the screen-space visibility of the box's
// shadow against the analytic one; instances that move, lose their shadow flag or go away
// and lights that change show in the next frame; caller buffers and uploaded arrays give
// the same shadow maps; the caller's normals; frames in flight; caster face culling; a
// point light's slot; timings and memory; the sampling frame that rotates the patterns.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <optional>
#include <string>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

// 30 cm: the resolve's normal offset and bilinear comparison blur the edge over a few
// texels of the cascade (about 3 cm here) and the pixels are 7 cm wide.
constexpr float kEdgeBand = 0.3f;

void expect_box_shadow(const FootprintCheck& check) {
    EXPECT_GT(check.judged, 20000u);
    EXPECT_GT(check.shadowed, 500u);
    EXPECT_EQ(check.wrong, 0u) << "pixels away from the edge differ from the analytic shadow";
    EXPECT_GE(check.iou, 0.97);
}

void expect_all_lit(const VisibilityImage2D& image) {
    EXPECT_EQ(*std::min_element(image.values.begin(), image.values.end()), 1.0f);
}

void expect_all_dark(const VisibilityImage2D& image) {
    EXPECT_EQ(*std::max_element(image.values.begin(), image.values.end()), 0.0f);
}

using ShadowSystemFrames = LibraryTest;

TEST_F(ShadowSystemFrames, SunShadowMatchesTheAnalyticFootprint) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    expect_box_shadow(check_footprint(render_visibility(shadows), kBoxCentre, kSunDirection, kEdgeBand));
}

TEST_F(ShadowSystemFrames, MovedInstanceShadowFollows) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    const InstanceId instance = add_scene(shadows, box, ground);
    expect_box_shadow(check_footprint(render_visibility(shadows), kBoxCentre, kSunDirection, kEdgeBand));
    const glm::vec3 moved{1.5f, 2.5f, 1.0f};
    shadows.set_instance_transform(instance, translation(moved));
    expect_box_shadow(check_footprint(render_visibility(shadows), moved, kSunDirection, kEdgeBand));
}

TEST_F(ShadowSystemFrames, InstanceWithoutShadowFlagOrRemovedCastsNothing) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    const InstanceId instance = add_scene(shadows, box, ground);
    shadows.set_instance_flags(instance, 0);
    expect_all_lit(render_visibility(shadows));
    shadows.set_instance_flags(instance, kInstanceCastsShadows);
    expect_box_shadow(check_footprint(render_visibility(shadows), kBoxCentre, kSunDirection, kEdgeBand));
    shadows.remove_instance(instance);
    expect_all_lit(render_visibility(shadows));
}

TEST_F(ShadowSystemFrames, ChangedSunShowsInTheNextFrame) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    render_visibility(shadows);
    const glm::vec3 direction{0.5f, -1.0f, 0.2f};
    const LightDesc sun{LightType::Directional, {direction.x, direction.y, direction.z}};
    shadows.set_lights({&sun, 1});
    expect_box_shadow(check_footprint(render_visibility(shadows), kBoxCentre, direction, kEdgeBand));
    // No light at all: no sunlight reaches anything, the sun's slot is 0 everywhere.
    shadows.set_lights({});
    const FrameInfo& info = shadows.prepare(top_down_view());
    EXPECT_FALSE(info.sun.has_value());
    submit([&](VkCommandBuffer cmd) {
        shadows.record_shadow_maps(cmd);
        record_ground_visibility(cmd, shadows, nullptr, NormalEncoding::SignedFloat);
    });
    expect_all_dark(read_visibility(shadows, 0));
}

// The caller's normal buffer replaces the normals reconstructed from depth: up gives the
// same answer, either encoding; down (facing away from the sun) gives 0 everywhere.
TEST_F(ShadowSystemFrames, CallerNormalsInEveryEncodingAndFaceNormals) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    const VisibilityImage2D reconstructed = render_visibility(shadows);
    const auto normals_image = [&](VkFormat format, const VkClearColorValue& value) {
        auto image = std::make_unique<TestImage>(device_, format, kScreen, kScreen,
                                                 VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                                 VK_IMAGE_ASPECT_COLOR_BIT);
        submit([&](VkCommandBuffer cmd) {
            const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
            barrier.dstStageMask = VK_PIPELINE_STAGE_2_CLEAR_BIT;
            barrier.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
            barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
            barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            barrier.image = image->image;
            barrier.subresourceRange = range;
            VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
            dependency.imageMemoryBarrierCount = 1;
            dependency.pImageMemoryBarriers = &barrier;
            vkCmdPipelineBarrier2(cmd, &dependency);
            vkCmdClearColorImage(cmd, image->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &value, 1, &range);
            barrier.srcStageMask = VK_PIPELINE_STAGE_2_CLEAR_BIT;
            barrier.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
            barrier.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            barrier.dstAccessMask = VK_ACCESS_2_SHADER_READ_BIT;
            barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
            barrier.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
            vkCmdPipelineBarrier2(cmd, &dependency);
        });
        return image;
    };
    const auto up_float = normals_image(VK_FORMAT_R16G16B16A16_SFLOAT, {{0.0f, 1.0f, 0.0f, 0.0f}});
    EXPECT_EQ(render_visibility(shadows, 0, up_float.get(), NormalEncoding::SignedFloat).values, reconstructed.values);
    const auto up_unorm = normals_image(VK_FORMAT_R8G8B8A8_UNORM, {{0.5f, 1.0f, 0.5f, 0.0f}});
    const VisibilityImage2D unorm = render_visibility(shadows, 0, up_unorm.get(), NormalEncoding::UnsignedNormalized);
    expect_box_shadow(check_footprint(unorm, kBoxCentre, kSunDirection, kEdgeBand));
    const auto down = normals_image(VK_FORMAT_R16G16B16A16_SFLOAT, {{0.0f, -1.0f, 0.0f, 0.0f}});
    const VisibilityImage2D away = render_visibility(shadows, 0, down.get(), NormalEncoding::SignedFloat);
    EXPECT_EQ(*std::max_element(away.values.begin(), away.values.end()), 0.0f);

    // Octahedral: (0, 1, 0) encodes as (0, 1). The same image as the face normals (zw): the
    // ground's own plane, which its depth gives too, so the same visibility.
    const auto up_octahedral = normals_image(VK_FORMAT_R16G16B16A16_SFLOAT, {{0.0f, 1.0f, 0.0f, 1.0f}});
    EXPECT_EQ(render_visibility(shadows, 0, up_octahedral.get(), NormalEncoding::Octahedral).values,
              reconstructed.values);
    EXPECT_EQ(
        render_visibility(shadows, 0, up_octahedral.get(), NormalEncoding::Octahedral, up_octahedral.get()).values,
        reconstructed.values);
    // A face turned from the sun is unlit whatever the shading normal: its normal (-1, 0, 0),
    // (-1, 0) in zw, against the sun toward +x.
    const auto face_down = normals_image(VK_FORMAT_R16G16B16A16_SFLOAT, {{0.0f, 1.0f, -1.0f, 0.0f}});
    const VisibilityImage2D face_away =
        render_visibility(shadows, 0, face_down.get(), NormalEncoding::Octahedral, face_down.get());
    EXPECT_EQ(*std::max_element(face_away.values.begin(), face_away.values.end()), 0.0f);
}

// The caller's own buffers (interleaved position + normal, an index offset and a vertex
// offset, and half-float positions) draw exactly the shadow maps the uploaded arrays draw.
TEST_F(ShadowSystemFrames, CallerBuffersEqualUploadedArrays) {
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    ShadowSystem uploaded(system_desc());
    add_scene(uploaded, box, ground);
    const VisibilityImage2D uploaded_visibility = render_visibility(uploaded);
    const std::vector<float> uploaded_depths = read_cascade_depths(uploaded);

    // Both meshes in one vertex buffer of 24-byte vertices (position, then a normal this
    // test does not need), after 5 unused vertices; indices after 2 unused ones.
    struct Vertex {
        Vec3 position;
        Vec3 normal;
    };
    constexpr int32_t kFirstVertex = 5;
    std::vector<Vertex> vertices(kFirstVertex);
    for (const Vec3& p : ground.positions) vertices.push_back({p, {0, 1, 0}});
    for (const Vec3& p : box.positions) vertices.push_back({p, {0, 0, 0}});
    std::vector<uint16_t> indices(2, 0);
    for (uint32_t i : ground.indices) indices.push_back(static_cast<uint16_t>(i));
    for (uint32_t i : box.indices) indices.push_back(static_cast<uint16_t>(i + ground.positions.size()));
    HostBuffer vertex_buffer(device_, vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    HostBuffer index_buffer(device_, indices.size() * sizeof(uint16_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    std::memcpy(vertex_buffer.mapped, vertices.data(), vertices.size() * sizeof(Vertex));
    std::memcpy(index_buffer.mapped, indices.data(), indices.size() * sizeof(uint16_t));

    ShadowSystem caller(system_desc());
    MeshDesc ground_desc;
    ground_desc.positions = {vertex_buffer.buffer, 0, sizeof(Vertex), VK_FORMAT_R32G32B32_SFLOAT};
    ground_desc.index_buffer = index_buffer.buffer;
    ground_desc.index_offset = 2 * sizeof(uint16_t);
    ground_desc.index_type = VK_INDEX_TYPE_UINT16;
    ground_desc.index_count = static_cast<uint32_t>(ground.indices.size());
    ground_desc.vertex_offset = kFirstVertex;
    ground_desc.bounds = {{-20, 0, -20}, {20, 0, 20}};
    MeshDesc box_desc = ground_desc;
    box_desc.index_offset += ground.indices.size() * sizeof(uint16_t);
    box_desc.index_count = static_cast<uint32_t>(box.indices.size());
    box_desc.bounds = {{-1, -1, -1}, {1, 1, 1}};
    caller.add_instance({caller.add_mesh(ground_desc), Mat4{}});
    caller.add_instance({caller.add_mesh(box_desc), translation(kBoxCentre)});
    const LightDesc sun{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}};
    caller.set_lights({&sun, 1});
    EXPECT_EQ(render_visibility(caller).values, uploaded_visibility.values);
    EXPECT_TRUE(read_cascade_depths(caller) == uploaded_depths) << "the cascades' depth differ";

    // Half floats represent these coordinates exactly: the same maps again.
    std::vector<uint16_t> halves;
    const auto half = [](float value) -> uint16_t {
        // Exact for the small integers of these meshes (|value| <= 20).
        if (value == 0.0f) return 0;
        const uint16_t sign = value < 0.0f ? 0x8000 : 0;
        float magnitude = std::abs(value);
        int exponent = 0;
        while (magnitude >= 2.0f) {
            magnitude *= 0.5f;
            ++exponent;
        }
        const auto mantissa = static_cast<uint16_t>((magnitude - 1.0f) * 1024.0f);
        return static_cast<uint16_t>(sign | ((exponent + 15) << 10) | mantissa);
    };
    for (const Vertex& v : vertices)
        halves.insert(halves.end(), {half(v.position.x), half(v.position.y), half(v.position.z), half(1.0f)});
    HostBuffer half_buffer(device_, halves.size() * sizeof(uint16_t), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    std::memcpy(half_buffer.mapped, halves.data(), halves.size() * sizeof(uint16_t));
    ShadowSystem half_system(system_desc());
    ground_desc.positions = {half_buffer.buffer, 0, 8, VK_FORMAT_R16G16B16A16_SFLOAT};
    box_desc.positions = ground_desc.positions;
    half_system.add_instance({half_system.add_mesh(ground_desc), Mat4{}});
    half_system.add_instance({half_system.add_mesh(box_desc), translation(kBoxCentre)});
    half_system.set_lights({&sun, 1});
    EXPECT_EQ(render_visibility(half_system).values, uploaded_visibility.values);
    EXPECT_TRUE(read_cascade_depths(half_system) == uploaded_depths) << "half-float positions draw other depths";
}

// Three frames in flight: frames are recorded and submitted without waiting, up to the
// third; prepare() of frame F only needs frame F - 3 complete. The box moves every frame;
// synchronization validation watches every submission, and the last frame is checked.
TEST_F(ShadowSystemFrames, FramesInFlightOverlapWithoutHazards) {
    constexpr uint32_t kInFlight = 3;
    constexpr uint32_t kFrames = 7;
    ShadowSystem shadows(system_desc(test_settings(), kInFlight));
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    const InstanceId instance = add_scene(shadows, box, ground);

    std::vector<VkCommandBuffer> commands(kFrames);
    VkCommandBufferAllocateInfo allocate_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate_info.commandPool = pool_;
    allocate_info.commandBufferCount = kFrames;
    TEST_VK(vkAllocateCommandBuffers(device_.device, &allocate_info, commands.data()));
    std::vector<VkFence> fences(kFrames);
    for (VkFence& fence : fences) {
        const VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        TEST_VK(vkCreateFence(device_.device, &fence_info, nullptr, &fence));
    }
    // A new box for every frame; its (one) depth image is shared, so frames that resolve
    // visibility are serialised by a barrier on it, as a renderer's depth buffer would be.
    glm::vec3 centre = kBoxCentre;
    for (uint32_t frame = 0; frame < kFrames; ++frame) {
        if (frame >= kInFlight) {
            TEST_VK(vkWaitForFences(device_.device, 1, &fences[frame - kInFlight], VK_TRUE, UINT64_MAX));
        }
        centre = kBoxCentre + glm::vec3(0.25f * static_cast<float>(frame), 0.0f, -0.2f * static_cast<float>(frame));
        shadows.set_instance_transform(instance, translation(centre));
        shadows.prepare(top_down_view());
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        TEST_VK(vkBeginCommandBuffer(commands[frame], &begin));
        shadows.record_shadow_maps(commands[frame]);
        record_ground_visibility(commands[frame], shadows, nullptr, NormalEncoding::SignedFloat);
        TEST_VK(vkEndCommandBuffer(commands[frame]));
        VkCommandBufferSubmitInfo command{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
        command.commandBuffer = commands[frame];
        VkSubmitInfo2 submit_info{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
        submit_info.commandBufferInfoCount = 1;
        submit_info.pCommandBufferInfos = &command;
        TEST_VK(vkQueueSubmit2(device_.queue, 1, &submit_info, fences[frame]));
    }
    TEST_VK(vkQueueWaitIdle(device_.queue));
    expect_box_shadow(check_footprint(read_visibility(shadows, 0), centre, kSunDirection, kEdgeBand));
    for (VkFence fence : fences) vkDestroyFence(device_.device, fence, nullptr);
    vkFreeCommandBuffers(device_.device, pool_, kFrames, commands.data());
}

// A ShadowSystem destroyed while its frames are still in flight (issue 32, item 9): the
// destructor waits for the queue, so nothing is destroyed in use (the validation layer,
// which checks every destroy against the submissions not yet known complete, stays quiet)
// and the frames have completed when it returns.
TEST_F(ShadowSystemFrames, DestroyedWithFramesInFlightWaitsForThem) {
    constexpr uint32_t kFrames = 2;
    auto shadows = std::make_unique<ShadowSystem>(system_desc(test_settings(), kFrames));
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(*shadows, box, ground);
    std::vector<VkCommandBuffer> commands(kFrames);
    VkCommandBufferAllocateInfo allocate_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate_info.commandPool = pool_;
    allocate_info.commandBufferCount = kFrames;
    TEST_VK(vkAllocateCommandBuffers(device_.device, &allocate_info, commands.data()));
    const VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence last_frame = VK_NULL_HANDLE;
    TEST_VK(vkCreateFence(device_.device, &fence_info, nullptr, &last_frame));
    for (uint32_t frame = 0; frame < kFrames; ++frame) {
        shadows->prepare(top_down_view());
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        TEST_VK(vkBeginCommandBuffer(commands[frame], &begin));
        shadows->record_shadow_maps(commands[frame]);
        record_ground_visibility(commands[frame], *shadows, nullptr, NormalEncoding::SignedFloat);
        TEST_VK(vkEndCommandBuffer(commands[frame]));
        VkCommandBufferSubmitInfo command{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
        command.commandBuffer = commands[frame];
        VkSubmitInfo2 submit_info{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
        submit_info.commandBufferInfoCount = 1;
        submit_info.pCommandBufferInfos = &command;
        TEST_VK(vkQueueSubmit2(device_.queue, 1, &submit_info, frame + 1 == kFrames ? last_frame : VK_NULL_HANDLE));
    }
    shadows.reset();  // no wait by the caller
    EXPECT_EQ(vkGetFenceStatus(device_.device, last_frame), VK_SUCCESS);
    TEST_VK(vkQueueWaitIdle(device_.queue));  // what the layer needs to retire the submissions
    vkDestroyFence(device_.device, last_frame, nullptr);
    vkFreeCommandBuffers(device_.device, pool_, kFrames, commands.data());
}

// Timestamps switched off: no query is recorded (a frame's times are never there), and the
// same frames with them on do have times, where the queue can time.
TEST_F(ShadowSystemFrames, TimestampsSwitchedOffRecordNoTimes) {
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device_.physical_device, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(device_.physical_device, &family_count, families.data());
    const bool queue_times = families[device_.queue_family].timestampValidBits != 0;
    for (const bool timestamps : {false, true}) {
        ShadowSystemDesc desc = system_desc();
        desc.timestamps = timestamps;
        ShadowSystem shadows(desc);
        add_scene(shadows, box, ground);
        for (int f = 0; f < 3; ++f) render_visibility(shadows);
        for (uint64_t frame = 1; frame <= 3; ++frame) {
            EXPECT_EQ(shadows.gpu_times(frame).has_value(), timestamps && queue_times)
                << "frame " << frame << (timestamps ? ", timestamps on" : ", timestamps off");
        }
    }
}

// A renderer that keeps more frames in flight than the system was made for reaches a
// prepare() whose slot the GPU may still use. Made deterministic here with a frame that is
// recorded but held back: prepare() of the frame that reuses its slot is a UsageError
// naming frames_in_flight, changes nothing, and succeeds once that frame has completed.
TEST_F(ShadowSystemFrames, MoreFramesInFlightThanTheSystemAreNamed) {
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device_.physical_device, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(device_.physical_device, &family_count, families.data());
    if (families[device_.queue_family].timestampValidBits == 0) GTEST_SKIP() << "the check needs timestamps";
    ShadowSystem shadows(system_desc(test_settings(), 2));
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    render_visibility(shadows);  // frame 1: uploads, submitted and complete
    VkCommandBuffer held = VK_NULL_HANDLE;
    VkCommandBufferAllocateInfo allocate_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate_info.commandPool = pool_;
    allocate_info.commandBufferCount = 1;
    TEST_VK(vkAllocateCommandBuffers(device_.device, &allocate_info, &held));
    EXPECT_EQ(shadows.prepare(top_down_view()).frame, 2u);
    const VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    TEST_VK(vkBeginCommandBuffer(held, &begin));
    shadows.record_shadow_maps(held);  // frame 2: recorded, not submitted yet
    TEST_VK(vkEndCommandBuffer(held));
    render_visibility(shadows);  // frame 3 reuses frame 1's slot: complete
    try {
        shadows.prepare(top_down_view());  // frame 4 would reuse frame 2's
        ADD_FAILURE() << "prepare() rewrote the slot of a frame that has not completed";
    } catch (const UsageError& error) {
        EXPECT_NE(std::string(error.what()).find("frame 2, 2 frame(s) ago, has not completed"), std::string::npos)
            << error.what();
        EXPECT_NE(std::string(error.what()).find("ShadowSystemDesc::frames_in_flight is 2"), std::string::npos)
            << error.what();
    }
    VkCommandBufferSubmitInfo command{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    command.commandBuffer = held;
    VkSubmitInfo2 submit_info{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit_info.commandBufferInfoCount = 1;
    submit_info.pCommandBufferInfos = &command;
    TEST_VK(vkQueueSubmit2(device_.queue, 1, &submit_info, VK_NULL_HANDLE));
    TEST_VK(vkQueueWaitIdle(device_.queue));
    EXPECT_EQ(shadows.prepare(top_down_view()).frame, 4u) << "the failed prepare() changed nothing";
    EXPECT_TRUE(shadows.gpu_times(2).has_value());
    vkFreeCommandBuffers(device_.device, pool_, 1, &held);
}

// Caster face culling, seen from the sun above: a one-sided quad facing up shows its front
// to the light. BackFaces keeps it, FrontFaces drops it unless it is double-sided; the
// quad facing down is the other way round; None always draws.
TEST_F(ShadowSystemFrames, CasterCullingByFacingAndDoubleSidedFlag) {
    const MeshArrays ground = ground_mesh();
    const MeshArrays up = quad_mesh(true);
    const MeshArrays down = quad_mesh(false);
    const glm::vec3 height{0.0f, 3.0f, 0.0f};
    const auto shadowed_pixels = [&](CasterCulling culling, const MeshArrays& quad, uint32_t flags) {
        Settings settings = test_settings();
        settings.shadow.caster_culling = culling;
        ShadowSystem shadows(system_desc(settings));
        shadows.add_instance({shadows.add_mesh(ground.data()), Mat4{}});
        shadows.add_instance({shadows.add_mesh(quad.data()), translation(height), flags});
        const LightDesc sun{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}};
        shadows.set_lights({&sun, 1});
        const VisibilityImage2D image = render_visibility(shadows);
        return std::count_if(image.values.begin(), image.values.end(), [](float v) { return v < 0.5f; });
    };
    const uint32_t one_sided = kInstanceCastsShadows;
    const uint32_t two_sided = kInstanceCastsShadows | kInstanceDoubleSided;
    // A 2 x 2 m quad's shadow covers about 4 m^2 / (7.2 cm)^2 = 770 pixels.
    constexpr long kShadow = 600;
    EXPECT_GT(shadowed_pixels(CasterCulling::None, up, one_sided), kShadow);
    EXPECT_GT(shadowed_pixels(CasterCulling::None, down, one_sided), kShadow);
    EXPECT_GT(shadowed_pixels(CasterCulling::BackFaces, up, one_sided), kShadow);
    EXPECT_EQ(shadowed_pixels(CasterCulling::BackFaces, down, one_sided), 0);
    EXPECT_EQ(shadowed_pixels(CasterCulling::FrontFaces, up, one_sided), 0);
    EXPECT_GT(shadowed_pixels(CasterCulling::FrontFaces, down, one_sided), kShadow);
    EXPECT_GT(shadowed_pixels(CasterCulling::FrontFaces, up, two_sided), kShadow);
    EXPECT_GT(shadowed_pixels(CasterCulling::BackFaces, down, two_sided), kShadow);
}

// A point light above the box: its shadow is the box projected from the light, in the
// light's visibility slot (1: layer 0, green); the sun's slot is 0 (there is no sun).
TEST_F(ShadowSystemFrames, PointLightShadowInItsSlot) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    const glm::vec3 position{0.8f, 7.0f, 0.5f};
    LightDesc point{LightType::Point};
    point.position = {position.x, position.y, position.z};
    point.range = 30.0f;
    shadows.set_lights({&point, 1});
    const FrameInfo& info = shadows.prepare(top_down_view());
    ASSERT_EQ(info.local_shadows.size(), 1u);
    EXPECT_EQ(info.local_shadows[0].layers, 6u);
    EXPECT_EQ(info.local_shadows[0].slot, 1u);
    submit([&](VkCommandBuffer cmd) {
        shadows.record_shadow_maps(cmd);
        record_ground_visibility(cmd, shadows, nullptr, NormalEncoding::SignedFloat);
    });
    EXPECT_EQ(shadows.visibility_image().slots, 2u);
    expect_all_dark(read_visibility(shadows, 0));  // there is no sun
    const FootprintCheck check =
        check_footprint(read_visibility(shadows, 1), kBoxCentre, {0.0f, -1.0f, 0.0f}, kEdgeBand, position);
    EXPECT_GT(check.shadowed, 2000u);
    EXPECT_EQ(check.wrong, 0u);
    EXPECT_GE(check.iou, 0.97);
}

// Outside a spot's map (beyond its square field of view, twice the outer angle across) its
// shadow is defined: lit, whatever the map's edge holds. A slab 1 m above the ground covers the map's
// whole -X edge, so the edge texels are shadowed, and clamping to them (the behaviour
// before) darkened the ground outside the cone on that side.
TEST_F(ShadowSystemFrames, SpotShadowIsLitOutsideItsMap) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    shadows.add_instance({shadows.add_mesh(ground.data()), Mat4{}});
    const glm::mat4 slab = glm::scale(glm::translate(glm::mat4(1.0f), {-5.5f, 1.0f, 0.0f}), {4.5f, 0.05f, 8.0f});
    shadows.add_instance({shadows.add_mesh(box.data()), to_mat4(slab)});  // x in [-10, -1], y about 1
    const glm::vec3 position{0.0f, 8.0f, 0.0f};
    LightDesc spot{LightType::Spot, {0.0f, -1.0f, 0.0f}, {position.x, position.y, position.z}};
    spot.outer_angle_degrees = 20.0f;
    spot.inner_angle_degrees = 15.0f;
    spot.range = 20.0f;
    shadows.set_lights({&spot, 1});
    const FrameInfo& info = shadows.prepare(top_down_view());
    ASSERT_EQ(info.local_shadows.size(), 1u);
    ASSERT_EQ(info.local_shadows[0].layers, 1u) << "a perspective spot";
    submit([&](VkCommandBuffer cmd) {
        shadows.record_shadow_maps(cmd);
        record_ground_visibility(cmd, shadows, nullptr, NormalEncoding::SignedFloat);
    });
    const VisibilityImage2D image = read_visibility(shadows, 1);
    // The map is square, 2 x outer angle across: its corners reach further from the axis.
    const float map_corner_angle =
        glm::degrees(std::atan(std::sqrt(2.0f) * std::tan(glm::radians(spot.outer_angle_degrees))));
    size_t outside_under_slab = 0, inside_under_slab = 0, outside_lit = 0, outside = 0;
    for (uint32_t y = 0; y < image.height; ++y) {
        for (uint32_t x = 0; x < image.width; ++x) {
            const glm::vec3 point = ground_point(x, y);
            const float angle =
                glm::degrees(std::acos(glm::dot(glm::normalize(point - position), glm::vec3(0.0f, -1.0f, 0.0f))));
            const float value = image.at(x, y);
            if (angle > map_corner_angle + 1.0f) {  // a degree clear of the map's corners
                ++outside;
                outside_lit += value == 1.0f ? 1 : 0;
                outside_under_slab += point.x < -1.5f ? 1 : 0;
            } else if (angle < spot.outer_angle_degrees - 1.0f && point.x < -2.0f) {
                ++inside_under_slab;
                EXPECT_EQ(value, 0.0f) << "the slab shadows the cone at pixel " << x << ", " << y;
            }
        }
    }
    EXPECT_GT(inside_under_slab, 200u);
    EXPECT_GT(outside_under_slab, 2000u) << "the slab's side, where the map's edge is shadowed";
    EXPECT_EQ(outside_lit, outside) << "pixels outside the spot's map that are not lit";
}

// A ShaderSpecialization and its info() view storage the system owns: an info taken from a
// temporary, from an object since destroyed, or from a copy or a moved-to object all read
// the same, right constants. (The scribble reuses freed memory; under AddressSanitizer,
// scripts/sanitize.sh, any read of freed memory fails outright.)
TEST_F(ShadowSystemFrames, ShaderSpecializationInfoOutlivesCopiesAndMoves) {
    Settings settings = test_settings();
    settings.shadow.filter.mode = ShadowFilter::Pcss;
    ShadowSystem shadows(system_desc(settings));
    const VkSpecializationInfo from_temporary = shadows.shader_specialization(3).info();
    auto original = std::make_unique<ShaderSpecialization>(shadows.shader_specialization(3));
    const std::vector<VkSpecializationMapEntry> entries(original->entries.begin(), original->entries.end());
    const std::vector<uint32_t> data(original->data.begin(), original->data.end());
    ASSERT_EQ(entries.size(), 8u);
    ASSERT_EQ(data.size(), entries.size());
    const VkSpecializationInfo from_original = original->info();
    ShaderSpecialization copy = *original;
    ShaderSpecialization moved = std::move(*original);
    original.reset();
    std::vector<std::vector<uint32_t>> scribble;
    for (int i = 0; i < 64; ++i) scribble.emplace_back(data.size() * 4, 0xDEADBEEFu);
    for (const VkSpecializationInfo& info : {from_temporary, from_original, copy.info(), moved.info()}) {
        ASSERT_EQ(info.mapEntryCount, entries.size());
        ASSERT_EQ(info.dataSize, data.size() * sizeof(uint32_t));
        for (size_t i = 0; i < entries.size(); ++i) {
            EXPECT_EQ(info.pMapEntries[i].constantID, 3u + i) << "the ids start at first_constant_id";
            EXPECT_EQ(info.pMapEntries[i].offset, entries[i].offset);
            EXPECT_EQ(info.pMapEntries[i].size, sizeof(uint32_t));
            EXPECT_EQ(static_cast<const uint32_t*>(info.pData)[i], data[i]) << "constant " << i;
        }
    }
}

// Over the local shadow budget, the extra lights are listed as unshadowed.
TEST_F(ShadowSystemFrames, LightsOverTheBudgetAreReported) {
    Settings settings = test_settings();
    settings.local_shadows.budget = 1;
    ShadowSystem shadows(system_desc(settings));
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    std::vector<LightDesc> lights(3, LightDesc{LightType::Point});
    lights[0] = LightDesc{LightType::Directional};
    lights[1].position = {0.0f, 7.0f, 0.0f};
    lights[2].position = {3.0f, 7.0f, 0.0f};
    shadows.set_lights(lights);
    const FrameInfo& info = shadows.prepare(top_down_view());
    EXPECT_EQ(info.sun, 0u);
    ASSERT_EQ(info.local_shadows.size(), 1u);
    ASSERT_EQ(info.unshadowed_lights.size(), 1u);
    EXPECT_NE(info.local_shadows[0].light, info.unshadowed_lights[0]);
    submit([&](VkCommandBuffer cmd) { shadows.record_shadow_maps(cmd); });
}

// GPU time per pass, once the frame's submission is complete (when the queue has
// timestamps), and the memory of what the settings ask for.
TEST_F(ShadowSystemFrames, GpuTimesAndMemory) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    render_visibility(shadows);
    const uint64_t frame = shadows.prepare(top_down_view()).frame - 1;
    const std::optional<GpuTimes> times = shadows.gpu_times(frame);
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device_.physical_device, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(device_.physical_device, &family_count, families.data());
    if (families[device_.queue_family].timestampValidBits == 0) {
        EXPECT_FALSE(times.has_value());
    } else {
        ASSERT_TRUE(times.has_value());
        EXPECT_EQ(times->frame, frame);
        std::vector<std::string> names;
        for (const PassTime& pass : times->passes) {
            names.push_back(pass.name);
            EXPECT_GE(pass.milliseconds, 0.0) << pass.name;
        }
        const std::vector<std::string> expected{"shadow_cascade_0", "shadow_cascade_1", "shadow_cascade_2",
                                                "shadow_cascade_3", "visibility"};
        EXPECT_EQ(names, expected);
    }
    EXPECT_FALSE(shadows.gpu_times(frame + 5).has_value());
    const MemoryStats memory = shadows.memory();
    const uint64_t resolution = shadows.settings().shadow.cascades.resolution;
    const uint64_t depth_layers = resolution * resolution * 4 * 4;  // four D32 layers
    EXPECT_GE(memory.cascade_maps, depth_layers);
    EXPECT_LT(memory.cascade_maps, depth_layers + depth_layers / 8) << "more than the depth layers (alignment)";
    EXPECT_EQ(memory.local_maps, 0u);
    EXPECT_GE(memory.visibility, uint64_t{kScreen} * kScreen * 4);
    EXPECT_GT(memory.buffers, 0u);
    EXPECT_EQ(memory.total(), memory.cascade_maps + memory.local_maps + memory.visibility + memory.buffers);
}

// The usual engine loop: wait for a slot's fence, prepare() the frame that reuses the slot,
// then read the times of the frame just waited for. They are kept until 2 x frames_in_flight
// frames later, then gone.
TEST_F(ShadowSystemFrames, GpuTimesAfterThePrepareThatReusesTheSlot) {
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device_.physical_device, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(device_.physical_device, &family_count, families.data());
    if (families[device_.queue_family].timestampValidBits == 0) GTEST_SKIP() << "the queue has no timestamps";
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    const std::vector<std::string> expected{"shadow_cascade_0", "shadow_cascade_1", "shadow_cascade_2",
                                            "shadow_cascade_3", "visibility"};
    for (const uint32_t frames_in_flight : {1u, 2u}) {
        ShadowSystem shadows(system_desc(test_settings(), frames_in_flight));
        add_scene(shadows, box, ground);
        for (uint32_t f = 0; f < frames_in_flight; ++f) render_visibility(shadows);  // frames 1 .. frames_in_flight
        EXPECT_EQ(shadows.prepare(top_down_view()).frame, frames_in_flight + 1u) << "reuses frame 1's slot";
        const std::optional<GpuTimes> times = shadows.gpu_times(1);
        ASSERT_TRUE(times.has_value()) << frames_in_flight << " frame(s) in flight";
        EXPECT_EQ(times->frame, 1u);
        std::vector<std::string> names;
        for (const PassTime& pass : times->passes) {
            names.push_back(pass.name);
            EXPECT_GE(pass.milliseconds, 0.0) << pass.name;
        }
        EXPECT_EQ(names, expected) << frames_in_flight << " frame(s) in flight";
        for (uint32_t f = 0; f < 2 * frames_in_flight; ++f) render_visibility(shadows);
        EXPECT_TRUE(shadows.gpu_times(frames_in_flight + 2).has_value()) << "a recent frame's, kept";
        EXPECT_FALSE(shadows.gpu_times(1).has_value()) << "older than 2 x frames_in_flight";
    }
}

// An alpha-masked caster: a 2 x 2 m quad whose texture is transparent on its left half
// (u < 0.5). Flagged alpha-masked, an instance casts only its right half; the same mesh
// without the flag casts the whole quad, also when both are drawn in one pass (the masked
// draw then binds the mesh's UVs although the mesh was just bound for the opaque one).
TEST_F(ShadowSystemFrames, AlphaMaskedAndOpaqueInstancesOfOneMesh) {
    TestImage texture(device_, VK_FORMAT_R8G8B8A8_UNORM, 2, 1,
                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    HostBuffer staging(device_, 8, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    const uint8_t texels[8] = {255, 255, 255, 0, 255, 255, 255, 255};
    std::memcpy(staging.mapped, texels, sizeof(texels));
    submit([&](VkCommandBuffer cmd) {
        VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        barrier.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        barrier.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        barrier.image = texture.image;
        barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dependency.imageMemoryBarrierCount = 1;
        dependency.pImageMemoryBarriers = &barrier;
        vkCmdPipelineBarrier2(cmd, &dependency);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {2, 1, 1};
        vkCmdCopyBufferToImage(cmd, staging.buffer, texture.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        // Sampled by the shadow passes' fragment shaders (AlphaMaskDesc's contract).
        barrier.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        barrier.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        barrier.dstStageMask = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
        barrier.dstAccessMask = VK_ACCESS_2_SHADER_READ_BIT;
        barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        barrier.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        vkCmdPipelineBarrier2(cmd, &dependency);
    });
    VkSamplerCreateInfo sampler_info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sampler_info.magFilter = sampler_info.minFilter = VK_FILTER_NEAREST;
    sampler_info.addressModeU = sampler_info.addressModeV = sampler_info.addressModeW =
        VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VkSampler sampler = VK_NULL_HANDLE;
    TEST_VK(vkCreateSampler(device_.device, &sampler_info, nullptr, &sampler));

    const MeshArrays ground = ground_mesh();
    const MeshArrays quad = quad_mesh(true);
    std::vector<Vec2> uvs;
    for (const Vec3& p : quad.positions) uvs.push_back({(p.x + 1.0f) * 0.5f, (p.z + 1.0f) * 0.5f});
    const auto shadowed_pixels = [&](bool opaque_instance, bool masked_instance, ShadowStrategy strategy) {
        Settings settings = test_settings();
        settings.shadow.strategy = strategy;
        ShadowSystem shadows(system_desc(settings));
        shadows.add_instance({shadows.add_mesh(ground.data()), Mat4{}});
        MeshData data = quad.data();
        data.uvs = uvs;
        data.alpha_mask = AlphaMaskDesc{texture.view, sampler, 0.5f, 1.0f};
        const MeshId mesh = shadows.add_mesh(data);
        // Side by side, 3 m apart: their shadows do not overlap.
        if (opaque_instance) shadows.add_instance({mesh, translation({-2.0f, 3.0f, 0.0f}), kInstanceCastsShadows});
        if (masked_instance) {
            shadows.add_instance({mesh, translation({2.0f, 3.0f, 0.0f}), kInstanceCastsShadows | kInstanceAlphaMasked});
        }
        const LightDesc sun{LightType::Directional, {0.0f, -1.0f, 0.0f}};
        shadows.set_lights({&sun, 1});
        const VisibilityImage2D image = render_visibility(shadows);
        return std::count_if(image.values.begin(), image.values.end(), [](float v) { return v < 0.5f; });
    };
    // The layered strategy draws the opaque and the masked instance from two buckets of
    // GPU-culled commands, with the same alpha test.
    for (const ShadowStrategy strategy : {ShadowStrategy::PerCascade, ShadowStrategy::Layered}) {
        SCOPED_TRACE(choice_name(kShadowStrategyChoices, strategy));
        const long opaque = shadowed_pixels(true, false, strategy);
        const long masked = shadowed_pixels(false, true, strategy);
        // The whole quad: 4 m^2 at (7.2 cm)^2 per pixel, about 770 pixels; the mask keeps half.
        EXPECT_NEAR(static_cast<double>(opaque), 770.0, 80.0);
        EXPECT_NEAR(static_cast<double>(masked), 0.5 * static_cast<double>(opaque), 40.0);
        EXPECT_EQ(shadowed_pixels(true, true, strategy), opaque + masked);
    }
    vkDestroySampler(device_.device, sampler, nullptr);
}

// A mesh given as arrays and removed before any frame recorded its upload: the upload must
// not be recorded into the retired buffer (with one frame in flight the buffer is destroyed
// by the next prepare(); validation would report the copy into a destroyed buffer).
TEST_F(ShadowSystemFrames, MeshRemovedBeforeItsUploadIsNeverCopied) {
    ShadowSystem shadows(system_desc(test_settings(), 1));
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    const MeshId removed = shadows.add_mesh(box.data());
    shadows.remove_mesh(removed);
    expect_box_shadow(check_footprint(render_visibility(shadows), kBoxCentre, kSunDirection, kEdgeBand));
    EXPECT_GT(shadows.memory().buffers, 0u);
}

// A direction is a direction whatever its length: components of 1e30 or 1e-30 (finite,
// non-zero) cast the shadow of the unit vector (found by fuzz_shadow_system: the float
// length overflowed and prepare() threw a std::invalid_argument).
TEST_F(ShadowSystemFrames, HugeAndTinyDirectionsAreTheSameLight) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    const std::vector<float> unit = render_visibility(shadows).values;
    for (const float scale : {1e30f, 1e-30f}) {
        const LightDesc sun{LightType::Directional,
                            {kSunDirection.x * scale, kSunDirection.y * scale, kSunDirection.z * scale}};
        shadows.set_lights({&sun, 1});
        EXPECT_EQ(render_visibility(shadows).values, unit) << scale;
    }
}

// ViewDesc::sampling_frame: by default the Poisson and PCSS patterns rotate every frame
// (the penumbra's pixels change between two identical frames); a fixed sampling frame
// gives bit-identical frames, and the same rotation as the frame number it names.
TEST_F(ShadowSystemFrames, FixedSamplingFrameStillsTheRotatingPatterns) {
    for (const ShadowFilter filter : {ShadowFilter::Poisson, ShadowFilter::Pcss}) {
        Settings settings = test_settings();
        settings.shadow.filter.mode = filter;
        ShadowSystem shadows(system_desc(settings));
        const MeshArrays box = box_mesh();
        const MeshArrays ground = ground_mesh();
        add_scene(shadows, box, ground);
        const auto render_with = [&](std::optional<uint32_t> sampling_frame) {
            ViewDesc view = top_down_view();
            view.sampling_frame = sampling_frame;
            shadows.prepare(view);
            submit([&](VkCommandBuffer cmd) {
                shadows.record_shadow_maps(cmd);
                record_ground_visibility(cmd, shadows, nullptr, NormalEncoding::SignedFloat);
            });
            return read_visibility(shadows, 0).values;
        };
        const std::vector<float> frame_0 = render_with(std::nullopt);  // frame number 0
        const std::vector<float> frame_1 = render_with(std::nullopt);
        EXPECT_NE(frame_0, frame_1) << "the pattern rotates from frame to frame";
        EXPECT_EQ(render_with(0u), frame_0);
        EXPECT_EQ(render_with(0u), frame_0);
        EXPECT_EQ(render_with(1u), frame_1);
    }
}

}  // namespace
}  // namespace penumbra::library_tests
