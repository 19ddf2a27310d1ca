#include "bench/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace penumbra::bench {

Summary summarize(std::vector<double> samples) {
    Summary summary;
    summary.samples = samples.size();
    if (samples.empty()) return summary;
    std::sort(samples.begin(), samples.end());
    const size_t n = samples.size();
    summary.min = samples.front();
    summary.max = samples.back();
    summary.median = n % 2 == 1 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
    // Nearest rank: the smallest sample with at least 95% of the samples at or below it.
    const auto rank = static_cast<size_t>(std::ceil(0.95 * static_cast<double>(n)));
    summary.p95 = samples[std::max<size_t>(rank, 1) - 1];
    summary.mean = std::accumulate(samples.begin(), samples.end(), 0.0) / static_cast<double>(n);
    return summary;
}

}  // namespace penumbra::bench
