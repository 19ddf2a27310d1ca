#pragma once
// Order statistics of benchmark samples: median, 95th percentile (nearest rank), min,
// max and mean. Median and percentiles rather than means because frame times have long
// tails (a single stall would move a mean).
#include <cstddef>
#include <vector>

namespace penumbra::bench {

struct Summary {
    double median = 0.0;
    double p95 = 0.0;
    double min = 0.0;
    double max = 0.0;
    double mean = 0.0;
    size_t samples = 0;
};

// All zero for no samples.
Summary summarize(std::vector<double> samples);

}  // namespace penumbra::bench
