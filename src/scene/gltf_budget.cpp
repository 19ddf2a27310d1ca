// The load budget (issue 32, items 6 and 7): what a glTF model would add to a scene is
// counted from its image headers and accessor counts before anything is decoded or
// expanded, so a file that asks for billions of triangles or gigapixels is refused in a time
// proportional to the file, not to what it describes.
#include <array>
#include <cstring>
#include <limits>

#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

uint32_t big_endian(std::span<const unsigned char> bytes, size_t offset, size_t size) {
    uint32_t value = 0;
    for (size_t i = 0; i < size; ++i) value = value << 8 | bytes[offset + i];
    return value;
}

// PNG (ISO 15948, 5.2 and 11.2.2): the 8-byte signature, then IHDR's length, type, width
// and height, big-endian.
std::optional<ImageHeader> read_png_header(std::span<const unsigned char> bytes) {
    static constexpr std::array<unsigned char, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (bytes.size() < 24 || std::memcmp(bytes.data(), kSignature.data(), kSignature.size()) != 0 ||
        std::memcmp(bytes.data() + 12, "IHDR", 4) != 0) {
        return std::nullopt;
    }
    return ImageHeader{big_endian(bytes, 16, 4), big_endian(bytes, 20, 4)};
}

// Start-of-frame markers (ITU T.81, B.1.1.3): C0-CF but DHT (C4), JPG (C8) and DAC (CC).
bool is_start_of_frame(unsigned char marker) {
    return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

// Markers without a length field: TEM, RSTn, SOI.
bool is_standalone(unsigned char marker) { return marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8); }

// JPEG (ITU T.81, B.2): SOI, then segments of marker and big-endian length until the first
// frame header, whose length is followed by precision, height and width. A scan or the end
// of the image before any frame is a damaged file.
std::optional<ImageHeader> read_jpeg_header(std::span<const unsigned char> bytes) {
    if (bytes.size() < 2 || bytes[0] != 0xFF || bytes[1] != 0xD8) return std::nullopt;
    size_t at = 2;
    while (at < bytes.size()) {
        if (bytes[at] != 0xFF) return std::nullopt;
        while (at < bytes.size() && bytes[at] == 0xFF) ++at;  // fill bytes
        if (at >= bytes.size()) return std::nullopt;
        const unsigned char marker = bytes[at++];
        if (is_standalone(marker)) continue;
        if (marker == 0xD9 || marker == 0xDA || at + 2 > bytes.size()) return std::nullopt;
        const uint32_t length = big_endian(bytes, at, 2);
        if (length < 2) return std::nullopt;
        if (is_start_of_frame(marker)) {
            if (length < 7 || at + 7 > bytes.size()) return std::nullopt;
            return ImageHeader{big_endian(bytes, at + 5, 2), big_endian(bytes, at + 3, 2)};
        }
        at += length;
    }
    return std::nullopt;
}

// The element count an accessor may really have, or 0 for one that converting will refuse
// (missing, or more elements than its buffer view has bytes, or beyond
// kMaxGltfElementsWithoutData without one): that error is the one to report, not the budget.
uint64_t plausible_count(const tinygltf::Model& model, int index) {
    if (index < 0 || static_cast<size_t>(index) >= model.accessors.size()) return 0;
    const tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(index)];
    if (accessor.bufferView < 0) return accessor.count <= kMaxGltfElementsWithoutData ? accessor.count : 0;
    if (static_cast<size_t>(accessor.bufferView) >= model.bufferViews.size()) return 0;
    const size_t view_bytes = model.bufferViews[static_cast<size_t>(accessor.bufferView)].byteLength;
    return accessor.count <= view_bytes ? accessor.count : 0;
}

uint64_t triangles_of(int mode, uint64_t index_count) {
    switch (mode) {
        case -1:  // absent: TRIANGLES
        case TINYGLTF_MODE_TRIANGLES:
            return index_count / 3;
        case TINYGLTF_MODE_TRIANGLE_STRIP:
        case TINYGLTF_MODE_TRIANGLE_FAN:
            return index_count >= 3 ? index_count - 2 : 0;
        default:  // points and lines cast no shadow and are dropped; unknown modes are refused
            return 0;
    }
}

}  // namespace

std::optional<ImageHeader> read_image_header(std::span<const unsigned char> bytes) {
    if (const std::optional<ImageHeader> png = read_png_header(bytes)) return png;
    return read_jpeg_header(bytes);
}

uint64_t saturating_add(uint64_t a, uint64_t b) {
    return a > std::numeric_limits<uint64_t>::max() - b ? std::numeric_limits<uint64_t>::max() : a + b;
}

uint64_t saturating_multiply(uint64_t a, uint64_t b) {
    if (a != 0 && b > std::numeric_limits<uint64_t>::max() / a) return std::numeric_limits<uint64_t>::max();
    return a * b;
}

bool positions_all_at_origin(const tinygltf::Model& model, const tinygltf::Primitive& primitive) {
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end() || !primitive.targets.empty()) return false;
    if (position->second < 0 || static_cast<size_t>(position->second) >= model.accessors.size()) return false;
    const tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(position->second)];
    return accessor.bufferView < 0 && !accessor.sparse.isSparse;
}

GltfCost primitive_cost(const tinygltf::Model& model, const tinygltf::Primitive& primitive) {
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end() || positions_all_at_origin(model, primitive)) return {};
    const uint64_t vertices = plausible_count(model, position->second);
    const uint64_t index_count = primitive.indices >= 0 ? plausible_count(model, primitive.indices) : vertices;
    GltfCost cost;
    cost.triangles = triangles_of(primitive.mode, index_count);
    if (cost.triangles == 0) return {};  // converting makes no mesh
    cost.bytes = saturating_add(saturating_multiply(vertices, sizeof(Vertex)),
                                saturating_multiply(cost.triangles, 3 * sizeof(uint32_t)));
    return cost;
}

GltfCost scene_cost(const Scene& scene) {
    GltfCost cost;
    cost.triangles = scene.triangle_count();
    for (const Mesh& mesh : scene.meshes) {
        cost.bytes += mesh.vertices.size() * sizeof(Vertex) + mesh.indices.size() * sizeof(uint32_t);
    }
    for (const Texture& texture : scene.textures) cost.bytes += texture.rgba8.size();
    return cost;
}

void check_load_budget(const GltfSource& source, const GltfCost& held, const GltfCost& added,
                       const LoadBudget& budget) {
    const auto before = [](uint64_t value) {
        return value == 0 ? std::string() : " (the scene held " + std::to_string(value) + " before)";
    };
    if (saturating_add(held.triangles, added.triangles) > budget.max_triangles) {
        source.fail("meshes", "would make " + std::to_string(added.triangles) + " triangles as placed" +
                                  before(held.triangles) + ", over the load budget of " +
                                  std::to_string(budget.max_triangles) + " (" + budget.max_triangles_name +
                                  " raises it); refused before converting them");
    }
    if (saturating_add(held.bytes, added.bytes) > budget.max_bytes) {
        source.fail("meshes", "images and meshes would take " + std::to_string(added.bytes) + " bytes" +
                                  before(held.bytes) + ", over the load budget of " + std::to_string(budget.max_bytes) +
                                  " bytes (" + budget.max_bytes_name +
                                  " raises it); refused before converting the meshes");
    }
}

}  // namespace penumbra
