#include "progress_bar.hpp"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace penumbra::cli {

std::function<void(uint32_t done, uint32_t total)> terminal_progress_bar() {
    if (!isatty(STDERR_FILENO)) return {};
    return [](uint32_t done, uint32_t total) {
        constexpr uint32_t kWidth = 40;
        const uint32_t filled = total == 0 ? kWidth : static_cast<uint32_t>(uint64_t{done} * kWidth / total);
        const std::string bar = std::string(filled, '#') + std::string(kWidth - filled, '.');
        std::fprintf(stderr, "\r[%s] %u/%u frames", bar.c_str(), done, total);
        if (done == total) std::fprintf(stderr, "\r\033[K");  // erase the bar once finished
        std::fflush(stderr);
    };
}

}  // namespace penumbra::cli
