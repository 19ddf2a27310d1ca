#pragma once
// A parallel loop over image rows on every hardware thread (rows are handed out one at a
// time from an atomic counter, so uneven rows balance themselves), with an optional
// progress report that is only ever called on the calling thread.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <thread>
#include <vector>

namespace penumbra::quality {

// Called with the rows finished so far and the total: after each row the calling thread
// finishes, and once with rows == total at the end.
using RowProgress = std::function<void(uint32_t rows_done, uint32_t rows)>;

template <typename RowFunction>
void parallel_rows(uint32_t rows, const RowFunction& row_function, const RowProgress& progress = {}) {
    const uint32_t threads = std::max(1u, std::min(rows, std::thread::hardware_concurrency()));
    std::atomic<uint32_t> next_row{0};
    std::atomic<uint32_t> rows_done{0};
    const auto worker = [&](bool reports) {
        for (uint32_t row = next_row++; row < rows; row = next_row++) {
            row_function(row);
            const uint32_t done = ++rows_done;
            if (reports && progress) progress(done, rows);
        }
    };
    {
        std::vector<std::jthread> pool;
        for (uint32_t t = 1; t < threads; ++t) pool.emplace_back(worker, false);
        worker(true);
    }  // the pool's threads are joined here
    if (progress) progress(rows, rows);
}

}  // namespace penumbra::quality
