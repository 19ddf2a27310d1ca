// Async compute (DeviceDesc::compute_queue_family, record_visibility_async()): the resolve
// recorded on a compute-only queue, with the caller's depth and visibility target handed
// between the families by ownership transfers and the queues ordered by semaphores, gives
// the graphics queue's image bit for bit, for both techniques and over several frames, with
// the validation layer's synchronization checks clean. Needs a device with a compute-only
// queue family (a discrete GPU; lavapipe has one family, so there it is skipped); the
// errors of a bad compute family and of the call without one are checked everywhere.
#include <string>
#include <utility>
#include <vector>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

// One image ownership barrier: the release half (on the queue of `from`) or the acquire half
// (on the queue of `to`), the same layouts in both (Vulkan spec, "Queue Family Ownership
// Transfer").
void ownership_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout old_layout,
                       VkImageLayout new_layout, uint32_t from, uint32_t to, bool release, VkPipelineStageFlags2 stage,
                       VkAccessFlags2 access) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    // The release's second scope and the acquire's first are ignored: NONE.
    barrier.srcStageMask = release ? stage : VK_PIPELINE_STAGE_2_NONE;
    barrier.srcAccessMask = release ? access : VK_ACCESS_2_NONE;
    barrier.dstStageMask = release ? VK_PIPELINE_STAGE_2_NONE : stage;
    barrier.dstAccessMask = release ? VK_ACCESS_2_NONE : access;
    barrier.oldLayout = old_layout;
    barrier.newLayout = new_layout;
    barrier.srcQueueFamilyIndex = from;
    barrier.dstQueueFamilyIndex = to;
    barrier.image = image;
    barrier.subresourceRange = {aspect, 0, 1, 0, 1};
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

class AsyncComputeTest : public LibraryTest {
protected:
    bool async_compute() const override { return true; }

    void SetUp() override {
        LibraryTest::SetUp();
        if (device_.compute_queue_family == VK_QUEUE_FAMILY_IGNORED) return;
        VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool_info.queueFamilyIndex = device_.compute_queue_family;
        TEST_VK(vkCreateCommandPool(device_.device, &pool_info, nullptr, &compute_pool_));
        for (VkSemaphore& semaphore : semaphores_) {
            const VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
            TEST_VK(vkCreateSemaphore(device_.device, &info, nullptr, &semaphore));
        }
    }

    void TearDown() override {
        if (context_) vkDeviceWaitIdle(device_.device);
        for (VkSemaphore semaphore : semaphores_) vkDestroySemaphore(device_.device, semaphore, nullptr);
        if (compute_pool_) vkDestroyCommandPool(device_.device, compute_pool_, nullptr);
        LibraryTest::TearDown();
    }

    // LibraryTest::submit_on(), the buffer freed by wait_and_free().
    void submit_on(VkQueue queue, VkCommandPool pool, VkSemaphore wait, VkPipelineStageFlags2 wait_stage,
                   VkSemaphore signal, const std::function<void(VkCommandBuffer)>& record) {
        recorded_.push_back({pool, LibraryTest::submit_on(queue, pool, wait, wait_stage, signal, record)});
    }

    void wait_and_free() {
        TEST_VK(vkDeviceWaitIdle(device_.device));
        for (const auto& [pool, cmd] : recorded_) vkFreeCommandBuffers(device_.device, pool, 1, &cmd);
        recorded_.clear();
    }

    // A frame with the resolve on the compute queue: the shadow maps and the depth on the
    // graphics queue, the depth handed over, the resolve into `target`, the target handed
    // back and copied out on the graphics queue. Returns the sun's visibility.
    VisibilityImage2D render_async(ShadowSystem& shadows, const ViewDesc& view, const TestImage& target) {
        const uint32_t graphics = device_.queue_family;
        const uint32_t compute = device_.compute_queue_family;
        shadows.prepare(view);
        ScreenInputs screen;
        submit_on(device_.queue, pool_, VK_NULL_HANDLE, VK_PIPELINE_STAGE_2_NONE, semaphores_[0],
                  [&](VkCommandBuffer cmd) {
                      screen = record_ground_depth(cmd, view, nullptr, NormalEncoding::SignedFloat, nullptr);
                      shadows.record_page_marking(cmd, screen);
                      shadows.record_shadow_maps(cmd);
                      // The depth's clear (and the marking's reads) go to the compute family.
                      ownership_barrier(cmd, depth_->image, VK_IMAGE_ASPECT_DEPTH_BIT,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, graphics, compute, true,
                                        VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                        VK_ACCESS_2_TRANSFER_WRITE_BIT);
                  });
        const VisibilityTarget visibility_target{target.image, target.view, VK_FORMAT_R8G8B8A8_UNORM,
                                                 kScreen,      kScreen,     1};
        submit_on(device_.compute_queue, compute_pool_, semaphores_[0], VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  semaphores_[1], [&](VkCommandBuffer cmd) {
                      ownership_barrier(cmd, depth_->image, VK_IMAGE_ASPECT_DEPTH_BIT,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, graphics, compute, false,
                                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);
                      shadows.record_visibility_async(cmd, screen, visibility_target);
                      // The visibility goes back to the graphics family, to be copied there.
                      ownership_barrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                        compute, graphics, true, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                        VK_ACCESS_2_NONE);
                  });
        HostBuffer readback(device_, VkDeviceSize{kScreen} * kScreen * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        submit_on(device_.queue, pool_, semaphores_[1], VK_PIPELINE_STAGE_2_COPY_BIT, VK_NULL_HANDLE,
                  [&](VkCommandBuffer cmd) {
                      ownership_barrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                        compute, graphics, false, VK_PIPELINE_STAGE_2_COPY_BIT,
                                        VK_ACCESS_2_TRANSFER_READ_BIT);
                      VkBufferImageCopy region{};
                      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                      region.imageExtent = {kScreen, kScreen, 1};
                      vkCmdCopyImageToBuffer(cmd, target.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer,
                                             1, &region);
                      host_read_barrier(cmd);
                  });
        wait_and_free();
        VisibilityImage2D result{kScreen, kScreen, std::vector<float>(size_t{kScreen} * kScreen)};
        const auto* rgba = static_cast<const uint8_t*>(readback.mapped);
        for (size_t i = 0; i < result.values.size(); ++i) result.values[i] = rgba[4 * i] / 255.0f;
        return result;
    }

    VkCommandPool compute_pool_ = VK_NULL_HANDLE;
    VkSemaphore semaphores_[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
    std::vector<std::pair<VkCommandPool, VkCommandBuffer>> recorded_;
};

TEST_F(AsyncComputeTest, TheResolveOnAComputeQueueEqualsTheGraphicsQueues) {
    if (device_.compute_queue_family == VK_QUEUE_FAMILY_IGNORED) {
        GTEST_SKIP() << "the device has no compute-only queue family (lavapipe has one family)";
    }
    for (const ShadowTechnique technique : {ShadowTechnique::Cascades, ShadowTechnique::Virtual}) {
        Settings settings = test_settings();
        settings.shadow.technique = technique;
        settings.shadow.virtual_maps.pool_mib = 16;
        settings.shadow.filter.mode = ShadowFilter::Pcf;
        ShadowSystem async(system_desc(settings));
        ShadowSystem graphics_only(system_desc(settings));
        const MeshArrays box = box_mesh(), ground = ground_mesh();
        add_scene(async, box, ground);
        add_scene(graphics_only, box, ground);
        const TestImage target(
            device_, VK_FORMAT_R8G8B8A8_UNORM, kScreen, kScreen,
            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
            VK_IMAGE_ASPECT_COLOR_BIT, 1);
        for (int f = 0; f < 3; ++f) {
            ViewDesc view = top_down_view_at(0.4f * static_cast<float>(f), 0.0f);
            view.sampling_frame = 0;
            const VisibilityImage2D expected = render_visibility_from(graphics_only, view);
            const VisibilityImage2D actual = render_async(async, view, target);
            EXPECT_EQ(differing_pixels(expected, actual), 0u)
                << (technique == ShadowTechnique::Virtual ? "virtual" : "cascades") << ", frame " << f;
            if (f == 0) expect_box_shadow_of_the_sun(actual);  // the top-down view itself
        }
    }
}

TEST_F(AsyncComputeTest, ABadComputeFamilyAndTheCallWithoutOneAreNamed) {
    ShadowSystemDesc desc = system_desc();
    desc.device.compute_queue_family = 99;
    expect_error<InputError>([&] { ShadowSystem shadows(desc); }, "DeviceDesc::compute_queue_family 99 does not exist");
    desc.device.compute_queue_family = desc.device.queue_family;
    expect_error<InputError>([&] { ShadowSystem shadows(desc); }, "is queue_family itself");
    if (device_.compute_queue_family != VK_QUEUE_FAMILY_IGNORED) {
        desc.device = device_;
        desc.device.compute_queue = VK_NULL_HANDLE;
        expect_error<InputError>([&] { ShadowSystem shadows(desc); }, "DeviceDesc::compute_queue is null");
    }

    desc.device = device_;
    desc.device.compute_queue_family = VK_QUEUE_FAMILY_IGNORED;
    desc.device.compute_queue = VK_NULL_HANDLE;
    ShadowSystem shadows(desc);
    const MeshArrays box = box_mesh(), ground = ground_mesh();
    add_scene(shadows, box, ground);
    const TestImage target(device_, VK_FORMAT_R8G8B8A8_UNORM, kScreen, kScreen,
                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_COLOR_BIT, 1);
    shadows.prepare(top_down_view());
    submit([&](VkCommandBuffer cmd) {
        const ScreenInputs screen =
            record_ground_depth(cmd, top_down_view(), nullptr, NormalEncoding::SignedFloat, nullptr);
        shadows.record_shadow_maps(cmd);
        expect_error<UsageError>(
            [&] {
                shadows.record_visibility_async(
                    cmd, screen, {target.image, target.view, VK_FORMAT_R8G8B8A8_UNORM, kScreen, kScreen, 1});
            },
            "ShadowSystem::record_visibility_async: the ShadowSystem was made without "
            "DeviceDesc::compute_queue_family");
        shadows.record_visibility(cmd, screen);  // the frame still resolves on the graphics queue
    });
    EXPECT_EQ(shadows.visibility_image().width, kScreen);
}

}  // namespace
}  // namespace penumbra::library_tests
