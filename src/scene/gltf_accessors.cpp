#include <cmath>
#include <cstring>

#include "penumbra/errors.hpp"
#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

// A validated accessor: `count` elements of `element_size` bytes, `stride` apart, the last
// one ending inside its buffer.
struct AccessorBytes {
    const unsigned char* first = nullptr;
    size_t count = 0;
    size_t stride = 0;
    int component_type = 0;
    int component_count = 0;
    bool normalized = false;
};

std::string component_type_name(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_INT:
            return "INT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return "FLOAT";
        default:
            return "component type " + std::to_string(component_type);
    }
}

const tinygltf::BufferView& checked_buffer_view(const GltfSource& source, const tinygltf::Accessor& accessor,
                                                const std::string& where) {
    const tinygltf::Model& model = source.model;
    if (accessor.bufferView < 0 || static_cast<size_t>(accessor.bufferView) >= model.bufferViews.size()) {
        source.fail(where, "accessor has bufferView " + std::to_string(accessor.bufferView) + " but the file has " +
                               std::to_string(model.bufferViews.size()) + " buffer views");
    }
    const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(accessor.bufferView)];
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size()) {
        source.fail(where, "bufferViews[" + std::to_string(accessor.bufferView) + "] refers to buffer " +
                               std::to_string(view.buffer) + " but the file has " +
                               std::to_string(model.buffers.size()) + " buffers");
    }
    const size_t buffer_size = model.buffers[static_cast<size_t>(view.buffer)].data.size();
    if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
        source.fail(where, "bufferViews[" + std::to_string(accessor.bufferView) + "] spans bytes " +
                               std::to_string(view.byteOffset) + ".." +
                               std::to_string(view.byteOffset + view.byteLength) + " of a buffer of " +
                               std::to_string(buffer_size) + " bytes");
    }
    return view;
}

AccessorBytes checked_accessor(const GltfSource& source, int index, const std::string& where) {
    const tinygltf::Model& model = source.model;
    if (index < 0 || static_cast<size_t>(index) >= model.accessors.size()) {
        source.fail(where, "accessor " + std::to_string(index) + " does not exist (the file has " +
                               std::to_string(model.accessors.size()) + " accessors)");
    }
    const tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(index)];
    const std::string accessor_where = where + " (accessors[" + std::to_string(index) + "])";
    if (accessor.sparse.isSparse) source.fail(accessor_where, "sparse accessors are not supported");
    const int component_size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(accessor.componentType));
    const int component_count = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
    if (component_size <= 0 || component_count <= 0) {
        source.fail(accessor_where, "invalid componentType " + std::to_string(accessor.componentType) + " or type " +
                                        std::to_string(accessor.type));
    }
    const tinygltf::BufferView& view = checked_buffer_view(source, accessor, accessor_where);
    const size_t element_size = static_cast<size_t>(component_size) * static_cast<size_t>(component_count);
    const size_t stride = view.byteStride != 0 ? view.byteStride : element_size;
    if (stride < element_size) {
        source.fail(accessor_where, "byteStride " + std::to_string(stride) + " is smaller than the element size " +
                                        std::to_string(element_size));
    }
    AccessorBytes bytes{nullptr, accessor.count, stride, accessor.componentType, component_count, accessor.normalized};
    if (accessor.count == 0) return bytes;
    // count <= byteLength keeps (count - 1) * stride from overflowing (stride <= 255 in valid
    // files, but a malformed one may say anything, hence the division).
    const bool fits = accessor.byteOffset <= view.byteLength &&
                      accessor.count - 1 <= (view.byteLength - accessor.byteOffset) / stride &&
                      (accessor.count - 1) * stride + element_size <= view.byteLength - accessor.byteOffset;
    if (!fits) {
        source.fail(accessor_where, std::to_string(accessor.count) + " elements of " + std::to_string(element_size) +
                                        " bytes at offset " + std::to_string(accessor.byteOffset) + " (stride " +
                                        std::to_string(stride) + ") overrun bufferViews[" +
                                        std::to_string(accessor.bufferView) + "] of " +
                                        std::to_string(view.byteLength) + " bytes");
    }
    bytes.first = model.buffers[static_cast<size_t>(view.buffer)].data.data() + view.byteOffset + accessor.byteOffset;
    return bytes;
}

template <typename T>
T read_unaligned(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
}

// One component as a float, applying the glTF normalisation rule for unsigned types.
float read_normalized_component(const AccessorBytes& bytes, size_t element, int component) {
    const unsigned char* at = bytes.first + element * bytes.stride;
    switch (bytes.component_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return read_unaligned<float>(at + 4 * component);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return static_cast<float>(at[component]) / 255.0f;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return static_cast<float>(read_unaligned<uint16_t>(at + 2 * component)) / 65535.0f;
        default:
            return 0.0f;  // excluded by the callers' type checks
    }
}

void require_layout(const GltfSource& source, const AccessorBytes& bytes, int component_count, bool type_ok,
                    const std::string& expected, const std::string& where) {
    if (bytes.component_count != component_count || !type_ok) {
        source.fail(where, "expected " + expected + ", got " + std::to_string(bytes.component_count) +
                               " components of " + component_type_name(bytes.component_type));
    }
}

}  // namespace

void GltfSource::fail(const std::string& where, const std::string& problem) const {
    throw InputError(origin + ": " + where + ": " + problem);
}

size_t accessor_count(const GltfSource& source, int accessor, const std::string& where) {
    return checked_accessor(source, accessor, where).count;
}

std::vector<glm::vec3> read_float_vec3_accessor(const GltfSource& source, int accessor, const std::string& where) {
    const AccessorBytes bytes = checked_accessor(source, accessor, where);
    require_layout(source, bytes, 3, bytes.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT, "VEC3 of FLOAT", where);
    std::vector<glm::vec3> values(bytes.count);
    for (size_t i = 0; i < bytes.count; ++i) {
        std::memcpy(&values[i], bytes.first + i * bytes.stride, sizeof(glm::vec3));
        if (!std::isfinite(values[i].x) || !std::isfinite(values[i].y) || !std::isfinite(values[i].z)) {
            source.fail(where, "element " + std::to_string(i) + " is not a finite number");
        }
    }
    return values;
}

std::vector<glm::vec2> read_texcoord_accessor(const GltfSource& source, int accessor, const std::string& where) {
    const AccessorBytes bytes = checked_accessor(source, accessor, where);
    const bool type_ok = bytes.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                         (bytes.normalized && (bytes.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                               bytes.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
    require_layout(source, bytes, 2, type_ok, "VEC2 of FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT", where);
    std::vector<glm::vec2> values(bytes.count);
    for (size_t i = 0; i < bytes.count; ++i) {
        values[i] = {read_normalized_component(bytes, i, 0), read_normalized_component(bytes, i, 1)};
    }
    return values;
}

std::vector<uint32_t> read_index_accessor(const GltfSource& source, int accessor, const std::string& where) {
    const AccessorBytes bytes = checked_accessor(source, accessor, where);
    const int type = bytes.component_type;
    const bool type_ok = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                         type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    require_layout(source, bytes, 1, type_ok, "SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT", where);
    std::vector<uint32_t> indices(bytes.count);
    for (size_t i = 0; i < bytes.count; ++i) {
        const unsigned char* at = bytes.first + i * bytes.stride;
        if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) indices[i] = at[0];
        if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) indices[i] = read_unaligned<uint16_t>(at);
        if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) indices[i] = read_unaligned<uint32_t>(at);
    }
    return indices;
}

}  // namespace penumbra
