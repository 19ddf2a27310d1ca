// Reading a .gltf or .glb file for tinygltf, safely: the file and every file its uris name
// must be regular files (a FIFO or a device would block the read forever), and the JSON may
// not nest deeper than kMaxGltfJsonDepth (tinygltf converts it recursively, and a few
// thousand levels of `extras` overflow the stack).
#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string_view>

#include "penumbra/errors.hpp"
#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

// tinygltf's messages end in newlines and may hold several lines; an InputError is one line.
std::string one_line(const std::string& text) {
    std::string result;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            if (!result.empty() && result.back() != ' ') result += "; ";
        } else {
            result += c;
        }
    }
    while (!result.empty() && (result.back() == ' ' || result.back() == ';')) result.pop_back();
    return result.empty() ? "unknown error" : result;
}

// What the image callback needs: the model whose buffer views it checks, and the bytes its
// decoded images may still take.
struct ImageLoading {
    const tinygltf::Model* model = nullptr;
    GltfImageAllowance allowance;
    uint64_t decoded_bytes = 0;  // RGBA8 bytes of the images accepted so far
};

// tinygltf has checked an image's view and buffer indices, not its byte range.
bool view_inside_buffer(const tinygltf::Model& model, const tinygltf::Image& image, const std::string& where,
                        std::string& err) {
    if (image.bufferView < 0) return true;
    const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(image.bufferView)];
    const size_t buffer_size = model.buffers[static_cast<size_t>(view.buffer)].data.size();
    if (view.byteOffset <= buffer_size && view.byteLength <= buffer_size - view.byteOffset) return true;
    err += where + ": bufferView " + std::to_string(image.bufferView) + " lies outside its buffer of " +
           std::to_string(buffer_size) + " bytes\n";
    return false;
}

// The header decides before the pixels are decoded: a PNG or JPEG (glTF 2.0, 3.9.4), whose
// width x height RGBA8 texels, with the images before it, fit the load budget. A 0.5 MB PNG
// may declare 16384 x 32767 pixels; it is refused, not decoded nor downscaled.
bool image_fits_budget(ImageLoading& loading, std::span<const unsigned char> bytes, const std::string& where,
                       std::string& err) {
    const std::optional<ImageHeader> header = read_image_header(bytes);
    if (!header) {
        err += where + ": not a PNG or JPEG image, or its header is cut short (glTF images are PNG or JPEG)\n";
        return false;
    }
    const uint64_t image_bytes = uint64_t{header->width} * header->height * 4;
    const uint64_t total = saturating_add(loading.decoded_bytes, image_bytes);
    if (total > loading.allowance.bytes) {
        err += where + ": " + std::to_string(header->width) + " x " + std::to_string(header->height) + " pixels (" +
               std::to_string(image_bytes) + " bytes as RGBA8) would take the scene past the load budget of " +
               std::to_string(loading.allowance.max_bytes) + " bytes (" + loading.allowance.budget_name +
               " raises it); refused before decoding\n";
        return false;
    }
    loading.decoded_bytes = total;
    return true;
}

// Checks the image's bytes and budget first, then decodes with tinygltf's stb_image loader.
bool load_image_checked(tinygltf::Image* image, const int image_index, std::string* err, std::string* warn,
                        int required_width, int required_height, const unsigned char* bytes, int size,
                        void* user_data) {
    auto& loading = *static_cast<ImageLoading*>(user_data);
    const std::string where = "images[" + std::to_string(image_index) + "]";
    if (!view_inside_buffer(*loading.model, *image, where, *err)) return false;
    const std::span<const unsigned char> encoded(bytes, size > 0 ? static_cast<size_t>(size) : 0);
    if (!image_fits_budget(loading, encoded, where, *err)) return false;
    return tinygltf::LoadImageData(image, image_index, err, warn, required_width, required_height, bytes, size,
                                   nullptr);
}

// tinygltf's file callbacks open the file to see whether it exists and then read it: on a
// FIFO or a character device either blocks. Only regular files are files here, and only
// those named relative to the model's folder (`user` points to it): tinygltf would also look
// in the current directory for a file that is not there.
bool regular_file_exists(const std::string& path, void* user) {
    const std::string& folder = *static_cast<const std::string*>(user);
    const std::string prefix = !folder.empty() && folder.back() == '/' ? folder : folder + "/";
    if (path.rfind(prefix, 0) != 0) return false;
    std::error_code error;
    return fs::is_regular_file(path, error);
}

bool read_regular_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    if (!regular_file_exists(path, user)) {
        *err += "\"" + path + "\" is not a regular file\n";
        return false;
    }
    return tinygltf::ReadWholeFile(out, err, path, user);
}

std::string lowercase_extension(const fs::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

std::vector<unsigned char> read_bytes(const fs::path& file, const std::string& origin) {
    std::ifstream stream(file, std::ios::binary);
    if (!stream) throw InputError(origin + ": cannot open the file");
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
    if (stream.bad()) throw InputError(origin + ": cannot read the file");
    return bytes;
}

uint32_t read_u32(const std::vector<unsigned char>& bytes, size_t offset) {
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + offset, sizeof(value));  // GLB is little-endian, like every target here
    return value;
}

// The JSON chunk of a GLB (12-byte header, then the JSON chunk's length and type); empty
// when the header is too damaged to find it (tinygltf then reports what is wrong).
std::string_view glb_json_chunk(const std::vector<unsigned char>& bytes) {
    constexpr size_t kHeader = 12;
    constexpr size_t kChunkHeader = 8;
    if (bytes.size() < kHeader + kChunkHeader) return {};
    const uint32_t chunk_length = read_u32(bytes, kHeader);
    if (chunk_length > bytes.size() - kHeader - kChunkHeader) return {};
    return {reinterpret_cast<const char*>(bytes.data()) + kHeader + kChunkHeader, chunk_length};
}

// Refuses a GLB whose chunks do not fit in it (glTF 2.0, 4.4: the header's length word is
// the whole container's; each chunk is an 8-byte length and type, then its data). tinygltf
// checks a BIN chunk's data against the length but forgets its 8-byte header, and reads
// past the end of the file when the length word is also the file's (as glb_with_json()
// writes it).
void check_glb_chunks(const std::vector<unsigned char>& bytes, const std::string& origin) {
    constexpr uint64_t kHeader = 12;
    constexpr uint64_t kChunkHeader = 8;
    if (bytes.size() < kHeader + kChunkHeader) return;  // tinygltf names a short file
    const uint64_t length = read_u32(bytes, 8);
    if (length > bytes.size()) {
        throw InputError(origin + ": the GLB header says " + std::to_string(length) + " bytes, the file has " +
                         std::to_string(bytes.size()) + " (truncated?)");
    }
    uint64_t offset = kHeader;
    for (int chunk = 0; offset + kChunkHeader <= length; ++chunk) {
        const uint64_t chunk_length = read_u32(bytes, static_cast<size_t>(offset));
        if (offset + kChunkHeader + chunk_length > length) {
            throw InputError(origin + ": GLB chunk " + std::to_string(chunk) + " says " + std::to_string(chunk_length) +
                             " bytes, only " + std::to_string(length - offset - kChunkHeader) +
                             " follow it in the container");
        }
        offset += kChunkHeader + chunk_length;
    }
}

// The same GLB with another JSON chunk (glTF 2.0, 4.4: a 12-byte header whose third word is
// the total length, then chunks of length, type and data, each padded to 4 bytes; JSON with
// spaces). The chunks after the JSON one are kept as they are.
std::vector<unsigned char> glb_with_json(const std::vector<unsigned char>& bytes, const std::string& json) {
    constexpr size_t kHeader = 12;
    constexpr size_t kChunkHeader = 8;
    const size_t rest = kHeader + kChunkHeader + glb_json_chunk(bytes).size();
    std::string padded = json;
    padded.resize((padded.size() + 3) / 4 * 4, ' ');
    std::vector<unsigned char> glb(bytes.begin(), bytes.begin() + kHeader);
    const auto append_u32 = [&](uint32_t value) {
        const auto* raw = reinterpret_cast<const unsigned char*>(&value);
        glb.insert(glb.end(), raw, raw + sizeof(value));
    };
    append_u32(static_cast<uint32_t>(padded.size()));
    append_u32(0x4E4F534Au);  // "JSON"
    glb.insert(glb.end(), padded.begin(), padded.end());
    const size_t container_end = std::max<size_t>(rest, read_u32(bytes, 8));  // check_glb_chunks(): <= size
    glb.insert(glb.end(), bytes.begin() + static_cast<std::ptrdiff_t>(rest),
               bytes.begin() + static_cast<std::ptrdiff_t>(container_end));
    const auto total = static_cast<uint32_t>(glb.size());
    std::memcpy(glb.data() + 8, &total, sizeof(total));
    return glb;
}

}  // namespace

size_t json_nesting_depth(std::string_view text, size_t stop_beyond) {
    size_t depth = 0;
    size_t deepest = 0;
    bool in_string = false;
    bool escaped = false;
    for (const char c : text) {
        if (in_string) {
            if (escaped) {
                escaped = false;
            } else if (c == '\\') {
                escaped = true;
            } else if (c == '"') {
                in_string = false;
            }
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
            if (deepest > stop_beyond) return deepest;
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

tinygltf::Model read_gltf_model(const fs::path& file, const std::string& origin, const GltfImageAllowance& images) {
    const std::string extension = lowercase_extension(file);
    if (extension != ".gltf" && extension != ".glb") {
        throw InputError(origin + ": unsupported model extension \"" + extension + "\" (expected .gltf or .glb)");
    }
    std::error_code error;
    if (!fs::exists(file, error)) throw InputError(origin + ": file not found");
    if (!fs::is_regular_file(file, error)) throw InputError(origin + ": not a regular file");
    const std::vector<unsigned char> bytes = read_bytes(file, origin);
    if (bytes.empty()) throw InputError(origin + ": the file is empty");
    if (bytes.size() > std::numeric_limits<uint32_t>::max()) {
        throw InputError(origin + ": larger than 4 GiB, which glTF cannot address");
    }
    const bool binary = extension == ".glb";
    // tinygltf reads a GLB of any version as if it were 2 (glTF 1.0's binary extension differs).
    if (binary && bytes.size() >= 12 && std::memcmp(bytes.data(), "glTF", 4) == 0 && read_u32(bytes, 4) != 2) {
        throw InputError(origin + ": GLB container version " + std::to_string(read_u32(bytes, 4)) +
                         " (glTF 2.0 files are version 2)");
    }
    if (binary) check_glb_chunks(bytes, origin);
    const std::string_view json =
        binary ? glb_json_chunk(bytes) : std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (json_nesting_depth(json, kMaxGltfJsonDepth) > kMaxGltfJsonDepth) {
        throw InputError(origin + ": its JSON nests arrays and objects more than " + std::to_string(kMaxGltfJsonDepth) +
                         " levels deep");
    }

    const std::string folder = fs::absolute(file, error).parent_path().string();
    check_gltf_json(json, origin, folder);
    const std::optional<GltfStandIns> stand_ins = json_with_stand_ins(json, binary);
    std::vector<unsigned char> rewritten;
    if (stand_ins) {
        rewritten = binary ? glb_with_json(bytes, stand_ins->json)
                           : std::vector<unsigned char>(stand_ins->json.begin(), stand_ins->json.end());
    }
    const std::vector<unsigned char>& input = stand_ins ? rewritten : bytes;
    if (input.size() > std::numeric_limits<uint32_t>::max()) {
        throw InputError(origin + ": larger than 4 GiB, which glTF cannot address");
    }

    tinygltf::TinyGLTF loader;
    std::string base_dir = folder;
    tinygltf::FsCallbacks callbacks{regular_file_exists, tinygltf::ExpandFilePath, read_regular_file,
                                    tinygltf::WriteWholeFile, &base_dir};
    loader.SetFsCallbacks(callbacks);
    tinygltf::Model model;
    ImageLoading image_loading{&model, images, 0};
    loader.SetImageLoader(load_image_checked, &image_loading);
    std::string errors;
    std::string warnings;
    const bool loaded =
        binary ? loader.LoadBinaryFromMemory(&model, &errors, &warnings, input.data(),
                                             static_cast<unsigned int>(input.size()), base_dir)
               : loader.LoadASCIIFromString(&model, &errors, &warnings, reinterpret_cast<const char*>(input.data()),
                                            static_cast<unsigned int>(input.size()), base_dir);
    if (!loaded) throw InputError(origin + ": cannot load glTF: " + one_line(errors.empty() ? warnings : errors));
    if (stand_ins) remove_stand_ins(model, *stand_ins);
    return model;
}

}  // namespace penumbra
