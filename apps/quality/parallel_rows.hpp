#pragma once
// A parallel loop over image rows on every hardware thread (rows are handed out one at a
// time from an atomic counter, so uneven rows balance themselves).
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace penumbra::quality {

template <typename RowFunction>
void parallel_rows(uint32_t rows, const RowFunction& row_function) {
    const uint32_t threads = std::max(1u, std::min(rows, std::thread::hardware_concurrency()));
    std::atomic<uint32_t> next_row{0};
    const auto worker = [&] {
        for (uint32_t row = next_row++; row < rows; row = next_row++) row_function(row);
    };
    std::vector<std::jthread> pool;
    for (uint32_t t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
}

}  // namespace penumbra::quality
