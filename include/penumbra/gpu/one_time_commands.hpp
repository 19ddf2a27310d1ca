#pragma once
// One-off command buffers on a device's queue: record, submit, wait (uploads of textures
// and buffers by the tools, which own their queue). The library never submits; this is
// for callers that do.
#include <vulkan/vulkan.h>

#include <functional>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/handle.hpp"

namespace penumbra::gpu {

class OneTimeCommands {
public:
    explicit OneTimeCommands(const Device& device);

    const Device& device() const { return device_; }

    // Records commands into a fresh primary command buffer, submits it and waits.
    void submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const;

private:
    const Device& device_;
    UniqueCommandPool pool_;
};

}  // namespace penumbra::gpu
