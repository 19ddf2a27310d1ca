#pragma once
// Buffers and images with their memory, as move-only RAII values, plus the factory
// helpers for the kinds Penumbra uses (vertex/index/uniform buffers, readback
// buffers, colour and depth render targets, layered shadow maps, textures).
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/handle.hpp"
#include "penumbra/gpu/one_time_commands.hpp"

namespace penumbra::gpu {

enum class MemoryKind {
    DeviceLocal,  // GPU-only; filled through a staging copy
    HostUpload,   // host-visible and coherent, persistently mapped (uniforms, staging)
    HostReadback  // host-visible, cached where possible, persistently mapped (readback)
};

// The device memory an image or buffer is bound to, given back to the allocator it came
// from (Device::allocator()) when destroyed.
class BoundMemory {
public:
    BoundMemory() = default;
    BoundMemory(DeviceMemoryAllocator& allocator, const MemoryAllocation& allocation)
        : allocator_(&allocator), allocation_(allocation) {}
    ~BoundMemory() { reset(); }
    BoundMemory(BoundMemory&& other) noexcept
        : allocator_(std::exchange(other.allocator_, nullptr)), allocation_(other.allocation_) {}
    BoundMemory& operator=(BoundMemory&& other) noexcept {
        if (this != &other) {
            reset();
            allocator_ = std::exchange(other.allocator_, nullptr);
            allocation_ = other.allocation_;
        }
        return *this;
    }
    BoundMemory(const BoundMemory&) = delete;
    BoundMemory& operator=(const BoundMemory&) = delete;

    VkDeviceMemory memory() const { return allocation_.memory; }
    VkDeviceSize offset() const { return allocation_.offset; }
    void* mapped() const { return allocation_.mapped; }

private:
    void reset() noexcept {
        if (allocator_) allocator_->free(allocation_);
        allocator_ = nullptr;
    }

    DeviceMemoryAllocator* allocator_ = nullptr;
    MemoryAllocation allocation_;
};

// Members in this order so that the buffer or image is destroyed before its memory is
// given back (and possibly bound to something else).
struct Buffer {
    BoundMemory memory;
    UniqueBuffer buffer;
    VkDeviceSize size = 0;
    void* mapped = nullptr;  // non-null for host-visible kinds

    VkBuffer get() const { return buffer.get(); }
};

Buffer create_buffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryKind kind);

// Creates a device-local buffer holding `bytes` (copied through a staging buffer, submitted
// and waited for on the queue of `commands`).
Buffer create_buffer_with_data(const OneTimeCommands& commands, std::span<const std::byte> bytes,
                               VkBufferUsageFlags usage);

struct ImageDesc {
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    uint32_t width = 1;
    uint32_t height = 1;
    uint32_t layers = 1;
    VkImageUsageFlags usage = 0;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    bool array_view = false;  // view the image as a 2D array even with one layer
    // One 2D view per layer of a layered image, for rendering into one layer at a time (an
    // image drawn into through gl_Layer, e.g. the virtual shadow map's pool, needs none).
    bool layer_views = true;
    // A size-compatible format to write the image through as a storage image (e.g.
    // R32G32_UINT for R16G16B16A16_UNORM): the image is created mutable, Image::storage_view
    // views every layer in it, and the other views are not storage views.
    VkFormat storage_view_format = VK_FORMAT_UNDEFINED;
};

struct Image {
    BoundMemory memory;
    UniqueImage image;
    UniqueImageView view;                      // all layers
    std::vector<UniqueImageView> layer_views;  // one 2D view per layer (layered, with ImageDesc::layer_views)
    UniqueImageView storage_view;              // with ImageDesc::storage_view_format: a 2D array view in it
    ImageDesc desc;
    VkDeviceSize memory_size = 0;  // bytes of its allocation (what it costs in GPU memory)

    VkImage get() const { return image.get(); }
    VkExtent2D extent() const { return {desc.width, desc.height}; }
};

Image create_image(const Device& device, const ImageDesc& desc);

// Clears every layer of a depth image with attachment usage (whatever it held) to `depth`
// and leaves it ShaderSampled: a map that is bound but has nothing drawn into it yet gets
// defined contents rather than being made readable from undefined ones.
void record_depth_clear_to_sampled(const Device& device, VkCommandBuffer cmd, const Image& image, float depth);

// An RGBA8 sRGB texture with the given pixels, ready for sampling (SHADER_READ_ONLY).
Image create_texture_rgba8(const OneTimeCommands& commands, uint32_t width, uint32_t height,
                           std::span<const uint8_t> rgba);

}  // namespace penumbra::gpu
