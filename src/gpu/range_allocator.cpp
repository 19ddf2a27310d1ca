#include "range_allocator.hpp"

#include <iterator>

namespace penumbra::gpu {

RangeAllocator::RangeAllocator(uint64_t capacity) : capacity_(capacity) {
    if (capacity > 0) free_.emplace(0, capacity);
}

std::optional<uint64_t> RangeAllocator::allocate(uint64_t size, uint64_t alignment) {
    if (size == 0 || alignment == 0 || (alignment & (alignment - 1)) != 0) return std::nullopt;
    for (auto range = free_.begin(); range != free_.end(); ++range) {
        const uint64_t start = range->first;
        const uint64_t end = start + range->second;
        const uint64_t aligned = (start + alignment - 1) & ~(alignment - 1);
        if (aligned < start || aligned > end || end - aligned < size) continue;
        free_.erase(range);
        // The padding before the aligned start and what is left after stay free.
        if (aligned > start) free_.emplace(start, aligned - start);
        if (end > aligned + size) free_.emplace(aligned + size, end - aligned - size);
        used_.emplace(aligned, size);
        return aligned;
    }
    return std::nullopt;
}

bool RangeAllocator::free(uint64_t offset) {
    const auto used = used_.find(offset);
    if (used == used_.end()) return false;
    const uint64_t size = used->second;
    used_.erase(used);
    insert_free(offset, size);
    return true;
}

void RangeAllocator::insert_free(uint64_t offset, uint64_t size) {
    auto next = free_.lower_bound(offset);
    if (next != free_.begin()) {
        const auto previous = std::prev(next);
        if (previous->first + previous->second == offset) {
            offset = previous->first;
            size += previous->second;
            free_.erase(previous);
        }
    }
    if (next != free_.end() && offset + size == next->first) {
        size += next->second;
        free_.erase(next);
    }
    free_.emplace(offset, size);
}

uint64_t RangeAllocator::free_bytes() const {
    uint64_t total = 0;
    for (const auto& [offset, size] : free_) total += size;
    return total;
}

}  // namespace penumbra::gpu
