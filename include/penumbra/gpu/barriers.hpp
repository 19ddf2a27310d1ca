#pragma once
// Image state transitions from declared usage (synchronization2). Passes declare the
// state an image must be in; the stage, access mask and layout of each state live
// here, in one table, instead of hand-written barriers throughout the code.
#include <vulkan/vulkan.h>

#include "penumbra/gpu/resources.hpp"

namespace penumbra::gpu {

enum class ImageState {
    Undefined,
    TransferDst,
    TransferSrc,
    ColorAttachment,
    DepthAttachment,
    // A finished depth buffer, read-only: tested by later passes (depth writes off) and
    // sampled by fragment and compute shaders (a depth pre-pass that a compute pass reads).
    DepthReadOnly,
    FragmentSampled,  // read by fragment shaders (textures, shadow maps)
    // Read by fragment and compute shaders: a ShadowSystem's maps between frames (the
    // caller's forward shading or the compute resolve reads them).
    ShaderSampled,
    // About to be overwritten completely after ShaderSampled reads (a map re-rendered every
    // frame): the contents are discarded, the reads of earlier frames still come first.
    DiscardAfterShaderReads,
    // The same two on a compute-only queue (async compute), whose barriers name no graphics
    // stage: read by compute shaders, and overwritten after such reads.
    ComputeSampled,
    DiscardAfterComputeReads,
    ComputeStorageWrite,  // written by a compute shader as a storage image
    ComputeStorage,       // read and written by compute shaders as a storage image
    BlitSrc,              // read by vkCmdBlitImage
    BlitDst,              // written by vkCmdBlitImage
    // A swapchain image just acquired: undefined contents, and the submission waits for
    // the acquire semaphore at ALL_COMMANDS, which this state's stage chains with.
    SwapchainAcquired,
    PresentSrc,  // handed to the presentation engine (which waits on a semaphore)
};

// Records one image memory barrier covering every layer of `image`.
void transition(const Device& device, VkCommandBuffer cmd, const Image& image, ImageState from, ImageState to);
// The same for an image the caller does not own as an Image (swapchain images): one
// mip level, layers [0, layers).
void transition(const Device& device, VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, uint32_t layers,
                ImageState from, ImageState to);

// A global memory dependency (buffers: uploads before their use as vertices, indices).
void memory_barrier(const Device& device, VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage,
                    VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access);

// Makes transfer writes to host-visible buffers visible to the host after the fence.
void transfer_to_host_barrier(const Device& device, VkCommandBuffer cmd);

}  // namespace penumbra::gpu
