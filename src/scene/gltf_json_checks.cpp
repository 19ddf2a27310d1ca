// What tinygltf lets through silently: a property of the wrong JSON type is skipped as if
// absent (`"mesh": "zero"` drops the mesh), a negative byteStride reads as 0 (packed), and
// an integer beyond a C int wraps (a mesh index of 2^32 names mesh 0, a material of 2^31 is
// "none"). The properties whose value is an index, a count, a byte offset or a stride are
// checked here, on the JSON itself, before tinygltf reads it (glTF 2.0 schema, section 5):
// every index must name an element of the array it indexes.
#include <algorithm>
#include <cstdint>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>

#include "penumbra/errors.hpp"
#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

using Json = nlohmann::json;

// The largest integer tinygltf stores without wrapping (it reads glTF's integers into int).
constexpr int64_t kLargestCInt = std::numeric_limits<int32_t>::max();

// The elements an index may name: "mesh 3 does not exist (the file has 2 meshes)".
struct IndexTarget {
    const char* kind;
    const char* plural;
    size_t count = 0;
};

// The elements of the document's top-level array `name` (none when it is absent).
IndexTarget elements_of(const Json& document, const char* name, const char* kind, const char* plural) {
    const auto found = document.find(name);
    const size_t count = (found != document.end() && found->is_array()) ? found->size() : 0;
    return {kind, plural, count};
}

std::string joined(const std::string& where, const char* key) { return where.empty() ? key : where + "." + key; }

class JsonChecker {
public:
    explicit JsonChecker(const std::string& origin) : origin_(origin) {}

    [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
        throw InputError(origin_ + ": " + where + ": " + problem);
    }

    // An optional property that must be an integer >= minimum (counts, offsets) and, where
    // tinygltf holds it in an int (modes, component types), <= maximum.
    void integer(const Json& object, const char* key, const std::string& where, int64_t minimum = 0,
                 int64_t maximum = std::numeric_limits<int64_t>::max()) const {
        if (!object.is_object() || !object.contains(key)) return;
        const Json& value = object[key];
        if (!value.is_number_integer() || value.get<int64_t>() < minimum ||
            (value.is_number_unsigned() && value.get<uint64_t>() > static_cast<uint64_t>(maximum)) ||
            value.get<int64_t>() > maximum) {
            const std::string range = maximum == std::numeric_limits<int64_t>::max()
                                          ? ">= " + std::to_string(minimum)
                                          : "from " + std::to_string(minimum) + " to " + std::to_string(maximum);
            fail(joined(where, key), "expected an integer " + range + ", got " + value.dump());
        }
    }

    // An optional glTFid: an integer naming one of `target`'s elements.
    void index(const Json& object, const char* key, const std::string& where, const IndexTarget& target) const {
        if (!object.is_object() || !object.contains(key)) return;
        index_value(object[key], joined(where, key), target);
    }

    // An optional array of glTFids, each naming one of `target`'s elements.
    void index_array(const Json& object, const char* key, const std::string& where, const IndexTarget& target) const {
        if (!object.is_object() || !object.contains(key)) return;
        const Json& array = object[key];
        if (!array.is_array()) fail(where + "." + key, "expected an array of indices, got " + array.dump());
        for (size_t i = 0; i < array.size(); ++i) {
            index_value(array[i], where + "." + key + "[" + std::to_string(i) + "]", target);
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
    void index_value(const Json& value, const std::string& where, const IndexTarget& target) const {
        // Unsigned first: 2^64 - 1 read as int64_t would look negative.
        if (value.is_number_unsigned() && value.get<uint64_t>() >= target.count) {
            fail(where, std::string(target.kind) + " " + value.dump() + " does not exist (the file has " +
                            std::to_string(target.count) + " " + target.plural + ")");
        }
        if (!value.is_number_integer() || value.get<int64_t>() < 0) {
            fail(where, "expected an index (an integer >= 0), got " + value.dump());
        }
        if (static_cast<uint64_t>(value.get<int64_t>()) >= target.count) {
            fail(where, std::string(target.kind) + " " + value.dump() + " does not exist (the file has " +
                            std::to_string(target.count) + " " + target.plural + ")");
        }
    }

    const std::string& origin_;
};

// Every array an index may name, counted once.
struct DocumentTargets {
    explicit DocumentTargets(const Json& document)
        : scenes(elements_of(document, "scenes", "scene", "scenes")),
          nodes(elements_of(document, "nodes", "node", "nodes")),
          meshes(elements_of(document, "meshes", "mesh", "meshes")),
          cameras(elements_of(document, "cameras", "camera", "cameras")),
          skins(elements_of(document, "skins", "skin", "skins")),
          accessors(elements_of(document, "accessors", "accessor", "accessors")),
          materials(elements_of(document, "materials", "material", "materials")),
          buffer_views(elements_of(document, "bufferViews", "bufferView", "buffer views")),
          buffers(elements_of(document, "buffers", "buffer", "buffers")),
          textures(elements_of(document, "textures", "texture", "textures")),
          images(elements_of(document, "images", "image", "images")),
          samplers(elements_of(document, "samplers", "sampler", "samplers")),
          lights{"light", "lights", punctual_light_count(document)} {}

    static size_t punctual_light_count(const Json& document) {
        const Json* level = &document;
        for (const char* key : {"extensions", "KHR_lights_punctual", "lights"}) {
            if (!level->is_object() || !level->contains(key)) return 0;
            level = &(*level)[key];
        }
        return level->is_array() ? level->size() : 0;
    }

    IndexTarget scenes, nodes, meshes, cameras, skins, accessors, materials, buffer_views, buffers, textures, images,
        samplers, lights;
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

// The extension object `name` of `owner`, or nullptr.
const Json* extension_object(const Json& owner, const char* name) {
    if (!owner.is_object() || !owner.contains("extensions") || !owner["extensions"].is_object()) return nullptr;
    const auto found = owner["extensions"].find(name);
    return found == owner["extensions"].end() ? nullptr : &*found;
}

// KHR_draco_mesh_compression: its bufferView names a view; its attributes' values are
// Draco's unique ids, held in an int by tinygltf.
void check_draco_extension(const JsonChecker& checker, const DocumentTargets& targets, const Json& primitive,
                           const std::string& where) {
    const Json* draco = extension_object(primitive, "KHR_draco_mesh_compression");
    if (draco == nullptr) return;
    const std::string at = where + ".extensions.KHR_draco_mesh_compression";
    checker.index(*draco, "bufferView", at, targets.buffer_views);
    if (!draco->is_object() || !draco->contains("attributes") || !(*draco)["attributes"].is_object()) return;
    for (const auto& [name, id] : (*draco)["attributes"].items()) {
        checker.integer((*draco)["attributes"], name.c_str(), at + ".attributes", 0, kLargestCInt);
    }
}

// EXT_meshopt_compression on a buffer view: its buffer, offsets, lengths and counts, which
// tinygltf holds in an int.
void check_meshopt_extension(const JsonChecker& checker, const DocumentTargets& targets, const Json& view,
                             const std::string& where) {
    const Json* meshopt = extension_object(view, "EXT_meshopt_compression");
    if (meshopt == nullptr) return;
    const std::string at = where + ".extensions.EXT_meshopt_compression";
    checker.index(*meshopt, "buffer", at, targets.buffers);
    checker.integer(*meshopt, "byteOffset", at, 0, kLargestCInt);
    checker.integer(*meshopt, "byteLength", at, 1, kLargestCInt);
    checker.integer(*meshopt, "byteStride", at, 1, kLargestCInt);
    checker.integer(*meshopt, "count", at, 1, kLargestCInt);
}

void check_primitives(const JsonChecker& checker, const DocumentTargets& targets, const Json& mesh,
                      const std::string& where) {
    if (!mesh.is_object() || !mesh.contains("primitives")) return;
    const Json& primitives = mesh["primitives"];
    if (!primitives.is_array()) checker.fail(where + ".primitives", "expected an array");
    for (size_t p = 0; p < primitives.size(); ++p) {
        const std::string at = where + ".primitives[" + std::to_string(p) + "]";
        const Json& primitive = primitives[p];
        checker.index(primitive, "indices", at, targets.accessors);
        checker.index(primitive, "material", at, targets.materials);
        checker.integer(primitive, "mode", at, 0, kLargestCInt);
        if (!primitive.is_object()) continue;
        if (primitive.contains("attributes") && primitive["attributes"].is_object()) {
            for (const auto& [name, accessor] : primitive["attributes"].items()) {
                checker.index(primitive["attributes"], name.c_str(), at + ".attributes", targets.accessors);
            }
        }
        check_draco_extension(checker, targets, primitive, at);
        if (!primitive.contains("targets") || !primitive["targets"].is_array()) continue;
        for (size_t t = 0; t < primitive["targets"].size(); ++t) {
            const Json& target = primitive["targets"][t];
            if (!target.is_object()) continue;
            for (const auto& [name, accessor] : target.items()) {
                checker.index(target, name.c_str(), at + ".targets[" + std::to_string(t) + "]", targets.accessors);
            }
        }
    }
}

// A material's textureInfo objects (the core ones, and the specular-glossiness diffuse
// texture Penumbra reads): their index names a texture, their texCoord a TEXCOORD_n.
void check_material(const JsonChecker& checker, const DocumentTargets& targets, const Json& material,
                    const std::string& where) {
    const auto texture_info = [&](const Json& owner, const char* key, const std::string& owner_where) {
        if (!owner.is_object() || !owner.contains(key)) return;
        const std::string at = owner_where + "." + key;
        checker.index(owner[key], "index", at, targets.textures);
        checker.integer(owner[key], "texCoord", at, 0, kLargestCInt);
    };
    for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"}) texture_info(material, key, where);
    if (!material.is_object()) return;
    if (material.contains("pbrMetallicRoughness")) {
        for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"}) {
            texture_info(material["pbrMetallicRoughness"], key, where + ".pbrMetallicRoughness");
        }
    }
    if (material.contains("extensions") && material["extensions"].is_object() &&
        material["extensions"].contains("KHR_materials_pbrSpecularGlossiness")) {
        texture_info(material["extensions"]["KHR_materials_pbrSpecularGlossiness"], "diffuseTexture",
                     where + ".extensions.KHR_materials_pbrSpecularGlossiness");
    }
}

// A node's KHR_lights_punctual.light names one of the document's punctual lights.
void check_node(const JsonChecker& checker, const DocumentTargets& targets, const Json& node,
                const std::string& where) {
    checker.index(node, "mesh", where, targets.meshes);
    checker.index(node, "camera", where, targets.cameras);
    checker.index(node, "skin", where, targets.skins);
    checker.index_array(node, "children", where, targets.nodes);
    if (node.is_object() && node.contains("extensions") && node["extensions"].is_object() &&
        node["extensions"].contains("KHR_lights_punctual")) {
        checker.index(node["extensions"]["KHR_lights_punctual"], "light", where + ".extensions.KHR_lights_punctual",
                      targets.lights);
    }
}

void check_accessor(const JsonChecker& checker, const DocumentTargets& targets, const Json& accessor,
                    const std::string& where) {
    checker.index(accessor, "bufferView", where, targets.buffer_views);
    checker.integer(accessor, "byteOffset", where);
    checker.integer(accessor, "componentType", where, 0, kLargestCInt);
    checker.integer(accessor, "count", where, 1);
    if (!accessor.is_object() || !accessor.contains("sparse")) return;
    const Json& sparse = accessor["sparse"];
    checker.integer(sparse, "count", where + ".sparse", 1);
    for (const char* part : {"indices", "values"}) {
        if (!sparse.is_object() || !sparse.contains(part)) continue;
        const std::string at = where + ".sparse." + part;
        checker.index(sparse[part], "bufferView", at, targets.buffer_views);
        checker.integer(sparse[part], "byteOffset", at);
        checker.integer(sparse[part], "componentType", at, 0, kLargestCInt);
    }
}

// Extensions a file may require without changing what casts a shadow or where (they shade
// surfaces, or Penumbra reads them; the two compression extensions are decoded, see
// gltf_compression.cpp): anything else in extensionsRequired is refused by
// name, rather than failing later on what tinygltf cannot read (a Draco mesh's accessors
// have no bufferView) or casting the wrong shadow.
bool honoured_when_required(const std::string& extension) {
    static const char* const kHonoured[] = {
        "KHR_mesh_quantization",   "KHR_draco_mesh_compression", "EXT_meshopt_compression",
        "KHR_lights_punctual",     "KHR_materials_unlit",        "KHR_materials_emissive_strength",
        "KHR_materials_clearcoat", "KHR_materials_sheen",        "KHR_materials_specular",
        "KHR_materials_ior",       "KHR_materials_iridescence",  "KHR_materials_variants",
        "KHR_materials_volume",    "KHR_texture_transform",      "KHR_materials_pbrSpecularGlossiness"};
    return std::find(std::begin(kHonoured), std::end(kHonoured), extension) != std::end(kHonoured);
}

std::string extension_feature(const std::string& extension) {
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
    const DocumentTargets targets(document);
    checker.index(document, "scene", "", targets.scenes);
    checker.each(document, "scenes", [&](const Json& scene, const std::string& where) {
        checker.index_array(scene, "nodes", where, targets.nodes);
    });
    checker.each(document, "nodes",
                 [&](const Json& node, const std::string& where) { check_node(checker, targets, node, where); });
    checker.each(document, "meshes",
                 [&](const Json& mesh, const std::string& where) { check_primitives(checker, targets, mesh, where); });
    checker.each(document, "materials", [&](const Json& material, const std::string& where) {
        check_material(checker, targets, material, where);
    });
    checker.each(document, "accessors", [&](const Json& accessor, const std::string& where) {
        check_accessor(checker, targets, accessor, where);
    });
    checker.each(document, "bufferViews", [&](const Json& view, const std::string& where) {
        checker.index(view, "buffer", where, targets.buffers);
        checker.integer(view, "byteOffset", where);
        checker.integer(view, "byteLength", where, 1);
        check_byte_stride(checker, view, where);
        check_meshopt_extension(checker, targets, view, where);
    });
    checker.each(document, "textures", [&](const Json& texture, const std::string& where) {
        checker.index(texture, "source", where, targets.images);
        checker.index(texture, "sampler", where, targets.samplers);
    });
    checker.each(document, "images", [&](const Json& image, const std::string& where) {
        checker.index(image, "bufferView", where, targets.buffer_views);
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
    check_gltf_json_values(document, origin);
}

}  // namespace penumbra
