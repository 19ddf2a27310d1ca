#include "penumbra/gpu/resources.hpp"
#include "penumbra/gpu/debug_names.hpp"

#include <cstring>
#include <string>

#include "penumbra/errors.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra/gpu/check.hpp"

namespace penumbra::gpu {
namespace {

VkMemoryPropertyFlags memory_properties(MemoryKind kind) {
    switch (kind) {
        case MemoryKind::DeviceLocal:
            return VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
        case MemoryKind::HostUpload:
        case MemoryKind::HostReadback:
            return VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    }
    return 0;
}

// Memory for an image or buffer from the device's allocator, checked as the contract of
// DeviceMemoryAllocator says.
BoundMemory allocate(const Device& device, const VkMemoryRequirements& requirements, VkMemoryPropertyFlags properties,
                     bool host_access, bool linear) {
    MemoryRequest request;
    request.requirements = requirements;
    request.required_properties = properties;
    request.host_access = host_access;
    request.linear = linear;
    request.purpose = device.object_purpose().c_str();
    const MemoryAllocation allocation = device.allocator().allocate(request);
    const std::string what = std::to_string(requirements.size) + " bytes for " + device.object_purpose();
    if (allocation.memory == VK_NULL_HANDLE) {
        throw DeviceError("DeviceMemoryAllocator::allocate returned no memory (" + what + ")");
    }
    BoundMemory bound(device.allocator(), allocation);
    if (requirements.alignment > 1 && allocation.offset % requirements.alignment != 0) {
        throw UsageError("DeviceMemoryAllocator::allocate returned offset " + std::to_string(allocation.offset) +
                         ", not a multiple of the alignment " + std::to_string(requirements.alignment) + " (" + what +
                         ")");
    }
    if (host_access && allocation.mapped == nullptr) {
        throw UsageError("DeviceMemoryAllocator::allocate returned no host address for memory the host accesses (" +
                         what + ")");
    }
    return bound;
}

UniqueImageView create_view(const Device& device, VkImage image, const ImageDesc& desc, VkImageViewType type,
                            uint32_t base_layer, uint32_t layer_count, bool storage_view = false) {
    VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    // A mutable image's views: the storage view alone is a storage view (its format is the
    // one that supports it).
    VkImageViewUsageCreateInfo usage{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
    if (desc.storage_view_format != VK_FORMAT_UNDEFINED) {
        usage.usage = storage_view ? VkImageUsageFlags{VK_IMAGE_USAGE_STORAGE_BIT}
                                   : desc.usage & ~VkImageUsageFlags{VK_IMAGE_USAGE_STORAGE_BIT};
        info.pNext = &usage;
    }
    info.image = image;
    info.viewType = type;
    info.format = storage_view ? desc.storage_view_format : desc.format;
    info.subresourceRange = {desc.aspect, 0, 1, base_layer, layer_count};
    VkImageView view = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkCreateImageView(device, &info, nullptr, &view));
    name_object(device, VK_OBJECT_TYPE_IMAGE_VIEW, view, "image view");
    return UniqueImageView(device, view);
}

// Exclusive to the device's queue family, or shared with its async compute family: the
// resolve on a compute queue reads the maps and buffers as they are, with no ownership
// transfer (Vulkan spec, "Resource Sharing Mode").
template <typename CreateInfo>
void set_sharing(const Device& device, CreateInfo& info) {
    if (!device.shares_with_compute()) {
        info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        return;
    }
    info.sharingMode = VK_SHARING_MODE_CONCURRENT;
    info.queueFamilyIndexCount = static_cast<uint32_t>(device.sharing_families().size());
    info.pQueueFamilyIndices = device.sharing_families().data();
}

}  // namespace

Buffer create_buffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryKind kind) {
    Buffer result;
    result.size = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    set_sharing(device, info);
    VkBuffer buffer = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkCreateBuffer(device, &info, nullptr, &buffer));
    name_object(device, VK_OBJECT_TYPE_BUFFER, buffer, "buffer");
    result.buffer = UniqueBuffer(device, buffer);

    VkMemoryRequirements requirements{};
    device->vkGetBufferMemoryRequirements(device, buffer, &requirements);
    const bool host_access = kind != MemoryKind::DeviceLocal;
    result.memory = allocate(device, requirements, memory_properties(kind), host_access, true);
    PENUMBRA_VK_CHECK(device->vkBindBufferMemory(device, buffer, result.memory.memory(), result.memory.offset()));
    if (host_access) result.mapped = result.memory.mapped();
    return result;
}

Buffer create_buffer_with_data(const OneTimeCommands& commands, std::span<const std::byte> bytes,
                               VkBufferUsageFlags usage) {
    const Device& device = commands.device();
    const VkDeviceSize size = bytes.empty() ? 16 : bytes.size();
    Buffer staging = create_buffer(device, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryKind::HostUpload);
    if (!bytes.empty()) std::memcpy(staging.mapped, bytes.data(), bytes.size());
    Buffer result = create_buffer(device, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::DeviceLocal);
    commands.submit_and_wait([&](VkCommandBuffer cmd) {
        const VkBufferCopy region{0, 0, size};
        device->vkCmdCopyBuffer(cmd, staging.get(), result.get(), 1, &region);
    });
    return result;
}

Image create_image(const Device& device, const ImageDesc& desc) {
    Image result;
    result.desc = desc;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = desc.format;
    info.extent = {desc.width, desc.height, 1};
    info.mipLevels = 1;
    info.arrayLayers = desc.layers;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = desc.usage;
    if (desc.storage_view_format != VK_FORMAT_UNDEFINED) {
        info.flags = VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT | VK_IMAGE_CREATE_EXTENDED_USAGE_BIT;
    }
    set_sharing(device, info);
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkCreateImage(device, &info, nullptr, &image));
    name_object(device, VK_OBJECT_TYPE_IMAGE, image, "image");
    result.image = UniqueImage(device, image);

    VkMemoryRequirements requirements{};
    device->vkGetImageMemoryRequirements(device, image, &requirements);
    result.memory = allocate(device, requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, false, false);
    result.memory_size = requirements.size;
    PENUMBRA_VK_CHECK(device->vkBindImageMemory(device, image, result.memory.memory(), result.memory.offset()));

    const bool layered = desc.layers > 1 || desc.array_view;
    result.view =
        create_view(device, image, desc, layered ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D, 0, desc.layers);
    if (layered && desc.layer_views) {
        for (uint32_t layer = 0; layer < desc.layers; ++layer) {
            result.layer_views.push_back(create_view(device, image, desc, VK_IMAGE_VIEW_TYPE_2D, layer, 1));
        }
    }
    if (desc.storage_view_format != VK_FORMAT_UNDEFINED) {
        result.storage_view = create_view(device, image, desc, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, desc.layers, true);
    }
    return result;
}

void record_depth_clear_to_sampled(const Device& device, VkCommandBuffer cmd, const Image& image, float depth) {
    transition(device, cmd, image, ImageState::Undefined, ImageState::DepthAttachment);
    VkRenderingAttachmentInfo attachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    attachment.imageView = image.view;
    attachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.clearValue.depthStencil = {depth, 0};
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {image.desc.width, image.desc.height}};
    info.layerCount = image.desc.layers;
    info.pDepthAttachment = &attachment;
    device->vkCmdBeginRendering(cmd, &info);
    device->vkCmdEndRendering(cmd);
    transition(device, cmd, image, ImageState::DepthAttachment, ImageState::ShaderSampled);
}

Image create_texture_rgba8(const OneTimeCommands& commands, uint32_t width, uint32_t height,
                           std::span<const uint8_t> rgba) {
    const Device& device = commands.device();
    ImageDesc desc;
    desc.format = VK_FORMAT_R8G8B8A8_SRGB;
    desc.width = width;
    desc.height = height;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    Image image = create_image(device, desc);

    Buffer staging = create_buffer(device, rgba.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryKind::HostUpload);
    std::memcpy(staging.mapped, rgba.data(), rgba.size());
    commands.submit_and_wait([&](VkCommandBuffer cmd) {
        transition(device, cmd, image, ImageState::Undefined, ImageState::TransferDst);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {width, height, 1};
        device->vkCmdCopyBufferToImage(cmd, staging.get(), image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                                       &region);
        transition(device, cmd, image, ImageState::TransferDst, ImageState::FragmentSampled);
    });
    return image;
}

}  // namespace penumbra::gpu
