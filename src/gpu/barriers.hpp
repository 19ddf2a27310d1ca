#pragma once
// Image state transitions from declared usage (synchronization2). Passes declare the
// state an image must be in; the stage, access mask and layout of each state live
// here, in one table, instead of hand-written barriers throughout the code.
#include <vulkan/vulkan.h>

#include "gpu/resources.hpp"

namespace penumbra::gpu {

enum class ImageState {
    Undefined,
    TransferDst,
    TransferSrc,
    ColorAttachment,
    DepthAttachment,
    FragmentSampled,  // read by fragment shaders (textures, shadow maps)
};

// Records one image memory barrier covering every layer of `image`.
void transition(VkCommandBuffer cmd, const Image& image, ImageState from, ImageState to);

// Makes transfer writes to host-visible buffers visible to the host after the fence.
void transfer_to_host_barrier(VkCommandBuffer cmd);

}  // namespace penumbra::gpu
