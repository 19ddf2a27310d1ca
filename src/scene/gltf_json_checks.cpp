// What tinygltf lets through silently: a property of the wrong JSON type is skipped as if
// absent (`"mesh": "zero"` drops the mesh) and a negative byteStride reads as 0 (packed).
// The properties whose value is an index, a count, a byte offset or a stride are checked
// here, on the JSON itself, before tinygltf reads it (glTF 2.0 schema, section 5).
#include <algorithm>
#include <iterator>
#include <nlohmann/json.hpp>

#include "penumbra/errors.hpp"
#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

using Json = nlohmann::json;

class JsonChecker {
public:
    explicit JsonChecker(const std::string& origin) : origin_(origin) {}

    [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
        throw InputError(origin_ + ": " + where + ": " + problem);
    }

    // An optional property that must be an integer >= minimum (glTF's glTFid and counts).
    void integer(const Json& object, const char* key, const std::string& where, int64_t minimum = 0) const {
        if (!object.is_object() || !object.contains(key)) return;
        const Json& value = object[key];
        if (!value.is_number_integer() || value.get<int64_t>() < minimum) {
            fail(where.empty() ? key : where + "." + key,
                 "expected an integer >= " + std::to_string(minimum) + ", got " + value.dump());
        }
    }

    // An optional array of indices.
    void index_array(const Json& object, const char* key, const std::string& where) const {
        if (!object.is_object() || !object.contains(key)) return;
        const Json& array = object[key];
        if (!array.is_array()) fail(where + "." + key, "expected an array of indices, got " + array.dump());
        for (size_t i = 0; i < array.size(); ++i) {
            if (!array[i].is_number_integer() || array[i].get<int64_t>() < 0) {
                fail(where + "." + key + "[" + std::to_string(i) + "]",
                     "expected an index (an integer >= 0), got " + array[i].dump());
            }
        }
    }

    // An optional string property; nullptr when absent.
    const std::string* string(const Json& object, const char* key, const std::string& where) const {
        if (!object.is_object() || !object.contains(key)) return nullptr;
        const Json& value = object[key];
        if (!value.is_string()) fail(where + "." + key, "expected a string, got " + value.dump());
        return value.get_ptr<const std::string*>();
    }

    // Calls check(element, "name[i]") for every element of the top-level array `name`.
    template <typename Check>
    void each(const Json& document, const char* name, Check&& check) const {
        if (!document.contains(name)) return;
        const Json& array = document[name];
        if (!array.is_array()) fail(name, "expected an array, got " + std::string(array.type_name()));
        for (size_t i = 0; i < array.size(); ++i) check(array[i], std::string(name) + "[" + std::to_string(i) + "]");
    }

private:
    const std::string& origin_;
};

void check_byte_stride(const JsonChecker& checker, const Json& view, const std::string& where) {
    checker.integer(view, "byteStride", where, 4);
    if (view.is_object() && view.contains("byteStride")) {
        const int64_t stride = view["byteStride"].get<int64_t>();
        if (stride > 252 || stride % 4 != 0) {
            checker.fail(where + ".byteStride",
                         "expected a multiple of 4 from 4 to 252, got " + std::to_string(stride));
        }
    }
}

void check_primitives(const JsonChecker& checker, const Json& mesh, const std::string& where) {
    if (!mesh.is_object() || !mesh.contains("primitives")) return;
    const Json& primitives = mesh["primitives"];
    if (!primitives.is_array()) checker.fail(where + ".primitives", "expected an array");
    for (size_t p = 0; p < primitives.size(); ++p) {
        const std::string at = where + ".primitives[" + std::to_string(p) + "]";
        for (const char* key : {"indices", "material", "mode"}) checker.integer(primitives[p], key, at);
        if (primitives[p].is_object() && primitives[p].contains("attributes")) {
            for (const auto& [name, accessor] : primitives[p]["attributes"].items()) {
                if (!accessor.is_number_integer() || accessor.get<int64_t>() < 0) {
                    checker.fail(at + ".attributes." + name, "expected an accessor index, got " + accessor.dump());
                }
            }
        }
    }
}

// Extensions a file may require without changing what casts a shadow or where (they shade
// surfaces, or Penumbra reads them): anything else in extensionsRequired is refused by
// name, rather than failing later on what tinygltf cannot read (a Draco mesh's accessors
// have no bufferView) or casting the wrong shadow.
bool honoured_when_required(const std::string& extension) {
    static const char* const kHonoured[] = {"KHR_mesh_quantization",
                                            "KHR_lights_punctual",
                                            "KHR_materials_unlit",
                                            "KHR_materials_emissive_strength",
                                            "KHR_materials_clearcoat",
                                            "KHR_materials_sheen",
                                            "KHR_materials_specular",
                                            "KHR_materials_ior",
                                            "KHR_materials_iridescence",
                                            "KHR_materials_variants",
                                            "KHR_materials_volume",
                                            "KHR_texture_transform",
                                            "KHR_materials_pbrSpecularGlossiness"};
    return std::find(std::begin(kHonoured), std::end(kHonoured), extension) != std::end(kHonoured);
}

std::string extension_feature(const std::string& extension) {
    if (extension == "KHR_draco_mesh_compression") return " (Draco-compressed meshes)";
    if (extension == "EXT_meshopt_compression") return " (meshoptimizer-compressed buffers)";
    if (extension == "KHR_texture_basisu" || extension == "EXT_texture_webp") return " (an image format)";
    return "";
}

void check_required_extensions(const JsonChecker& checker, const Json& document) {
    if (!document.contains("extensionsRequired")) return;
    const Json& required = document["extensionsRequired"];
    if (!required.is_array()) checker.fail("extensionsRequired", "expected an array of extension names");
    for (size_t i = 0; i < required.size(); ++i) {
        if (!required[i].is_string()) {
            checker.fail("extensionsRequired[" + std::to_string(i) + "]", "expected an extension name");
        }
        const std::string& name = required[i].get_ref<const std::string&>();
        if (!honoured_when_required(name)) {
            checker.fail("extensionsRequired",
                         "the file requires " + name + extension_feature(name) + ", which Penumbra does not support");
        }
    }
}

}  // namespace

void check_gltf_json(std::string_view json, const std::string& origin, const std::filesystem::path& folder) {
    const Json document = Json::parse(json.begin(), json.end(), nullptr, false);
    if (document.is_discarded() || !document.is_object()) return;  // tinygltf reports the syntax error
    const JsonChecker checker(origin);
    check_required_extensions(checker, document);
    checker.integer(document, "scene", "");
    checker.each(document, "scenes",
                 [&](const Json& scene, const std::string& where) { checker.index_array(scene, "nodes", where); });
    checker.each(document, "nodes", [&](const Json& node, const std::string& where) {
        for (const char* key : {"mesh", "camera", "skin"}) checker.integer(node, key, where);
        checker.index_array(node, "children", where);
    });
    checker.each(document, "meshes",
                 [&](const Json& mesh, const std::string& where) { check_primitives(checker, mesh, where); });
    checker.each(document, "accessors", [&](const Json& accessor, const std::string& where) {
        for (const char* key : {"bufferView", "byteOffset", "componentType"}) checker.integer(accessor, key, where);
        checker.integer(accessor, "count", where, 1);
        if (accessor.is_object() && accessor.contains("sparse")) {
            const Json& sparse = accessor["sparse"];
            checker.integer(sparse, "count", where + ".sparse", 1);
            for (const char* part : {"indices", "values"}) {
                if (!sparse.is_object() || !sparse.contains(part)) continue;
                for (const char* key : {"bufferView", "byteOffset", "componentType"}) {
                    checker.integer(sparse[part], key, where + ".sparse." + part);
                }
            }
        }
    });
    checker.each(document, "bufferViews", [&](const Json& view, const std::string& where) {
        for (const char* key : {"buffer", "byteOffset"}) checker.integer(view, key, where);
        checker.integer(view, "byteLength", where, 1);
        check_byte_stride(checker, view, where);
    });
    checker.each(document, "textures", [&](const Json& texture, const std::string& where) {
        for (const char* key : {"source", "sampler"}) checker.integer(texture, key, where);
    });
    checker.each(document, "images", [&](const Json& image, const std::string& where) {
        checker.integer(image, "bufferView", where);
        if (const std::string* uri = checker.string(image, "uri", where))
            check_gltf_uri({*uri, where + ".uri", folder, {}}, origin);
    });
    checker.each(document, "buffers", [&](const Json& buffer, const std::string& where) {
        checker.integer(buffer, "byteLength", where, 1);
        const std::string* uri = checker.string(buffer, "uri", where);
        if (uri && buffer.contains("byteLength")) {
            check_gltf_uri({*uri, where + ".uri", folder, buffer["byteLength"].get<uint64_t>()}, origin);
        }
    });
}

}  // namespace penumbra
