#pragma once
// Reports of a benchmark run: a plain-text table (median, p95 and min per pass, in ms)
// and a JSON document with the same numbers plus device, settings and scene statistics
// (schema "penumbra-bench/1", documented in docs/bench.md).
#include <filesystem>
#include <string>

#include "bench/bench_job.hpp"

namespace penumbra::bench {

std::string format_bench_table(const BenchResult& result);

std::string bench_json(const BenchResult& result);

// Writes bench_json() to `path` atomically (a temporary file renamed into place), so a
// failed run never leaves a half-written report. Throws InputError when it cannot.
void write_bench_json(const BenchResult& result, const std::filesystem::path& path);

}  // namespace penumbra::bench
