#pragma once
// A one-line progress bar on stderr for long benchmark runs, drawn only when stderr is
// a terminal (so logs and pipes get no carriage returns).
#include <cstdint>
#include <functional>

namespace penumbra::cli {

// A callback for BenchJob::progress, or an empty function when stderr is not a TTY.
std::function<void(uint32_t done, uint32_t total)> terminal_progress_bar();

// A callback for CompareJob::progress (the rows of each frame's reference being traced),
// or an empty function when stderr is not a TTY.
std::function<void(uint32_t frame, uint32_t frames, uint32_t rows_done, uint32_t rows)> terminal_trace_progress_bar();

}  // namespace penumbra::cli
