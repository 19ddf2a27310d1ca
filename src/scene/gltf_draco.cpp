// KHR_draco_mesh_compression (glTF extension, Khronos/KHR_draco_mesh_compression/README.md):
// a primitive whose attributes and indices are one Draco-compressed mesh in a buffer view.
// The extension's `attributes` map each glTF attribute to a Draco attribute's unique id; the
// primitive's accessors keep their count, type and bounds but have no data of their own.
// Each decoded primitive gets new FLOAT accessors (Draco dequantizes positions, normals and
// texture coordinates while decoding) and an UNSIGNED_INT index accessor from its faces.
//
// When a file also carries uncompressed fallback accessors (the extension only in
// extensionsUsed), the decoded data is used all the same: the extension's rule for a loader
// that supports it, and one path for every Draco primitive, whether or not a fallback exists.
#include <draco/compression/decode.h>

#include <cstring>
#include <memory>
#include <type_traits>

#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

constexpr const char* kExtension = "KHR_draco_mesh_compression";

// One glTF attribute of the primitive and the Draco attribute that holds it.
struct MappedAttribute {
    std::string name;
    int accessor = -1;
    uint32_t draco_id = 0;
    size_t components = 0;
};

struct DracoPrimitive {
    size_t buffer_view = 0;
    std::vector<MappedAttribute> attributes;
};

size_t component_count(const GltfSource& source, const tinygltf::Accessor& accessor, const std::string& where) {
    const int count = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
    if (count <= 0 || count > 4) source.fail(where, "expected a SCALAR or VEC2 to VEC4 accessor");
    return static_cast<size_t>(count);
}

// The extension's attributes must be a subset of the primitive's (the extension's
// "Conformance"): each names an accessor the primitive has.
DracoPrimitive read_extension(const GltfSource& source, const tinygltf::Primitive& primitive,
                              const tinygltf::Value& extension, const std::string& where) {
    if (!extension.IsObject()) source.fail(where, "expected an object");
    DracoPrimitive draco;
    draco.buffer_view = extension_integer(source, extension, "bufferView", where);
    if (draco.buffer_view >= source.model.bufferViews.size()) {
        source.fail(where + ".bufferView", "bufferView " + std::to_string(draco.buffer_view) +
                                               " does not exist (the file has " +
                                               std::to_string(source.model.bufferViews.size()) + " buffer views)");
    }
    if (!extension.Has("attributes") || !extension.Get("attributes").IsObject()) {
        source.fail(where + ".attributes", "expected an object mapping attribute names to Draco ids");
    }
    const tinygltf::Value& attributes = extension.Get("attributes");
    for (const std::string& name : attributes.Keys()) {
        const auto accessor = primitive.attributes.find(name);
        if (accessor == primitive.attributes.end()) {
            source.fail(where + ".attributes." + name, "the primitive has no " + name + " attribute");
        }
        const std::string at = where + ".attributes";
        const auto id = extension_integer(source, attributes, name.c_str(), at);
        if (accessor->second < 0 || static_cast<size_t>(accessor->second) >= source.model.accessors.size()) {
            source.fail(where + ".attributes." + name, "the primitive's accessor does not exist");
        }
        const tinygltf::Accessor& gltf = source.model.accessors[static_cast<size_t>(accessor->second)];
        draco.attributes.push_back(
            {name, accessor->second, static_cast<uint32_t>(id), component_count(source, gltf, at + "." + name)});
    }
    return draco;
}

// What the decoded primitive will take, from its accessors' counts, before decoding.
uint64_t declared_bytes(const GltfSource& source, const tinygltf::Primitive& primitive, const DracoPrimitive& draco) {
    uint64_t bytes = 0;
    for (const MappedAttribute& attribute : draco.attributes) {
        const size_t count = source.model.accessors[static_cast<size_t>(attribute.accessor)].count;
        bytes = saturating_add(bytes, saturating_multiply(count, attribute.components * sizeof(float)));
    }
    if (primitive.indices >= 0 && static_cast<size_t>(primitive.indices) < source.model.accessors.size()) {
        const size_t count = source.model.accessors[static_cast<size_t>(primitive.indices)].count;
        bytes = saturating_add(bytes, saturating_multiply(count, sizeof(uint32_t)));
    }
    return bytes;
}

std::unique_ptr<draco::Mesh> decode_mesh(const GltfSource& source, const DracoPrimitive& draco,
                                         const std::string& where) {
    const tinygltf::BufferView& view = source.model.bufferViews[draco.buffer_view];
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= source.model.buffers.size()) {
        source.fail(where + ".bufferView", "its buffer " + std::to_string(view.buffer) + " does not exist");
    }
    const std::vector<unsigned char>& bytes = source.model.buffers[static_cast<size_t>(view.buffer)].data;
    if (view.byteOffset > bytes.size() || view.byteLength > bytes.size() - view.byteOffset) {
        source.fail(where + ".bufferView", "bufferViews[" + std::to_string(draco.buffer_view) +
                                               "] overruns its buffer of " + std::to_string(bytes.size()) + " bytes");
    }
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes.data() + view.byteOffset), view.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) {
        source.fail(where, "cannot decode the Draco mesh in bufferViews[" + std::to_string(draco.buffer_view) +
                               "]: " + decoded.status().error_msg_string());
    }
    return std::move(decoded).value();
}

// The decoded values of one attribute, point by point, as `components` floats each.
std::vector<float> read_attribute(const GltfSource& source, const draco::Mesh& mesh, const MappedAttribute& mapped,
                                  const std::string& where) {
    const draco::PointAttribute* attribute = mesh.GetAttributeByUniqueId(mapped.draco_id);
    const std::string at = where + ".attributes." + mapped.name;
    if (attribute == nullptr) {
        source.fail(at, "Draco attribute " + std::to_string(mapped.draco_id) + " does not exist (the mesh has " +
                            std::to_string(mesh.num_attributes()) + " attributes)");
    }
    if (attribute->num_components() != mapped.components) {
        source.fail(at, "the Draco attribute has " + std::to_string(attribute->num_components()) +
                            " components, the accessor " + std::to_string(mapped.components));
    }
    // Draco's point-to-value map is read without bounds checks: it must cover every point.
    if (!attribute->is_mapping_identity() && attribute->indices_map_size() < mesh.num_points()) {
        source.fail(at, "the Draco attribute maps " + std::to_string(attribute->indices_map_size()) + " of " +
                            std::to_string(mesh.num_points()) + " points");
    }
    std::vector<float> values(size_t{mesh.num_points()} * mapped.components);
    for (draco::PointIndex point(0); point < mesh.num_points(); ++point) {
        float* out = values.data() + size_t{point.value()} * mapped.components;
        if (!attribute->ConvertValue<float>(attribute->mapped_index(point), static_cast<int8_t>(mapped.components),
                                            out)) {
            source.fail(at, "the Draco attribute's values cannot be read as numbers");
        }
    }
    return values;
}

std::vector<uint32_t> read_faces(const draco::Mesh& mesh) {
    std::vector<uint32_t> indices;
    indices.reserve(size_t{mesh.num_faces()} * 3);
    for (draco::FaceIndex face(0); face < mesh.num_faces(); ++face) {
        for (const draco::PointIndex& corner : mesh.face(face)) indices.push_back(corner.value());
    }
    return indices;
}

// The decoded mesh stands, whatever the accessors' counts say: the Khronos samples made
// by COLLADA2GLTF before 2018 declare the counts from before Draco's encoder merged or split
// points and left out degenerate faces (2CylinderEngine's meshes[1]: 936 indices declared,
// 792 corners decoded; Buggy: 3,454 points declared, 3,623 decoded), and the decoded indices
// index the decoded points. Only dropping faces is the encoder's to do: more corners than
// the index accessor declares is an error. What the points take beyond the declared size
// is taken from the allowance after decoding; the triangle budget counts the decoded
// indices.
void check_decoded_size(const GltfSource& source, const tinygltf::Primitive& primitive, const DracoPrimitive& draco,
                        const draco::Mesh& mesh, uint64_t declared, GltfDecodeAllowance& allowance,
                        const std::string& where) {
    const uint64_t corners = uint64_t{mesh.num_faces()} * 3;
    if (primitive.indices >= 0 && source.model.accessors[static_cast<size_t>(primitive.indices)].count < corners) {
        source.fail(where, "the Draco mesh decodes " + std::to_string(corners) + " corners, more than the " +
                               std::to_string(source.model.accessors[static_cast<size_t>(primitive.indices)].count) +
                               " of the index accessor");
    }
    uint64_t decoded = saturating_multiply(corners, sizeof(uint32_t));
    for (const MappedAttribute& attribute : draco.attributes) {
        decoded = saturating_add(decoded, saturating_multiply(mesh.num_points(), attribute.components * sizeof(float)));
    }
    if (decoded > declared) take_decoded_bytes(source, allowance, decoded - declared, where);
}

// A new buffer, view and accessor holding `values`; returns the accessor's index.
template <typename T>
int append_accessor(tinygltf::Model& model, const std::vector<T>& values, tinygltf::Accessor accessor,
                    const std::string& where) {
    tinygltf::Buffer buffer;
    buffer.data.resize(values.size() * sizeof(T));
    if (!values.empty()) std::memcpy(buffer.data.data(), values.data(), buffer.data.size());
    buffer.uri = "(decoded " + where + ")";
    tinygltf::BufferView view;
    view.buffer = static_cast<int>(model.buffers.size());
    view.byteLength = buffer.data.size();
    model.buffers.push_back(std::move(buffer));
    accessor.bufferView = static_cast<int>(model.bufferViews.size());
    accessor.byteOffset = 0;
    accessor.sparse.isSparse = false;
    accessor.normalized = false;
    accessor.componentType =
        std::is_same_v<T, float> ? TINYGLTF_COMPONENT_TYPE_FLOAT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    model.bufferViews.push_back(std::move(view));
    model.accessors.push_back(std::move(accessor));
    return static_cast<int>(model.accessors.size() - 1);
}

void decode_primitive(tinygltf::Model& model, const GltfSource& source, tinygltf::Primitive& primitive,
                      GltfDecodeAllowance& allowance, const std::string& where) {
    const std::string at = where + ".extensions." + kExtension;
    // Draco encodes triangle meshes and point clouds; points and lines cast no shadow and
    // are dropped unread, and strips and fans have no Draco form.
    if (primitive.mode == TINYGLTF_MODE_POINTS || primitive.mode == TINYGLTF_MODE_LINE ||
        primitive.mode == TINYGLTF_MODE_LINE_LOOP || primitive.mode == TINYGLTF_MODE_LINE_STRIP) {
        return;
    }
    if (primitive.mode != -1 && primitive.mode != TINYGLTF_MODE_TRIANGLES) {
        source.fail(where + ".mode",
                    "a Draco-compressed primitive must be TRIANGLES, got " + std::to_string(primitive.mode));
    }
    const DracoPrimitive draco = read_extension(source, primitive, primitive.extensions.at(kExtension), at);
    const uint64_t declared = declared_bytes(source, primitive, draco);
    take_decoded_bytes(source, allowance, declared, at);
    const std::unique_ptr<draco::Mesh> mesh = decode_mesh(source, draco, at);
    check_decoded_size(source, primitive, draco, *mesh, declared, allowance, at);
    for (const MappedAttribute& attribute : draco.attributes) {
        const std::vector<float> values = read_attribute(source, *mesh, attribute, at);
        tinygltf::Accessor decoded = model.accessors[static_cast<size_t>(attribute.accessor)];
        decoded.count = mesh->num_points();
        primitive.attributes[attribute.name] = append_accessor(model, values, decoded, at);
    }
    tinygltf::Accessor indices;
    indices.type = TINYGLTF_TYPE_SCALAR;
    indices.count = size_t{mesh->num_faces()} * 3;
    primitive.indices = append_accessor(model, read_faces(*mesh), indices, at);
}

}  // namespace

void decode_draco_primitives(tinygltf::Model& model, const GltfSource& source, GltfDecodeAllowance& allowance) {
    for (size_t m = 0; m < model.meshes.size(); ++m) {
        for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
            tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
            if (primitive.extensions.count(kExtension) == 0) continue;
            decode_primitive(model, source, primitive, allowance,
                             "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "]");
        }
    }
}

}  // namespace penumbra
