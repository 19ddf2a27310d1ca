#include "inspect.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>

#include "penumbra/errors.hpp"
#include "penumbra/scene/inventory.hpp"

namespace penumbra::cli {
namespace {

using nlohmann::json;

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

std::string vector_text(const glm::vec3& v) {
    return "[" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + "]";
}

std::string bounds_text(const Aabb& box) {
    return box.empty() ? "empty" : vector_text(box.min) + " .. " + vector_text(box.max);
}

std::string quoted_or_unnamed(const std::string& name) {
    return name.empty() ? "(unnamed)" : "\"" + escape_control_characters(name) + "\"";
}

std::string alpha_modes_text(const SceneEntry& entry) {
    std::string text;
    for (const AlphaMode mode : entry.alpha_modes)
        text += (text.empty() ? "" : "+") + std::string(alpha_mode_name(mode));
    return text;
}

std::string share_text(uint32_t count, size_t total) {
    if (count == 0) return "none";
    return count == total ? "all" : std::to_string(count) + " of " + std::to_string(total);
}

// "objects[2] gltf sky.gltf node nodes[0] (unnamed) mesh meshes[0] "skbox" exclude_casters "skbox"".
std::string entry_heading(const SceneEntry& entry) {
    const InstanceOrigin& o = entry.origin;
    std::string text =
        o.object >= 0 ? "objects[" + std::to_string(o.object) + "] " + o.type : entry.name + " (built-in)";
    if (!o.file.empty()) text += " " + escape_control_characters(o.file);
    if (o.node < 0) return text;
    return text + "  node nodes[" + std::to_string(o.node) + "] " + quoted_or_unnamed(o.node_name) + "  mesh meshes[" +
           std::to_string(o.mesh) + "] " + quoted_or_unnamed(o.mesh_name) + "  exclude_casters \"" +
           escape_control_characters(exclusion_name(o)) + "\"";
}

std::string entry_details(const SceneEntry& entry) {
    const size_t instances = entry.instances.size();
    return "    " + std::to_string(entry.primitives) + " primitive(s), " + std::to_string(entry.placements) +
           " placement(s), " + std::to_string(entry.triangles) +
           " triangles; casts: " + share_text(entry.casting, instances) +
           ", receives: " + share_text(entry.receiving, instances) +
           (entry.dynamic ? ", dynamic: " + share_text(entry.dynamic, instances) : "") + "; alpha " +
           alpha_modes_text(entry) + "; bounds " + bounds_text(entry.bounds) + "\n";
}

std::string light_line(size_t index, const Light& light) {
    std::string text = "  lights[" + std::to_string(index) + "] " + light_type_name(light.type);
    if (light.type != LightType::Directional) text += " at " + vector_text(light.position);
    if (light.type != LightType::Point) text += " toward " + vector_text(light.direction);
    text += ", intensity " + number(light.intensity);
    if (light.type != LightType::Directional) text += ", range " + number(light.range) + " m";
    return text + (light.cast_shadows ? ", casts shadows\n" : ", no shadows\n");
}

std::string format_text(const Scene& scene, const std::string& scene_name, const std::vector<SceneEntry>& entries) {
    std::string text = escape_control_characters(scene_name) + ": " + std::to_string(entries.size()) +
                       " object(s) or glTF node(s), " + std::to_string(scene.instances.size()) + " instance(s), " +
                       std::to_string(scene.triangle_count()) + " triangles, bounds " +
                       bounds_text(scene.world_bounds()) + "\n";
    const Camera& c = scene.camera;
    text += "camera: eye " + vector_text(c.eye) + ", target " + vector_text(c.target) + ", fov " +
            number(c.fov_y_degrees) + ", near " + number(c.near_plane) + ", far " + number(c.far_plane) + "\n";
    text += "lights: " + std::to_string(scene.lights.size()) + "\n";
    for (size_t i = 0; i < scene.lights.size(); ++i) text += light_line(i, scene.lights[i]);
    text += "objects:\n";
    for (const SceneEntry& entry : entries) text += "  " + entry_heading(entry) + "\n" + entry_details(entry);
    for (const std::string& warning : scene.warnings) text += "warning: " + escape_control_characters(warning) + "\n";
    return text;
}

json vector_json(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

json bounds_json(const Aabb& box) {
    if (box.empty()) return nullptr;
    return {{"min", vector_json(box.min)}, {"max", vector_json(box.max)}};
}

json entry_json(const SceneEntry& entry) {
    const InstanceOrigin& o = entry.origin;
    json modes = json::array();
    for (const AlphaMode mode : entry.alpha_modes) modes.push_back(alpha_mode_name(mode));
    json result = {{"name", entry.name},
                   {"object", o.object >= 0 ? json(o.object) : json(nullptr)},
                   {"type", o.type},
                   {"primitives", entry.primitives},
                   {"placements", entry.placements},
                   {"instances", entry.instances.size()},
                   {"triangles", entry.triangles},
                   {"casting", entry.casting},
                   {"receiving", entry.receiving},
                   {"dynamic", entry.dynamic},
                   {"alpha_modes", modes},
                   {"bounds", bounds_json(entry.bounds)}};
    if (o.node >= 0) {
        result["file"] = o.file;
        result["node"] = o.node;
        result["node_name"] = o.node_name;
        result["mesh"] = o.mesh;
        result["mesh_name"] = o.mesh_name;
        result["exclude_casters"] = exclusion_name(o);
    }
    return result;
}

json light_json(const Light& light) {
    return {{"type", light_type_name(light.type)},
            {"direction", vector_json(light.direction)},
            {"position", vector_json(light.position)},
            {"color", vector_json(light.color)},
            {"intensity", light.intensity},
            {"range", light.range},
            {"cast_shadows", light.cast_shadows}};
}

std::string format_json(const Scene& scene, const std::string& scene_name, const std::vector<SceneEntry>& entries) {
    json document = {{"scene", scene_name},
                     {"instances", scene.instances.size()},
                     {"triangles", scene.triangle_count()},
                     {"bounds", bounds_json(scene.world_bounds())},
                     {"camera",
                      {{"eye", vector_json(scene.camera.eye)},
                       {"target", vector_json(scene.camera.target)},
                       {"up", vector_json(scene.camera.up)},
                       {"fov", scene.camera.fov_y_degrees},
                       {"near", scene.camera.near_plane},
                       {"far", scene.camera.far_plane}}},
                     {"lights", json::array()},
                     {"objects", json::array()},
                     {"warnings", scene.warnings}};
    for (const Light& light : scene.lights) document["lights"].push_back(light_json(light));
    for (const SceneEntry& entry : entries) document["objects"].push_back(entry_json(entry));
    // Names from files may hold any bytes: replace invalid UTF-8 rather than throw.
    return document.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

}  // namespace

std::string format_inspection(const Scene& scene, const std::string& scene_name, bool json_output) {
    const std::vector<SceneEntry> entries = scene_inventory(scene);
    return json_output ? format_json(scene, scene_name, entries) : format_text(scene, scene_name, entries);
}

std::string inspect_scene(const InspectJob& job) {
    return format_inspection(load_scene(job.scene, job.load_budget), job.scene, job.json);
}

}  // namespace penumbra::cli
