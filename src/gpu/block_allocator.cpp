#include "block_allocator.hpp"

#include <algorithm>

#include "penumbra/gpu/check.hpp"
#include "penumbra/gpu/debug_names.hpp"
#include "penumbra/gpu/device.hpp"

namespace penumbra::gpu {

BlockAllocator::~BlockAllocator() {
    for (const std::unique_ptr<Block>& block : blocks_) release(*block);
}

MemoryAllocation BlockAllocator::allocate(const MemoryRequest& request) {
    const VkMemoryRequirements& needs = request.requirements;
    const uint32_t memory_type = device_.find_memory_type(needs.memoryTypeBits, request.required_properties);
    const VkDeviceSize alignment = std::max<VkDeviceSize>(needs.alignment, 1);
    Block* placed_in = nullptr;
    std::optional<uint64_t> offset;
    if (needs.size <= kBlockSize / 2) {
        for (const std::unique_ptr<Block>& block : blocks_) {
            if (block->memory_type != memory_type || block->linear != request.linear) continue;
            if ((offset = block->ranges.allocate(needs.size, alignment))) {
                placed_in = block.get();
                break;
            }
        }
    }
    if (!placed_in) {
        // A request larger than half a block gets a block of exactly its size.
        placed_in = &add_block(memory_type, request.linear, needs.size > kBlockSize / 2 ? needs.size : kBlockSize);
        offset = placed_in->ranges.allocate(needs.size, alignment);
    }
    MemoryAllocation allocation;
    allocation.memory = placed_in->memory;
    allocation.offset = *offset;
    allocation.mapped = placed_in->mapped ? placed_in->mapped + *offset : nullptr;
    allocation.user_data = placed_in;
    return allocation;
}

void BlockAllocator::free(const MemoryAllocation& allocation) noexcept {
    const auto owner = std::find_if(blocks_.begin(), blocks_.end(), [&](const std::unique_ptr<Block>& block) {
        return block.get() == allocation.user_data;
    });
    if (owner == blocks_.end() || !(*owner)->ranges.free(allocation.offset)) return;
    if ((*owner)->ranges.empty()) {
        release(**owner);
        blocks_.erase(owner);
    }
}

BlockAllocator::Block& BlockAllocator::add_block(uint32_t memory_type, bool linear, VkDeviceSize size) {
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = size;
    info.memoryTypeIndex = memory_type;
    auto block = std::make_unique<Block>(Block{VK_NULL_HANDLE, memory_type, linear, nullptr, RangeAllocator(size)});
    PENUMBRA_VK_CHECK(device_->vkAllocateMemory(device_, &info, nullptr, &block->memory));
    name_object(device_, VK_OBJECT_TYPE_DEVICE_MEMORY, block->memory, "memory block");
    // Every block of a host-visible type is mapped: a later request for host access may
    // land in a block made for a device-only one.
    if (device_.memory_properties().memoryTypes[memory_type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
        void* mapped = nullptr;
        const VkResult result = device_->vkMapMemory(device_, block->memory, 0, VK_WHOLE_SIZE, 0, &mapped);
        if (result != VK_SUCCESS) {
            device_->vkFreeMemory(device_, block->memory, nullptr);
            PENUMBRA_VK_CHECK(result);
        }
        block->mapped = static_cast<std::byte*>(mapped);
    }
    blocks_.push_back(std::move(block));
    return *blocks_.back();
}

void BlockAllocator::release(Block& block) noexcept {
    // vkFreeMemory unmaps a mapped block.
    device_->vkFreeMemory(device_, block.memory, nullptr);
}

}  // namespace penumbra::gpu
