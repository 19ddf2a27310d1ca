#include <fstream>
#include <sstream>

#include "penumbra/errors.hpp"
#include "penumbra/scene/loader.hpp"
#include "penumbra/settings.hpp"
#include "scene/scene_objects.hpp"
#include "scene/toml_fields.hpp"

namespace penumbra {
namespace {

std::string format_vec3(const glm::vec3& value) {
    return "[" + format_number(value.x) + ", " + format_number(value.y) + ", " + format_number(value.z) + "]";
}

void require_non_negative(TomlTableReader& reader, std::string_view key, const glm::vec3& color) {
    if (color.r < 0.0f || color.g < 0.0f || color.b < 0.0f) {
        reader.fail(key, "components must be >= 0, got " + format_vec3(color));
    }
}

Camera read_camera(TomlTableReader reader) {
    Camera camera;
    camera.eye = reader.vec3_or("eye", camera.eye);
    camera.target = reader.vec3_or("target", camera.target);
    camera.up = reader.vec3_or("up", camera.up);
    camera.fov_y_degrees = reader.number_or("fov", camera.fov_y_degrees);
    camera.near_plane = reader.number_or("near", camera.near_plane);
    camera.far_plane = reader.number_or("far", camera.far_plane);
    reader.reject_unknown_keys();

    if (camera.eye == camera.target) {
        reader.fail("target", "equals eye " + format_vec3(camera.eye) + ", so the camera has no view direction");
    }
    if (glm::length(camera.up) == 0.0f) reader.fail("up", "zero-length vector " + format_vec3(camera.up));
    // An up parallel to the view direction is legal here: make_camera_view() picks another.
    camera.up = glm::normalize(camera.up);
    if (camera.fov_y_degrees <= 0.0f || camera.fov_y_degrees >= 180.0f) {
        reader.fail("fov", "must be between 0 and 180 degrees (exclusive), got " + format_number(camera.fov_y_degrees));
    }
    if (camera.near_plane <= 0.0f) reader.fail("near", "must be > 0, got " + format_number(camera.near_plane));
    if (camera.far_plane <= camera.near_plane) {
        reader.fail("far", "must be greater than near (" + format_number(camera.near_plane) + "), got " +
                               format_number(camera.far_plane));
    }
    return camera;
}

LightType read_light_type(TomlTableReader& reader) {
    const std::string type = reader.optional_string("type").value_or("directional");
    if (type == "directional") return LightType::Directional;
    if (type == "spot") return LightType::Spot;
    if (type == "point") return LightType::Point;
    reader.fail("type", "unknown light type \"" + type + "\" (expected directional, spot or point)");
}

// Keys of spot and point lights, validated: 0 <= inner <= outer < 180 degrees (half-angles
// from the axis; a spot wider than 60 degrees is shadowed by a cube, docs/local-lights.md),
// range > 0, radius >= 0, shadow_resolution 16..8192.
void read_local_light_keys(TomlTableReader& reader, Light& light) {
    light.position = reader.vec3_or("position", light.position);
    light.range = reader.number_or("range", light.range);
    light.radius = reader.number_or("radius", light.radius);
    if (const std::optional<double> resolution = reader.optional_number("shadow_resolution")) {
        if (*resolution < 16.0 || *resolution > 8192.0 ||
            *resolution != static_cast<double>(static_cast<int>(*resolution))) {
            reader.fail("shadow_resolution",
                        "must be an integer between 16 and 8192, got " + format_number(*resolution));
        }
        light.shadow_resolution = static_cast<uint32_t>(*resolution);
    }
    if (light.type == LightType::Spot) {
        light.inner_angle_degrees = reader.number_or("inner_angle", light.inner_angle_degrees);
        light.outer_angle_degrees = reader.number_or("outer_angle", light.outer_angle_degrees);
        if (light.outer_angle_degrees <= 0.0f || light.outer_angle_degrees >= 180.0f) {
            reader.fail("outer_angle",
                        "must be between 0 and 180 degrees (exclusive; a half-angle from the axis), got " +
                            format_number(light.outer_angle_degrees));
        }
        if (light.inner_angle_degrees < 0.0f || light.inner_angle_degrees > light.outer_angle_degrees) {
            reader.fail("inner_angle", "must be between 0 and outer_angle (" +
                                           format_number(light.outer_angle_degrees) + ") degrees, got " +
                                           format_number(light.inner_angle_degrees));
        }
    }
    if (light.range <= 0.0f) reader.fail("range", "must be > 0, got " + format_number(light.range));
    if (light.radius < 0.0f) reader.fail("radius", "must be >= 0, got " + format_number(light.radius));
}

Light read_light(TomlTableReader reader) {
    Light light;
    light.type = read_light_type(reader);
    if (light.type != LightType::Point) light.direction = reader.vec3_or("direction", light.direction);
    light.color = reader.vec3_or("color", light.color);
    light.intensity = reader.number_or("intensity", light.intensity);
    if (light.type == LightType::Directional) {
        light.angular_diameter_degrees = reader.number_or("angular_diameter", light.angular_diameter_degrees);
    }
    light.cast_shadows = reader.boolean_or("cast_shadows", light.cast_shadows);
    if (light.type != LightType::Directional) read_local_light_keys(reader, light);
    reader.reject_unknown_keys();

    if (glm::length(light.direction) == 0.0f) {
        reader.fail("direction", "zero-length vector " + format_vec3(light.direction));
    }
    light.direction = glm::normalize(light.direction);
    require_non_negative(reader, "color", light.color);
    if (light.intensity < 0.0f) reader.fail("intensity", "must be >= 0, got " + format_number(light.intensity));
    if (light.angular_diameter_degrees < 0.0f || light.angular_diameter_degrees > 45.0f) {
        reader.fail("angular_diameter",
                    "must be between 0 and 45 degrees, got " + format_number(light.angular_diameter_degrees));
    }
    return light;
}

glm::vec3 read_ambient(TomlTableReader reader, const glm::vec3& fallback) {
    const glm::vec3 color = reader.vec3_or("color", fallback);
    reader.reject_unknown_keys();
    require_non_negative(reader, "color", color);
    return color;
}

// A ShadowSystem takes at most kMaxLights lights: a scene with more is this file's error,
// named here, not the library's later ("ShadowSystem::set_lights: 301 lights").
void check_light_count(const std::string& origin, const Scene& scene, size_t from_lights_table) {
    if (scene.lights.size() <= kMaxLights) return;
    const std::string most = ", at most " + std::to_string(kMaxLights) + " (the lights one ShadowSystem takes)";
    if (scene.lights.size() == from_lights_table) {
        throw_scene_error(origin, "lights", std::to_string(from_lights_table) + " lights" + most);
    }
    throw_scene_error(origin, "objects",
                      "the glTF models' lights bring the scene to " + std::to_string(scene.lights.size()) +
                          " lights (" + std::to_string(from_lights_table) + " from [[lights]])" + most);
}

}  // namespace

Scene parse_scene_toml(std::string_view text, const std::string& origin, const std::filesystem::path& base_directory,
                       const LoadBudget& budget) {
    const toml::table root = parse_toml_text(text, origin);
    TomlTableReader reader(root, origin, "");
    // [shadow] and [output] are render settings, parsed by the layer that owns them.
    reader.accept("shadow");
    reader.accept("output");
    Scene scene;
    if (const toml::table* camera = reader.optional_table("camera")) {
        scene.camera = read_camera(TomlTableReader(*camera, origin, "camera"));
    }
    const std::vector<const toml::table*> lights = reader.table_array("lights");
    for (size_t i = 0; i < lights.size(); ++i) {
        scene.lights.push_back(read_light(TomlTableReader(*lights[i], origin, "lights[" + std::to_string(i) + "]")));
    }
    check_light_count(origin, scene, lights.size());
    if (const toml::table* ambient = reader.optional_table("ambient")) {
        scene.ambient = read_ambient(TomlTableReader(*ambient, origin, "ambient"), scene.ambient);
    }
    reader.accept("objects");  // read last, by append_scene_objects()
    // Unknown top-level tables are reported before the (possibly slow) model loading.
    reader.reject_unknown_keys();
    append_scene_objects(reader, scene, base_directory, budget);
    check_light_count(origin, scene, lights.size());
    return scene;
}

Scene load_scene(const std::string& path_or_builtin, const LoadBudget& budget) {
    if (path_or_builtin.starts_with(kBuiltinPrefix)) {
        return builtin_scene(path_or_builtin.substr(kBuiltinPrefix.size()));
    }
    const std::filesystem::path file(path_or_builtin);
    const std::string text = read_text_file(file, path_or_builtin, "scene file");
    return parse_scene_toml(text, path_or_builtin, file.parent_path(), budget);
}

}  // namespace penumbra
