#pragma once
// PNG output and input (libpng). Writes go through OutputFiles (output_files.hpp): checked
// first, atomic, through symbolic links, never over a non-regular file, nothing left
// behind on failure or interruption. encode_png_* give the file's bytes for a set of
// outputs written together.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace penumbra {

struct PngImage {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t channels = 0;          // 1 (gray) or 4 (RGBA)
    uint32_t bit_depth = 0;         // 8 or 16
    std::vector<uint16_t> samples;  // row-major, row 0 at the top, channels interleaved
};

std::string encode_png_rgba8(uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba);
std::string encode_png_gray8(uint32_t width, uint32_t height, const std::vector<uint8_t>& gray);
std::string encode_png_gray16(uint32_t width, uint32_t height, const std::vector<uint16_t>& gray);

void write_png_rgba8(const std::filesystem::path& path, uint32_t width, uint32_t height,
                     const std::vector<uint8_t>& rgba);
void write_png_gray8(const std::filesystem::path& path, uint32_t width, uint32_t height,
                     const std::vector<uint8_t>& gray);
void write_png_gray16(const std::filesystem::path& path, uint32_t width, uint32_t height,
                      const std::vector<uint16_t>& gray);

// Reads an 8- or 16-bit gray or RGB(A) PNG (RGB is expanded to RGBA). Throws InputError.
PngImage read_png(const std::filesystem::path& path);

}  // namespace penumbra
