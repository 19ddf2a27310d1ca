#include "scene/scene_objects.hpp"

#include <algorithm>
#include <map>
#include <optional>

#include "penumbra/errors.hpp"
#include "penumbra/scene/loader.hpp"
#include "penumbra/scene/primitives.hpp"
#include "scene/procedural_textures.hpp"

namespace penumbra {
namespace {

const Material kDefaultPrimitiveMaterial{glm::vec4{0.8f, 0.8f, 0.8f, 1.0f}};

std::string format_vector(const float* values, int count) {
    std::string text = "[";
    for (int i = 0; i < count; ++i) text += (i == 0 ? "" : ", ") + format_number(values[i]);
    return text + "]";
}

float positive_number(TomlTableReader& reader, std::string_view key, float fallback) {
    const float value = reader.number_or(key, fallback);
    if (value <= 0.0f) reader.fail(key, "must be > 0, got " + format_number(value));
    return value;
}

float unit_interval_number(TomlTableReader& reader, std::string_view key, float fallback) {
    const float value = reader.number_or(key, fallback);
    if (value < 0.0f || value > 1.0f) reader.fail(key, "must be between 0 and 1, got " + format_number(value));
    return value;
}

template <int N>
glm::vec<N, float> positive_components(TomlTableReader& reader, std::string_view key, const glm::vec<N, float>& value) {
    for (int i = 0; i < N; ++i) {
        if (value[i] <= 0.0f) {
            reader.fail(key, "every component must be > 0, got " + format_vector(&value[0], N));
        }
    }
    return value;
}

// translation, rotation (Euler degrees, X then Y then Z) and scale of an object or instance.
glm::mat4 read_transform(TomlTableReader& reader) {
    const glm::vec3 translation = reader.vec3_or("translation", glm::vec3{0.0f});
    const glm::vec3 rotation = reader.vec3_or("rotation", glm::vec3{0.0f});
    const glm::vec3 scale =
        positive_components(reader, "scale", reader.optional_vec3_or_scalar("scale").value_or(glm::vec3{1.0f}));
    return compose_transform(translation, rotation, scale);
}

AlphaMode read_alpha_mode(TomlTableReader& reader, AlphaMode fallback) {
    const std::optional<std::string> name = reader.optional_string("alpha_mode");
    if (!name) return fallback;
    if (*name == "opaque") return AlphaMode::Opaque;
    if (*name == "mask") return AlphaMode::Mask;
    if (*name == "blend") return AlphaMode::Blend;
    reader.fail("alpha_mode", "unknown alpha mode \"" + *name + "\" (expected opaque, mask or blend)");
}

std::optional<ProceduralPattern> read_texture_pattern(TomlTableReader& reader) {
    const std::optional<std::string> name = reader.optional_string("texture");
    if (!name) return std::nullopt;
    const std::optional<ProceduralPattern> pattern = procedural_pattern_from_name(*name);
    if (!pattern) {
        reader.fail("texture",
                    "unknown procedural texture \"" + *name + "\" (expected " + procedural_pattern_names() + ")");
    }
    return pattern;
}

Mesh read_primitive_shape(TomlTableReader& reader, const std::string& type) {
    if (type == "plane") {
        const std::optional<glm::vec2> size = reader.optional_vec2("size");
        const glm::vec2 extent = positive_components(reader, "size", size.value_or(glm::vec2{10.0f}));
        return make_plane(extent.x, extent.y);
    }
    if (type == "box") {
        return make_box(
            positive_components(reader, "size", reader.optional_vec3_or_scalar("size").value_or(glm::vec3{1.0f})));
    }
    if (type == "sphere") return make_sphere(positive_number(reader, "radius", 0.5f));
    const float radius = positive_number(reader, "radius", 0.5f);
    return make_cylinder(radius, positive_number(reader, "height", 1.0f));
}

class ObjectBuilder {
public:
    ObjectBuilder(Scene& scene, const std::filesystem::path& base_directory, const LoadBudget& budget)
        : scene_(scene), base_directory_(base_directory), budget_(budget) {}

    void add_object(TomlTableReader& reader) {
        const std::string type = reader.required_string("type");
        if (type == "plane" || type == "box" || type == "sphere" || type == "cylinder") {
            add_primitive(reader, type);
        } else if (type == "gltf") {
            add_gltf(reader);
        } else {
            reader.fail("type", "unknown object type \"" + type + "\" (expected plane, box, sphere, cylinder or gltf)");
        }
    }

private:
    void add_primitive(TomlTableReader& reader, const std::string& type) {
        Mesh mesh = read_primitive_shape(reader, type);
        const glm::mat4 world = read_transform(reader);
        const Material material = read_primitive_material(reader);
        const glm::vec2 uv_scale =
            positive_components(reader, "uv_scale", reader.optional_vec2("uv_scale").value_or(glm::vec2{1.0f}));
        Instance instance{static_cast<uint32_t>(scene_.meshes.size()), world};
        instance.cast_shadows = reader.boolean_or("cast_shadows", true);
        instance.receive_shadows = reader.boolean_or("receive_shadows", true);
        instance.dynamic = reader.boolean_or("dynamic", false);
        const std::string path = reader.key_path("type");  // "objects[2].type"
        instance.name = path.substr(0, path.rfind('.')) + " (" + type + ")";
        instance.origin.type = type;
        reader.reject_unknown_keys();
        for (Vertex& vertex : mesh.vertices) vertex.uv *= uv_scale;
        mesh.material = static_cast<uint32_t>(scene_.materials.size());
        scene_.materials.push_back(material);
        scene_.instances.push_back(instance);
        scene_.meshes.push_back(std::move(mesh));
    }

    Material read_primitive_material(TomlTableReader& reader) {
        Material material = kDefaultPrimitiveMaterial;
        material.base_color = reader.color_or("color", material.base_color);
        for (int i = 0; i < 4; ++i) {
            if (material.base_color[i] < 0.0f || (i == 3 && material.base_color[i] > 1.0f)) {
                reader.fail("color", "components must be >= 0 and alpha at most 1, got " +
                                         format_vector(&material.base_color[0], 4));
            }
        }
        const std::optional<ProceduralPattern> pattern = read_texture_pattern(reader);
        if (pattern) material.base_color_texture = procedural_texture(*pattern);
        // A cutoff or a texture with holes implies alpha masking unless alpha_mode says otherwise.
        const bool wants_mask = reader.contains("alpha_cutoff") || (pattern && pattern_has_holes(*pattern));
        material.alpha_mode = read_alpha_mode(reader, wants_mask ? AlphaMode::Mask : AlphaMode::Opaque);
        material.alpha_cutoff = unit_interval_number(reader, "alpha_cutoff", material.alpha_cutoff);
        material.double_sided = reader.boolean_or("double_sided", material.double_sided);
        material.roughness = unit_interval_number(reader, "roughness", material.roughness);
        material.metallic = unit_interval_number(reader, "metallic", material.metallic);
        material.emissive = reader.vec3_or("emissive", material.emissive);
        if (material.emissive.x < 0.0f || material.emissive.y < 0.0f || material.emissive.z < 0.0f) {
            reader.fail("emissive", "components must be >= 0, got " + format_vector(&material.emissive[0], 3));
        }
        return material;
    }

    int32_t procedural_texture(ProceduralPattern pattern) {
        if (const auto found = procedural_textures_.find(pattern); found != procedural_textures_.end()) {
            return found->second;
        }
        const auto index = static_cast<int32_t>(scene_.textures.size());
        scene_.textures.push_back(make_procedural_texture(pattern));
        procedural_textures_.emplace(pattern, index);
        return index;
    }

    void add_gltf(TomlTableReader& reader) {
        const std::string written_file = reader.required_string("file");
        const std::filesystem::path file = base_directory_ / written_file;
        const glm::mat4 object_transform = read_transform(reader);
        GltfImportOptions options;
        const bool casts = reader.boolean_or("cast_shadows", true);
        const bool receives = reader.boolean_or("receive_shadows", true);
        const bool dynamic = reader.boolean_or("dynamic", false);
        options.exclude_casters = reader.optional_string_list("exclude_casters").value_or(std::vector<std::string>{});
        std::vector<glm::mat4> placements;
        const bool has_instances = reader.contains("instances");
        for (const toml::table* instance : reader.table_array("instances")) {
            TomlTableReader instance_reader(
                *instance, reader.origin(),
                reader.key_path("instances") + "[" + std::to_string(placements.size()) + "]");
            // The object's own transform acts as the parent of every instance.
            placements.push_back(object_transform * read_transform(instance_reader));
            options.placement_casts.push_back(instance_reader.boolean_or("cast_shadows", casts));
            options.placement_receives.push_back(instance_reader.boolean_or("receive_shadows", receives));
            options.placement_dynamic.push_back(instance_reader.boolean_or("dynamic", dynamic));
            instance_reader.reject_unknown_keys();
        }
        if (has_instances && placements.empty()) {
            reader.fail("instances", "empty array (leave the key out for one instance at the object's transform)");
        }
        if (!has_instances) {
            placements.push_back(object_transform);
            options.placement_casts.push_back(casts);
            options.placement_receives.push_back(receives);
            options.placement_dynamic.push_back(dynamic);
        }
        options.import_lights = reader.boolean_or("import_lights", false);
        options.budget = budget_;
        reader.reject_unknown_keys();
        const size_t first = scene_.instances.size();
        try {
            append_gltf(scene_, file, placements, options);
        } catch (const InputError& error) {
            reader.fail("file", error.what());
        }
        for (size_t i = first; i < scene_.instances.size(); ++i) {
            scene_.instances[i].origin.file = written_file;
        }
    }

    Scene& scene_;
    std::filesystem::path base_directory_;
    const LoadBudget& budget_;
    std::map<ProceduralPattern, int32_t> procedural_textures_;
};

}  // namespace

void append_scene_objects(TomlTableReader& root, Scene& scene, const std::filesystem::path& base_directory,
                          const LoadBudget& budget) {
    ObjectBuilder builder(scene, base_directory, budget);
    const std::vector<const toml::table*> objects = root.table_array("objects");
    for (size_t i = 0; i < objects.size(); ++i) {
        TomlTableReader reader(*objects[i], root.origin(), root.key_path("objects") + "[" + std::to_string(i) + "]");
        const size_t first = scene.instances.size();
        builder.add_object(reader);
        for (size_t j = first; j < scene.instances.size(); ++j)
            scene.instances[j].origin.object = static_cast<int32_t>(i);
    }
}

}  // namespace penumbra
