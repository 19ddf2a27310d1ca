// Uses the installed Vulkan helper component the way the penumbra tools' renderer does:
// a gpu::Device viewing the device of a VulkanContext, an RAII buffer, one-off commands
// and a host barrier. Uploads a pattern, copies it on the GPU into a readback buffer and
// checks every word on the host.
// Exit codes: 0 the words are right and the validation layer said nothing, 1 otherwise.
#include <cstdint>
#include <cstdio>
#include <exception>
#include <span>
#include <vector>

#include "penumbra/gpu/barriers.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/features.hpp"
#include "penumbra/gpu/one_time_commands.hpp"
#include "penumbra/gpu/resources.hpp"
#include "penumbra/penumbra.hpp"

namespace {

constexpr uint32_t kWords = 1024;
constexpr uint32_t kPattern = 0x2a5a7e01;

penumbra::gpu::EnabledFeatures features_of(const penumbra::DeviceDesc& desc) {
    const penumbra::gpu::FeatureChain chain = penumbra::gpu::read_feature_chain(*desc.enabled_features);
    return {chain.multiview, chain.depth_clamp, chain.depth_bias_clamp, chain.gpu_driven()};
}

// Uploads a pattern into a device-local buffer, copies it back into a readback buffer and
// returns the number of words that differ.
uint32_t wrong_words(const penumbra::VulkanContext& context) {
    const penumbra::DeviceDesc& desc = context.device_desc();
    const penumbra::gpu::Device device(
        {desc.instance, desc.physical_device, desc.device, desc.queue, desc.queue_family}, features_of(desc),
        desc.get_instance_proc_addr);
    const penumbra::gpu::OneTimeCommands commands(device);
    std::vector<uint32_t> pattern(kWords);
    for (uint32_t i = 0; i < kWords; ++i) pattern[i] = kPattern ^ (i * 2654435761u);
    const penumbra::gpu::Buffer uploaded = penumbra::gpu::create_buffer_with_data(
        commands, std::as_bytes(std::span(pattern)), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    const penumbra::gpu::Buffer readback = penumbra::gpu::create_buffer(
        device, kWords * sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT, penumbra::gpu::MemoryKind::HostReadback);
    commands.submit_and_wait([&](VkCommandBuffer cmd) {
        const VkBufferCopy region{0, 0, kWords * sizeof(uint32_t)};
        device->vkCmdCopyBuffer(cmd, uploaded.get(), readback.get(), 1, &region);
        penumbra::gpu::transfer_to_host_barrier(device, cmd);
    });
    const auto* words = static_cast<const uint32_t*>(readback.mapped);
    uint32_t wrong = 0;
    for (uint32_t i = 0; i < kWords; ++i) wrong += words[i] != pattern[i] ? 1 : 0;
    return wrong;
}

}  // namespace

int main() {
    try {
        penumbra::VulkanContextOptions options;
        options.validation = true;
        const std::shared_ptr<penumbra::ValidationLog> log = options.validation_log;
        uint32_t wrong = 0;
        {
            const penumbra::VulkanContext context(options);
            wrong = wrong_words(context);
        }
        for (const std::string& message : log->messages) std::fprintf(stderr, "validation: %s\n", message.c_str());
        std::printf("%u of %u words wrong\n", wrong, kWords);
        return wrong == 0 && log->messages.empty() ? 0 : 1;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "gpu_component: %s\n", error.what());
        return 1;
    }
}
