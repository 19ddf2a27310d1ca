#pragma once
// One primary command buffer and one fence that are reused for every frame, so that
// rendering many frames allocates nothing per frame (Context::submit_and_wait is for
// one-off uploads and allocates a command buffer and a fence each call).
#include <vulkan/vulkan.h>

#include <functional>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/handle.hpp"

namespace penumbra::gpu {

class FrameCommands {
public:
    explicit FrameCommands(const Device& device);

    // Resets the command buffer, records into it, submits it and waits for the fence.
    // The previous frame has always completed before the next one starts recording.
    void submit_and_wait(const std::function<void(VkCommandBuffer)>& record);

private:
    const Device& device_;
    UniqueCommandPool pool_;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;  // freed with the pool
    UniqueFence fence_;
};

}  // namespace penumbra::gpu
