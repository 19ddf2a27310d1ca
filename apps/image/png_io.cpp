#include "image/png_io.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <system_error>

#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};
using UniqueFile = std::unique_ptr<std::FILE, FileCloser>;

std::filesystem::path temporary_sibling(const std::filesystem::path& path) {
    std::random_device entropy;
    return path.parent_path() / ("." + path.filename().string() + ".tmp" + std::to_string(entropy() % 1000000));
}

// Encodes rows into `file`; returns false on a libpng error.
bool encode_png(std::FILE* file, uint32_t width, uint32_t height, int color_type, int bit_depth,
                const std::vector<png_bytep>& rows) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_init_io(png, file);
    png_set_IHDR(png, info, width, height, bit_depth, color_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (color_type == PNG_COLOR_TYPE_RGBA) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    if (bit_depth == 16) png_set_swap(png);  // our samples are little-endian; PNG is big-endian
    png_write_image(png, const_cast<png_bytepp>(rows.data()));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

void write_png_atomically(const std::filesystem::path& path, uint32_t width, uint32_t height, int color_type,
                          int bit_depth, const uint8_t* pixels, size_t row_bytes) {
    std::vector<png_bytep> rows(height);
    for (uint32_t y = 0; y < height; ++y) rows[y] = const_cast<png_bytep>(pixels + y * row_bytes);

    const std::filesystem::path temporary = temporary_sibling(path);
    UniqueFile file(std::fopen(temporary.c_str(), "wb"));
    if (!file) throw InputError(path.string() + ": cannot open for writing: " + std::strerror(errno));
    const bool encoded = encode_png(file.get(), width, height, color_type, bit_depth, rows);
    const bool closed = std::fclose(file.release()) == 0;
    std::error_code error;
    if (!encoded || !closed) {
        std::filesystem::remove(temporary, error);
        throw InputError(path.string() + ": writing the PNG failed (disk full?)");
    }
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw InputError(path.string() + ": cannot write: " + error.message());
    }
}

}  // namespace

void write_png_rgba8(const std::filesystem::path& path, uint32_t width, uint32_t height,
                     const std::vector<uint8_t>& rgba) {
    write_png_atomically(path, width, height, PNG_COLOR_TYPE_RGBA, 8, rgba.data(), size_t{width} * 4);
}

void write_png_gray8(const std::filesystem::path& path, uint32_t width, uint32_t height,
                     const std::vector<uint8_t>& gray) {
    write_png_atomically(path, width, height, PNG_COLOR_TYPE_GRAY, 8, gray.data(), width);
}

void write_png_gray16(const std::filesystem::path& path, uint32_t width, uint32_t height,
                      const std::vector<uint16_t>& gray) {
    write_png_atomically(path, width, height, PNG_COLOR_TYPE_GRAY, 16, reinterpret_cast<const uint8_t*>(gray.data()),
                         size_t{width} * 2);
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
