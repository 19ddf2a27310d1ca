#include "progress_bar.hpp"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace penumbra::cli {

namespace {

std::string bar(uint32_t done, uint32_t total) {
    constexpr uint32_t kWidth = 40;
    const uint32_t filled = total == 0 ? kWidth : static_cast<uint32_t>(uint64_t{done} * kWidth / total);
    return "[" + std::string(filled, '#') + std::string(kWidth - filled, '.') + "]";
}

}  // namespace

std::function<void(uint32_t done, uint32_t total)> terminal_progress_bar() {
    if (!isatty(STDERR_FILENO)) return {};
    return [](uint32_t done, uint32_t total) {
        std::fprintf(stderr, "\r%s %u/%u frames", bar(done, total).c_str(), done, total);
        if (done == total) std::fprintf(stderr, "\r\033[K");  // erase the bar once finished
        std::fflush(stderr);
    };
}

std::function<void(uint32_t frame, uint32_t frames, uint32_t rows_done, uint32_t rows)> terminal_trace_progress_bar() {
    if (!isatty(STDERR_FILENO)) return {};
    return [](uint32_t frame, uint32_t frames, uint32_t rows_done, uint32_t rows) {
        std::fprintf(stderr, "\r%s tracing the reference of frame %u/%u", bar(rows_done, rows).c_str(), frame + 1,
                     frames);
        if (frame + 1 == frames && rows_done == rows) std::fprintf(stderr, "\r\033[K");  // erase it once finished
        std::fflush(stderr);
    };
}

}  // namespace penumbra::cli
