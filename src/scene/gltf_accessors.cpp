#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "penumbra/errors.hpp"
#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

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

// `length` bytes at `offset` in buffer view `view_index`, checked against the view and its
// buffer (sizes from a malformed file may say anything: every sum is checked for overflow).
const unsigned char* checked_view_range(const GltfSource& source, int view_index, size_t offset, size_t length,
                                        const std::string& where) {
    const tinygltf::Model& model = source.model;
    if (view_index < 0 || static_cast<size_t>(view_index) >= model.bufferViews.size()) {
        source.fail(where, "bufferView " + std::to_string(view_index) + " does not exist (the file has " +
                               std::to_string(model.bufferViews.size()) + " buffer views)");
    }
    const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(view_index)];
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size()) {
        source.fail(where, "bufferViews[" + std::to_string(view_index) + "] refers to buffer " +
                               std::to_string(view.buffer) + " but the file has " +
                               std::to_string(model.buffers.size()) + " buffers");
    }
    const size_t buffer_size = model.buffers[static_cast<size_t>(view.buffer)].data.size();
    if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
        source.fail(where, "bufferViews[" + std::to_string(view_index) + "] spans bytes " +
                               std::to_string(view.byteOffset) + ".." +
                               std::to_string(view.byteOffset + view.byteLength) + " of a buffer of " +
                               std::to_string(buffer_size) + " bytes");
    }
    if (offset > view.byteLength || length > view.byteLength - offset) {
        source.fail(where, std::to_string(length) + " bytes at offset " + std::to_string(offset) +
                               " overrun bufferViews[" + std::to_string(view_index) + "] of " +
                               std::to_string(view.byteLength) + " bytes");
    }
    return model.buffers[static_cast<size_t>(view.buffer)].data.data() + view.byteOffset + offset;
}

struct AccessorLayout {
    const tinygltf::Accessor* accessor = nullptr;
    std::string where;  // "<use> (accessors[i])"
    size_t component_size = 0;
    size_t component_count = 0;
    bool normalized = false;  // integer components map to [0, 1] or [-1, 1] (never for indices)
    size_t element_size() const { return component_size * component_count; }
};

AccessorLayout checked_layout(const GltfSource& source, int index, const std::string& where) {
    const tinygltf::Model& model = source.model;
    if (index < 0 || static_cast<size_t>(index) >= model.accessors.size()) {
        source.fail(where, "accessor " + std::to_string(index) + " does not exist (the file has " +
                               std::to_string(model.accessors.size()) + " accessors)");
    }
    AccessorLayout layout;
    layout.accessor = &model.accessors[static_cast<size_t>(index)];
    layout.where = where + " (accessors[" + std::to_string(index) + "])";
    const int component_size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(layout.accessor->componentType));
    const int component_count = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(layout.accessor->type));
    if (component_size <= 0 || component_count <= 0) {
        source.fail(layout.where, "invalid componentType " + std::to_string(layout.accessor->componentType) +
                                      " or type " + std::to_string(layout.accessor->type));
    }
    layout.component_size = static_cast<size_t>(component_size);
    layout.component_count = static_cast<size_t>(component_count);
    layout.normalized = layout.accessor->normalized;
    return layout;
}

template <typename T>
T read_unaligned(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
}

// One component; integers normalised where the accessor says so (glTF 2.0, 3.11: signed
// types map to [-1, 1] with the most negative value clamped, unsigned ones to [0, 1]).
double read_component(const unsigned char* at, int component_type, bool normalized) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return read_unaligned<float>(at);
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const double value = static_cast<int8_t>(at[0]);
            return normalized ? std::max(value / 127.0, -1.0) : value;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return normalized ? at[0] / 255.0 : at[0];
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const double value = read_unaligned<int16_t>(at);
            return normalized ? std::max(value / 32767.0, -1.0) : value;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const double value = read_unaligned<uint16_t>(at);
            return normalized ? value / 65535.0 : value;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return read_unaligned<uint32_t>(at);
        default:
            return 0.0;  // excluded by checked_layout and the callers' type checks
    }
}

// The dense part: `count` elements from the buffer view, or zeros without one (glTF 2.0,
// 3.6.2.3: how a sparse accessor without a bufferView starts).
void read_dense(const GltfSource& source, const AccessorLayout& layout, std::vector<double>& values) {
    const tinygltf::Accessor& accessor = *layout.accessor;
    if (accessor.bufferView < 0) {
        if (accessor.count > kMaxGltfElementsWithoutData) {
            source.fail(layout.where, std::to_string(accessor.count) + " elements without a bufferView exceed " +
                                          std::to_string(kMaxGltfElementsWithoutData));
        }
        values.assign(accessor.count * layout.component_count, 0.0);
        return;
    }
    const unsigned char* view_start = checked_view_range(source, accessor.bufferView, 0, 0, layout.where);
    const tinygltf::BufferView& view = source.model.bufferViews[static_cast<size_t>(accessor.bufferView)];
    const size_t element_size = layout.element_size();
    const size_t stride = view.byteStride != 0 ? view.byteStride : element_size;
    if (stride < element_size) {
        source.fail(layout.where, "byteStride " + std::to_string(stride) + " is smaller than the element size " +
                                      std::to_string(element_size));
    }
    // count - 1 <= (byteLength - byteOffset) / stride keeps (count - 1) * stride from overflowing.
    const bool fits =
        accessor.count == 0 || (accessor.byteOffset <= view.byteLength &&
                                accessor.count - 1 <= (view.byteLength - accessor.byteOffset) / stride &&
                                (accessor.count - 1) * stride + element_size <= view.byteLength - accessor.byteOffset);
    if (!fits) {
        source.fail(layout.where, std::to_string(accessor.count) + " elements of " + std::to_string(element_size) +
                                      " bytes at offset " + std::to_string(accessor.byteOffset) + " (stride " +
                                      std::to_string(stride) + ") overrun bufferViews[" +
                                      std::to_string(accessor.bufferView) + "] of " + std::to_string(view.byteLength) +
                                      " bytes");
    }
    const unsigned char* first = view_start + accessor.byteOffset;
    values.resize(accessor.count * layout.component_count);
    for (size_t i = 0; i < accessor.count; ++i) {
        for (size_t c = 0; c < layout.component_count; ++c) {
            values[i * layout.component_count + c] = read_component(first + i * stride + c * layout.component_size,
                                                                    accessor.componentType, layout.normalized);
        }
    }
}

// glTF 2.0, 3.6.2.3: `sparse.count` strictly increasing element indices, each replaced by
// the tightly packed element of the values' view.
void apply_sparse(const GltfSource& source, const AccessorLayout& layout, std::vector<double>& values) {
    const tinygltf::Accessor& accessor = *layout.accessor;
    const auto& sparse = accessor.sparse;
    const std::string where = layout.where + ".sparse";
    if (sparse.count < 1 || static_cast<size_t>(sparse.count) > accessor.count) {
        source.fail(where + ".count",
                    "expected 1.." + std::to_string(accessor.count) + ", got " + std::to_string(sparse.count));
    }
    const auto count = static_cast<size_t>(sparse.count);
    const int index_type = sparse.indices.componentType;
    if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        source.fail(where + ".indices.componentType",
                    "expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT, got " + component_type_name(index_type));
    }
    if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) {
        source.fail(where, "a byteOffset is negative");
    }
    const auto index_size = static_cast<size_t>(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(index_type)));
    const unsigned char* indices =
        checked_view_range(source, sparse.indices.bufferView, static_cast<size_t>(sparse.indices.byteOffset),
                           count * index_size, where + ".indices");
    const size_t element_size = layout.element_size();
    const unsigned char* replacements =
        checked_view_range(source, sparse.values.bufferView, static_cast<size_t>(sparse.values.byteOffset),
                           count * element_size, where + ".values");
    size_t previous = 0;
    for (size_t i = 0; i < count; ++i) {
        const auto element = static_cast<size_t>(read_component(indices + i * index_size, index_type, false));
        if (element >= accessor.count) {
            source.fail(where + ".indices", "index " + std::to_string(element) + " at position " + std::to_string(i) +
                                                " is out of range (the accessor has " + std::to_string(accessor.count) +
                                                " elements)");
        }
        if (i > 0 && element <= previous) {
            source.fail(where + ".indices", "index " + std::to_string(element) + " at position " + std::to_string(i) +
                                                " does not increase (glTF requires strictly increasing indices)");
        }
        previous = element;
        for (size_t c = 0; c < layout.component_count; ++c) {
            values[element * layout.component_count + c] = read_component(
                replacements + i * element_size + c * layout.component_size, accessor.componentType, layout.normalized);
        }
    }
}

// The component types a use accepts: glTF 2.0 core (3.7.2.1) and, where the file uses
// KHR_mesh_quantization, the integer types that extension adds.
struct Accepted {
    const char* core;                                   // described for the error message
    std::vector<std::pair<int, bool>> core_types;       // (componentType, normalized)
    std::vector<std::pair<int, bool>> quantized_types;  // with KHR_mesh_quantization
};

constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kUbyte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;
constexpr int kUshort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;

const Accepted& accepted(GltfAttribute use) {
    static const Accepted position{"VEC3 of FLOAT",
                                   {{kFloat, false}},
                                   {{kByte, false},
                                    {kByte, true},
                                    {kUbyte, false},
                                    {kUbyte, true},
                                    {kShort, false},
                                    {kShort, true},
                                    {kUshort, false},
                                    {kUshort, true}}};
    static const Accepted normal{"VEC3 of FLOAT", {{kFloat, false}}, {{kByte, true}, {kShort, true}}};
    static const Accepted texcoord{
        "VEC2 of FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT",
        {{kFloat, false}, {kUbyte, true}, {kUshort, true}},
        {{kByte, false}, {kByte, true}, {kUbyte, false}, {kShort, false}, {kShort, true}, {kUshort, false}}};
    static const Accepted position_delta{
        "VEC3 of FLOAT", {{kFloat, false}}, {{kByte, false}, {kByte, true}, {kShort, false}, {kShort, true}}};
    // glTF 2.0, 3.7.2.1: COLOR_n is VEC3 or VEC4 of these (no quantized extras).
    static const Accepted color{"VEC3 or VEC4 of FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT",
                                {{kFloat, false}, {kUbyte, true}, {kUshort, true}},
                                {}};
    switch (use) {
        case GltfAttribute::Color:
            return color;
        case GltfAttribute::Position:
            return position;
        case GltfAttribute::Normal:
        case GltfAttribute::NormalDelta:
            return normal;
        case GltfAttribute::Texcoord:
            return texcoord;
        case GltfAttribute::PositionDelta:
            return position_delta;
    }
    return position;
}

bool listed(const std::vector<std::pair<int, bool>>& types, int component_type, bool normalized) {
    return std::find(types.begin(), types.end(), std::make_pair(component_type, normalized)) != types.end();
}

std::string describe_type(const tinygltf::Accessor& accessor, size_t component_count) {
    return std::to_string(component_count) + " components of " + (accessor.normalized ? "normalized " : "") +
           component_type_name(accessor.componentType);
}

// Every element's components, dense data then the sparse substitution.
std::vector<double> read_values(const GltfSource& source, const AccessorLayout& layout) {
    std::vector<double> values;
    read_dense(source, layout, values);
    if (layout.accessor->sparse.isSparse) apply_sparse(source, layout, values);
    return values;
}

}  // namespace

bool GltfSource::uses_extension(const std::string& name) const {
    return std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), name) != model.extensionsUsed.end() ||
           std::find(model.extensionsRequired.begin(), model.extensionsRequired.end(), name) !=
               model.extensionsRequired.end();
}

void GltfSource::fail(const std::string& where, const std::string& problem) const {
    throw InputError(origin + ": " + where + ": " + problem);
}

size_t accessor_count(const GltfSource& source, int accessor, const std::string& where) {
    return checked_layout(source, accessor, where).accessor->count;
}

namespace {

// VEC2 or VEC3 of a type `use` accepts, as floats (finite and within kMaxNumberMagnitude).
template <typename Vector>
std::vector<Vector> read_vector_accessor(const GltfSource& source, int index, GltfAttribute use,
                                         const std::string& where) {
    constexpr auto kComponents = static_cast<size_t>(Vector::length());
    const AccessorLayout layout = checked_layout(source, index, where);
    const tinygltf::Accessor& accessor = *layout.accessor;
    const Accepted& types = accepted(use);
    const bool core = listed(types.core_types, accessor.componentType, accessor.normalized);
    const bool quantized = listed(types.quantized_types, accessor.componentType, accessor.normalized);
    if (layout.component_count != kComponents || !(core || quantized)) {
        source.fail(where,
                    "expected " + std::string(types.core) + ", got " + describe_type(accessor, layout.component_count));
    }
    if (!core && !source.uses_extension("KHR_mesh_quantization")) {
        source.fail(where, describe_type(accessor, layout.component_count) +
                               " needs the KHR_mesh_quantization extension, which the file does not declare");
    }
    const std::vector<double> values = read_values(source, layout);
    std::vector<Vector> vectors(accessor.count);
    for (size_t i = 0; i < accessor.count; ++i) {
        for (size_t c = 0; c < kComponents; ++c) {
            const double value = values[i * kComponents + c];
            if (!std::isfinite(value) || std::abs(value) > kMaxNumberMagnitude) {
                source.fail(where, "element " + std::to_string(i) + " is not a finite number within 1e9");
            }
            vectors[i][static_cast<glm::length_t>(c)] = static_cast<float>(value);
        }
    }
    return vectors;
}

}  // namespace

std::vector<glm::vec3> read_vec3_accessor(const GltfSource& source, int accessor, GltfAttribute use,
                                          const std::string& where) {
    return read_vector_accessor<glm::vec3>(source, accessor, use, where);
}

std::vector<glm::vec2> read_texcoord_accessor(const GltfSource& source, int accessor, const std::string& where) {
    return read_vector_accessor<glm::vec2>(source, accessor, GltfAttribute::Texcoord, where);
}

std::vector<glm::vec4> read_color_accessor(const GltfSource& source, int accessor, const std::string& where) {
    if (checked_layout(source, accessor, where).component_count == 4) {
        return read_vector_accessor<glm::vec4>(source, accessor, GltfAttribute::Color, where);
    }
    const std::vector<glm::vec3> rgb = read_vector_accessor<glm::vec3>(source, accessor, GltfAttribute::Color, where);
    std::vector<glm::vec4> colors(rgb.size());
    for (size_t i = 0; i < rgb.size(); ++i) colors[i] = glm::vec4{rgb[i], 1.0f};
    return colors;
}

std::vector<uint32_t> read_index_accessor(const GltfSource& source, int index, const std::string& where) {
    const AccessorLayout layout = checked_layout(source, index, where);
    const int type = layout.accessor->componentType;
    const bool type_ok = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                         type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    if (layout.component_count != 1 || !type_ok) {
        source.fail(where, "expected SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT, got " +
                               describe_type(*layout.accessor, layout.component_count));
    }
    AccessorLayout plain = layout;
    plain.normalized = false;  // indices are never normalised
    const std::vector<double> values = read_values(source, plain);
    std::vector<uint32_t> indices(values.size());
    for (size_t i = 0; i < values.size(); ++i) indices[i] = static_cast<uint32_t>(values[i]);
    return indices;
}

}  // namespace penumbra
