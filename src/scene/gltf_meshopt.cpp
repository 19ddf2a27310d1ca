// EXT_meshopt_compression (glTF extension, Vendor/EXT_meshopt_compression/README.md): a
// buffer view's bytes stored compressed in another buffer range, decoded here with
// meshoptimizer's decoders into the view's own layout, `count` elements of `byteStride`
// bytes, and the view pointed at the decoded bytes.
#include <meshoptimizer.h>

#include <cstring>

#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

constexpr const char* kExtension = "EXT_meshopt_compression";

enum class MeshoptMode { Attributes, Triangles, Indices };
enum class MeshoptFilter { None, Octahedral, Quaternion, Exponential };

struct CompressedView {
    size_t buffer = 0;
    size_t byte_offset = 0;
    size_t byte_length = 0;
    size_t byte_stride = 0;
    size_t count = 0;
    MeshoptMode mode = MeshoptMode::Attributes;
    MeshoptFilter filter = MeshoptFilter::None;
};

MeshoptMode read_mode(const GltfSource& source, const std::string& text, const std::string& where) {
    if (text == "ATTRIBUTES") return MeshoptMode::Attributes;
    if (text == "TRIANGLES") return MeshoptMode::Triangles;
    if (text == "INDICES") return MeshoptMode::Indices;
    source.fail(where, "unknown mode \"" + text + "\" (expected ATTRIBUTES, TRIANGLES or INDICES)");
}

MeshoptFilter read_filter(const GltfSource& source, const std::string& text, const std::string& where) {
    if (text == "NONE") return MeshoptFilter::None;
    if (text == "OCTAHEDRAL") return MeshoptFilter::Octahedral;
    if (text == "QUATERNION") return MeshoptFilter::Quaternion;
    if (text == "EXPONENTIAL") return MeshoptFilter::Exponential;
    source.fail(where, "unknown filter \"" + text + "\" (expected NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL)");
}

// The extension's validity rules ("JSON schema updates"), which are also the decoders'
// preconditions: meshoptimizer asserts on a stride or count they exclude.
void check_layout(const GltfSource& source, const CompressedView& view, const std::string& where) {
    const size_t stride = view.byte_stride;
    const bool indices = view.mode != MeshoptMode::Attributes;
    if (!indices && (stride == 0 || stride % 4 != 0 || stride > 256)) {
        source.fail(where + ".byteStride",
                    "expected a multiple of 4 from 4 to 256 in ATTRIBUTES mode, got " + std::to_string(stride));
    }
    if (indices && stride != 2 && stride != 4) {
        source.fail(where + ".byteStride", "expected 2 or 4 for indices, got " + std::to_string(stride));
    }
    if (view.mode == MeshoptMode::Triangles && view.count % 3 != 0) {
        source.fail(where + ".count", "expected a multiple of 3 in TRIANGLES mode, got " + std::to_string(view.count));
    }
    if (indices && view.filter != MeshoptFilter::None) {
        source.fail(where + ".filter", "indices take no filter");
    }
    const bool filter_fits = view.filter == MeshoptFilter::None ||
                             (view.filter == MeshoptFilter::Octahedral && (stride == 4 || stride == 8)) ||
                             (view.filter == MeshoptFilter::Quaternion && stride == 8) ||
                             (view.filter == MeshoptFilter::Exponential && stride % 4 == 0);
    if (!filter_fits) {
        source.fail(where + ".filter", "does not fit byteStride " + std::to_string(stride) +
                                           " (OCTAHEDRAL takes 4 or 8, QUATERNION 8, EXPONENTIAL multiples of 4)");
    }
}

CompressedView read_compressed_view(const GltfSource& source, const tinygltf::BufferView& parent,
                                    const tinygltf::Value& extension, const std::string& where) {
    if (!extension.IsObject()) source.fail(where, "expected an object");
    CompressedView view;
    view.buffer = extension_integer(source, extension, "buffer", where);
    view.byte_offset = extension_integer(source, extension, "byteOffset", where, 0);
    view.byte_length = extension_integer(source, extension, "byteLength", where);
    view.byte_stride = extension_integer(source, extension, "byteStride", where);
    view.count = extension_integer(source, extension, "count", where);
    view.mode = read_mode(source, extension_string(source, extension, "mode", where), where + ".mode");
    view.filter = read_filter(source, extension_string(source, extension, "filter", where, "NONE"), where + ".filter");
    check_layout(source, view, where);
    // The parent view describes the decoded layout: count x byteStride bytes, and the same stride.
    if (saturating_multiply(view.count, view.byte_stride) != parent.byteLength) {
        source.fail(where, std::to_string(view.count) + " elements of " + std::to_string(view.byte_stride) +
                               " bytes do not make the view's byteLength of " + std::to_string(parent.byteLength));
    }
    if (parent.byteStride != 0 && parent.byteStride != view.byte_stride) {
        source.fail(where + ".byteStride", std::to_string(view.byte_stride) + " differs from the view's byteStride " +
                                               std::to_string(parent.byteStride));
    }
    return view;
}

// The compressed bytes, checked to lie inside a buffer that holds data.
std::span<const unsigned char> compressed_bytes(const GltfSource& source, const CompressedView& view,
                                                const std::string& where) {
    const std::vector<tinygltf::Buffer>& buffers = source.model.buffers;
    if (view.buffer >= buffers.size()) {
        source.fail(where + ".buffer", "buffer " + std::to_string(view.buffer) + " does not exist (the file has " +
                                           std::to_string(buffers.size()) + " buffers)");
    }
    const tinygltf::Buffer& buffer = buffers[view.buffer];
    if (is_placeholder_buffer(buffer)) {
        source.fail(where + ".buffer", "buffers[" + std::to_string(view.buffer) +
                                           "] has no uri: it is a fallback, not the compressed data");
    }
    if (view.byte_offset > buffer.data.size() || view.byte_length > buffer.data.size() - view.byte_offset) {
        source.fail(where, "bytes " + std::to_string(view.byte_offset) + ".." +
                               std::to_string(view.byte_offset + view.byte_length) + " overrun buffers[" +
                               std::to_string(view.buffer) + "] of " + std::to_string(buffer.data.size()) + " bytes");
    }
    return {buffer.data.data() + view.byte_offset, view.byte_length};
}

// meshoptimizer's decoders return 0 on success and a negative number for a stream that is
// malformed or ends early (they never read past `compressed`).
std::vector<unsigned char> decode(const GltfSource& source, const CompressedView& view,
                                  std::span<const unsigned char> compressed, const std::string& where) {
    std::vector<unsigned char> decoded(view.count * view.byte_stride);
    int result = 0;
    switch (view.mode) {
        case MeshoptMode::Attributes:
            result = meshopt_decodeVertexBuffer(decoded.data(), view.count, view.byte_stride, compressed.data(),
                                                compressed.size());
            break;
        case MeshoptMode::Triangles:
            result = meshopt_decodeIndexBuffer(decoded.data(), view.count, view.byte_stride, compressed.data(),
                                               compressed.size());
            break;
        case MeshoptMode::Indices:
            result = meshopt_decodeIndexSequence(decoded.data(), view.count, view.byte_stride, compressed.data(),
                                                 compressed.size());
            break;
    }
    if (result != 0) {
        source.fail(where, "the compressed data is corrupt or cut short (meshoptimizer's decoder returned " +
                               std::to_string(result) + ")");
    }
    // Appendix B: each filter turns the decoded elements into the accessor's values in place.
    switch (view.filter) {
        case MeshoptFilter::None:
            break;
        case MeshoptFilter::Octahedral:
            meshopt_decodeFilterOct(decoded.data(), view.count, view.byte_stride);
            break;
        case MeshoptFilter::Quaternion:
            meshopt_decodeFilterQuat(decoded.data(), view.count, view.byte_stride);
            break;
        case MeshoptFilter::Exponential:
            meshopt_decodeFilterExp(decoded.data(), view.count, view.byte_stride);
            break;
    }
    return decoded;
}

}  // namespace

void decode_meshopt_buffer_views(tinygltf::Model& model, const GltfSource& source, GltfDecodeAllowance& allowance) {
    for (size_t i = 0; i < model.bufferViews.size(); ++i) {
        const auto found = model.bufferViews[i].extensions.find(kExtension);
        if (found == model.bufferViews[i].extensions.end()) continue;
        const std::string where = "bufferViews[" + std::to_string(i) + "].extensions." + kExtension;
        const CompressedView view = read_compressed_view(source, model.bufferViews[i], found->second, where);
        take_decoded_bytes(source, allowance, model.bufferViews[i].byteLength, where);
        std::vector<unsigned char> decoded = decode(source, view, compressed_bytes(source, view, where), where);
        // The decoded bytes become a buffer of their own, the whole of the view.
        tinygltf::Buffer buffer;
        buffer.data = std::move(decoded);
        buffer.uri = "(decoded " + where + ")";
        model.buffers.push_back(std::move(buffer));
        tinygltf::BufferView& parent = model.bufferViews[i];
        parent.buffer = static_cast<int>(model.buffers.size() - 1);
        parent.byteOffset = 0;
        if (view.mode == MeshoptMode::Attributes) parent.byteStride = view.byte_stride;
    }
}

}  // namespace penumbra
