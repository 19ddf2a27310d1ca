// Compressed geometry, decoded before the rest of the loader sees the model: once a
// EXT_meshopt_compression buffer view holds its decoded bytes and a
// KHR_draco_mesh_compression primitive names plain accessors, the checked accessor readers,
// the load budget and the conversion treat them like any other data.
#include <algorithm>
#include <nlohmann/json.hpp>

#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

using Json = nlohmann::json;

// EXT_meshopt_compression, "Fallback buffers": a placeholder buffer has no uri (in a GLB,
// buffer 0 without a uri is the BIN chunk, so placeholders have index 1 or above).
bool is_meshopt_placeholder(const Json& buffer, size_t index, bool binary) {
    return buffer.is_object() && !buffer.contains("uri") && !(binary && index == 0);
}

bool lists_extension(const Json& document, const char* list, const char* extension) {
    if (!document.contains(list) || !document[list].is_array()) return false;
    for (const Json& name : document[list]) {
        if (name.is_string() && name.get_ref<const std::string&>() == extension) return true;
    }
    return false;
}

void stand_in_placeholder_buffers(Json& document, bool binary, GltfStandIns& stand_ins) {
    if (!document.contains("buffers") || !document["buffers"].is_array()) return;
    Json& buffers = document["buffers"];
    for (size_t i = 0; i < buffers.size(); ++i) {
        if (!is_meshopt_placeholder(buffers[i], i, binary)) continue;
        buffers[i]["uri"] = "data:application/octet-stream;base64,AA==";  // one zero byte
        buffers[i]["byteLength"] = 1;
        stand_ins.placeholder_buffers.push_back(i);
    }
}

// The index accessor of a Draco primitive, when it has no bufferView, gets the primitive's
// Draco bufferView (the JSON checks have held both indices in range).
void stand_in_draco_index_views(Json& document, GltfStandIns& stand_ins) {
    if (!document.contains("meshes") || !document["meshes"].is_array() || !document.contains("accessors") ||
        !document["accessors"].is_array()) {
        return;
    }
    Json& accessors = document["accessors"];
    for (const Json& mesh : document["meshes"]) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (const Json& primitive : mesh["primitives"]) {
            if (!primitive.is_object() || !primitive.contains("indices") || !primitive.contains("extensions")) continue;
            const Json& extensions = primitive["extensions"];
            if (!extensions.is_object() || !extensions.contains("KHR_draco_mesh_compression")) continue;
            const Json& draco = extensions["KHR_draco_mesh_compression"];
            if (!draco.is_object() || !draco.contains("bufferView") || !draco["bufferView"].is_number_unsigned()) {
                continue;
            }
            const Json& indices = primitive["indices"];
            if (!indices.is_number_unsigned() || indices.get<uint64_t>() >= accessors.size()) continue;
            Json& accessor = accessors[indices.get<size_t>()];
            if (!accessor.is_object() || accessor.contains("bufferView")) continue;
            accessor["bufferView"] = draco["bufferView"];
            stand_ins.draco_index_accessors.push_back(indices.get<size_t>());
        }
    }
}

// tinygltf can hold no placeholder: it refuses a buffer without a uri, and would copy a
// GLB's BIN chunk into each one. Their views name them, but only their decoded bytes are read.
void refuse_views_of_placeholders(const tinygltf::Model& model, const GltfSource& source) {
    for (size_t i = 0; i < model.bufferViews.size(); ++i) {
        const int buffer = model.bufferViews[i].buffer;
        if (buffer < 0 || static_cast<size_t>(buffer) >= model.buffers.size()) continue;
        if (!is_placeholder_buffer(model.buffers[static_cast<size_t>(buffer)])) continue;
        source.fail("bufferViews[" + std::to_string(i) + "]",
                    "names buffers[" + std::to_string(buffer) +
                        "], which has no uri (an EXT_meshopt_compression fallback), but the view is not compressed");
    }
}

// What the model's images take once tinygltf has decoded them, as RGBA8 (what the scene keeps).
uint64_t decoded_image_bytes(const tinygltf::Model& model) {
    uint64_t bytes = 0;
    for (const tinygltf::Image& image : model.images) {
        const uint64_t pixels = uint64_t(std::max(image.width, 0)) * uint64_t(std::max(image.height, 0));
        bytes = saturating_add(bytes, saturating_multiply(pixels, 4));
    }
    return bytes;
}

}  // namespace

std::optional<GltfStandIns> json_with_stand_ins(std::string_view json, bool binary) {
    Json document = Json::parse(json.begin(), json.end(), nullptr, false);
    if (document.is_discarded() || !document.is_object()) return std::nullopt;
    GltfStandIns stand_ins;
    if (lists_extension(document, "extensionsUsed", "EXT_meshopt_compression") ||
        lists_extension(document, "extensionsRequired", "EXT_meshopt_compression")) {
        stand_in_placeholder_buffers(document, binary, stand_ins);
    }
    stand_in_draco_index_views(document, stand_ins);
    if (stand_ins.placeholder_buffers.empty() && stand_ins.draco_index_accessors.empty()) return std::nullopt;
    stand_ins.json = document.dump();
    return stand_ins;
}

void remove_stand_ins(tinygltf::Model& model, const GltfStandIns& stand_ins) {
    for (const size_t index : stand_ins.placeholder_buffers) {
        model.buffers[index].uri.clear();
        model.buffers[index].data.clear();
    }
    for (const size_t index : stand_ins.draco_index_accessors) model.accessors[index].bufferView = -1;
}

void take_decoded_bytes(const GltfSource& source, GltfDecodeAllowance& allowance, uint64_t bytes,
                        const std::string& where) {
    if (bytes > allowance.bytes) {
        source.fail(where, "decompresses to " + std::to_string(bytes) +
                               " bytes, which would take the scene past the load budget of " +
                               std::to_string(allowance.max_bytes) + " bytes (" + allowance.budget_name +
                               " raises it); refused before decoding");
    }
    allowance.bytes -= bytes;
}

size_t extension_integer(const GltfSource& source, const tinygltf::Value& object, const char* key,
                         const std::string& where, std::optional<size_t> fallback) {
    if (!object.Has(key)) {
        if (fallback) return *fallback;
        source.fail(where, std::string("has no \"") + key + "\"");
    }
    const tinygltf::Value& value = object.Get(key);
    if (!value.IsInt() || value.GetNumberAsInt() < 0) {
        source.fail(where + "." + key, "expected an integer >= 0");
    }
    return static_cast<size_t>(value.GetNumberAsInt());
}

std::string extension_string(const GltfSource& source, const tinygltf::Value& object, const char* key,
                             const std::string& where, std::optional<std::string> fallback) {
    if (!object.Has(key)) {
        if (fallback) return *fallback;
        source.fail(where, std::string("has no \"") + key + "\"");
    }
    const tinygltf::Value& value = object.Get(key);
    if (!value.IsString()) source.fail(where + "." + key, "expected a string");
    return value.Get<std::string>();
}

void decode_compressed_geometry(tinygltf::Model& model, const std::string& origin, GltfDecodeAllowance& allowance) {
    const GltfSource source{model, origin};
    const uint64_t images = decoded_image_bytes(model);
    allowance.bytes = allowance.bytes > images ? allowance.bytes - images : 0;
    decode_meshopt_buffer_views(model, source, allowance);
    refuse_views_of_placeholders(model, source);
    decode_draco_primitives(model, source, allowance);
}

}  // namespace penumbra
