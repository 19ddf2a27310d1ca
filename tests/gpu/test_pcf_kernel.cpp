// The pcf kernel (penumbra/glsl/pcf.glsl) reads the (2R+1)^2 grid of bilinear comparison
// taps as (R+1)^2 weighted taps. Run on the device (tests/gpu/shaders/pcf_kernel_probe.comp),
// its taps must give every texel of the (2R+2) texels per axis exactly the plain grid's
// weight: 1 - f for the first, 1 between, f for the last; and each tap must fall between
// the two texels it stands for, so that it reads nothing else. Renders with and without
// receiver-plane bias are compared with the plain grid in the 2026-11-25 closing note
// (identical without it; with it, the plane is taken at each merged tap).
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <vector>

#include "penumbra/gpu/barriers.hpp"
#include "penumbra/gpu/pipeline.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/settings.hpp"
#include "renderer/app_context.hpp"
#include "test_shaders.hpp"

namespace penumbra::testing {
namespace {

constexpr int kPositions = 64;
constexpr int kStride = 2 * (kMaxPcfRadius + 1);

std::vector<float> run_probe(std::vector<std::string>& messages) {
    VulkanContextOptions options;
    options.validation = true;
    std::vector<float> values(size_t{kPositions} * (kMaxPcfRadius + 1) * kStride);
    {
        const renderer::AppContext context(options);
        const gpu::Buffer buffer = gpu::create_buffer(
            context, values.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::HostReadback);
        const VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT,
                                                   nullptr};
        const gpu::UniqueDescriptorSetLayout set_layout = gpu::create_descriptor_set_layout(context, {&binding, 1});
        const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
        const gpu::UniqueDescriptorPool pool = gpu::create_descriptor_pool(context, 1, {&size, 1});
        const VkDescriptorSet set = gpu::allocate_descriptor_set(context, pool, set_layout);
        gpu::write_storage_buffer(context, set, 0, buffer.get(), buffer.size);
        const VkDescriptorSetLayout layouts[] = {set_layout};
        const gpu::UniquePipelineLayout layout = gpu::create_pipeline_layout(context, layouts, {});
        const gpu::UniquePipeline pipeline = gpu::create_compute_pipeline(
            context, {VK_SHADER_STAGE_COMPUTE_BIT, shaders::pcf_kernel_probe_comp(), {}}, layout);
        context.submit_and_wait([&](VkCommandBuffer cmd) {
            context->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
            context->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
            context->vkCmdDispatch(cmd, kMaxPcfRadius + 1, 1, 1);
            gpu::memory_barrier(context, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                                VK_ACCESS_2_HOST_READ_BIT);
        });
        std::memcpy(values.data(), buffer.mapped, values.size() * sizeof(float));
    }
    messages = options.validation_log->messages;
    return values;
}

TEST(PcfKernel, MergedTapsWeighEveryTexelAsThePlainGrid) {
    std::vector<std::string> messages;
    const std::vector<float> values = run_probe(messages);
    EXPECT_TRUE(messages.empty()) << messages.front();
    for (int radius = 0; radius <= kMaxPcfRadius; ++radius) {
        for (int k = 0; k < kPositions; ++k) {
            const float f = static_cast<float>(k) / kPositions;
            const float* taps = &values[(size_t{static_cast<size_t>(radius)} * kPositions + k) * kStride];
            // Texel t (relative to the texel centre before the receiver) in [-R, R + 1].
            std::vector<double> texel_weight(2 * radius + 2, 0.0);
            double total = 0.0;
            for (int tap = 0; tap <= radius; ++tap) {
                const int first = 2 * tap - radius;
                const double weight = taps[kMaxPcfRadius + 1 + tap];
                // The tap's place past the first texel's centre: between the pair, inclusive.
                const double between = taps[tap] + f - first;
                ASSERT_GE(between, -1e-6) << "R " << radius << " f " << f << " tap " << tap;
                ASSERT_LE(between, 1.0 + 1e-6) << "R " << radius << " f " << f << " tap " << tap;
                texel_weight[first + radius] += weight * (1.0 - between);
                texel_weight[first + radius + 1] += weight * between;
                total += weight;
            }
            EXPECT_NEAR(total, 2 * radius + 1, 1e-5);
            for (int t = -radius; t <= radius + 1; ++t) {
                const double expected = t == -radius ? 1.0 - f : (t == radius + 1 ? f : 1.0);
                EXPECT_NEAR(texel_weight[t + radius], expected, 1e-5) << "R " << radius << " f " << f << " texel " << t;
            }
        }
    }
}

}  // namespace
}  // namespace penumbra::testing
