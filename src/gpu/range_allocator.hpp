#pragma once
// First-fit placement of aligned ranges in a block of bytes: the bookkeeping of the default
// device memory allocator (gpu/block_allocator.hpp), kept free of Vulkan so that it can be
// tested alone. A freed range merges with the free ranges beside it.
#include <cstdint>
#include <map>
#include <optional>

namespace penumbra::gpu {

class RangeAllocator {
public:
    explicit RangeAllocator(uint64_t capacity);

    // The offset of `size` bytes aligned to `alignment` (a power of two), or nullopt when
    // no free range holds them.
    std::optional<uint64_t> allocate(uint64_t size, uint64_t alignment);
    // Gives back the range allocate() returned at `offset`; false (nothing changes) for an
    // offset that is not one.
    bool free(uint64_t offset);

    uint64_t capacity() const { return capacity_; }
    uint64_t free_bytes() const;
    bool empty() const { return used_.empty(); }  // nothing allocated
    size_t free_ranges() const { return free_.size(); }

private:
    void insert_free(uint64_t offset, uint64_t size);

    uint64_t capacity_;
    std::map<uint64_t, uint64_t> free_;  // offset -> size; never two that touch
    std::map<uint64_t, uint64_t> used_;  // offset -> size
};

}  // namespace penumbra::gpu
