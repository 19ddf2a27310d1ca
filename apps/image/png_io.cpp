#include "image/png_io.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <system_error>

#include "image/output_files.hpp"
#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

void append_bytes(png_structp png, png_bytep data, png_size_t length) {
    auto* bytes = static_cast<std::string*>(png_get_io_ptr(png));
    bytes->append(reinterpret_cast<const char*>(data), length);
}

void no_flush(png_structp) {}

// The PNG file of `rows` in memory; throws when libpng fails (out of memory).
std::string encode_png(uint32_t width, uint32_t height, int color_type, int bit_depth, const uint8_t* pixels,
                       size_t row_bytes) {
    std::vector<png_bytep> rows(height);
    for (uint32_t y = 0; y < height; ++y) rows[y] = const_cast<png_bytep>(pixels + y * row_bytes);
    std::string bytes;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        throw Error("encoding a " + std::to_string(width) + "x" + std::to_string(height) + " PNG failed");
    }
    png_set_write_fn(png, &bytes, append_bytes, no_flush);
    png_set_IHDR(png, info, width, height, bit_depth, color_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (color_type == PNG_COLOR_TYPE_RGBA) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    if (bit_depth == 16) png_set_swap(png);  // our samples are little-endian; PNG is big-endian
    png_write_image(png, rows.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return bytes;
}

}  // namespace

std::string encode_png_rgba8(uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba) {
    return encode_png(width, height, PNG_COLOR_TYPE_RGBA, 8, rgba.data(), size_t{width} * 4);
}

std::string encode_png_gray8(uint32_t width, uint32_t height, const std::vector<uint8_t>& gray) {
    return encode_png(width, height, PNG_COLOR_TYPE_GRAY, 8, gray.data(), width);
}

std::string encode_png_gray16(uint32_t width, uint32_t height, const std::vector<uint16_t>& gray) {
    return encode_png(width, height, PNG_COLOR_TYPE_GRAY, 16, reinterpret_cast<const uint8_t*>(gray.data()),
                      size_t{width} * 2);
}

void write_png_rgba8(const std::filesystem::path& path, uint32_t width, uint32_t height,
                     const std::vector<uint8_t>& rgba) {
    write_output_file(path, encode_png_rgba8(width, height, rgba));
}

void write_png_gray8(const std::filesystem::path& path, uint32_t width, uint32_t height,
                     const std::vector<uint8_t>& gray) {
    write_output_file(path, encode_png_gray8(width, height, gray));
}

void write_png_gray16(const std::filesystem::path& path, uint32_t width, uint32_t height,
                      const std::vector<uint16_t>& gray) {
    write_output_file(path, encode_png_gray16(width, height, gray));
}

PngImage read_png(const std::filesystem::path& path) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&image, path.c_str())) {
        throw InputError(path.string() + ": cannot read PNG: " + image.message);
    }
    const bool gray = (image.format & PNG_FORMAT_FLAG_COLOR) == 0;
    const bool sixteen = (image.format & PNG_FORMAT_FLAG_LINEAR) != 0;
    PngImage result;
    result.width = image.width;
    result.height = image.height;
    result.channels = gray ? 1 : 4;
    result.bit_depth = sixteen ? 16 : 8;
    // The simplified API treats 16-bit data as linear and 8-bit as sRGB; asking for the
    // file's own encoding avoids any conversion, so values come back exactly as stored.
    image.format = (gray ? PNG_FORMAT_GRAY : PNG_FORMAT_RGBA) | (sixteen ? PNG_FORMAT_FLAG_LINEAR : 0);
    const size_t count = size_t{image.width} * image.height * result.channels;
    if (sixteen) {
        result.samples.resize(count);
        if (!png_image_finish_read(&image, nullptr, result.samples.data(), 0, nullptr)) {
            throw InputError(path.string() + ": cannot decode PNG: " + image.message);
        }
    } else {
        std::vector<uint8_t> bytes(count);
        if (!png_image_finish_read(&image, nullptr, bytes.data(), 0, nullptr)) {
            throw InputError(path.string() + ": cannot decode PNG: " + image.message);
        }
        result.samples.assign(bytes.begin(), bytes.end());
    }
    return result;
}

}  // namespace penumbra
