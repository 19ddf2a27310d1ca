#pragma once
// Penumbra's default DeviceMemoryAllocator: images and buffers are placed in blocks of
// device memory shared by many resources (one vkAllocateMemory per block, as VMA and most
// engines do, rather than one per resource: drivers limit the number of allocations and
// each costs a kernel call). Buffers and optimal-tiling images get blocks of their own, so
// bufferImageGranularity never separates neighbours; a request larger than half a block
// gets a block of its own size. Host-visible blocks stay mapped.
#include <cstdint>
#include <memory>
#include <vector>

#include "penumbra/memory.hpp"
#include "range_allocator.hpp"

namespace penumbra::gpu {

class Device;

class BlockAllocator final : public DeviceMemoryAllocator {
public:
    static constexpr VkDeviceSize kBlockSize = VkDeviceSize{64} << 20;

    explicit BlockAllocator(const Device& device) : device_(device) {}
    ~BlockAllocator() override;
    BlockAllocator(const BlockAllocator&) = delete;
    BlockAllocator& operator=(const BlockAllocator&) = delete;

    MemoryAllocation allocate(const MemoryRequest& request) override;
    void free(const MemoryAllocation& allocation) noexcept override;

    size_t block_count() const { return blocks_.size(); }

private:
    struct Block {
        VkDeviceMemory memory = VK_NULL_HANDLE;
        uint32_t memory_type = 0;
        bool linear = false;
        std::byte* mapped = nullptr;
        RangeAllocator ranges;
    };

    Block& add_block(uint32_t memory_type, bool linear, VkDeviceSize size);
    void release(Block& block) noexcept;

    const Device& device_;
    std::vector<std::unique_ptr<Block>> blocks_;
};

}  // namespace penumbra::gpu
