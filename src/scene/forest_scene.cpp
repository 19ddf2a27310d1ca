#include "scene/forest_scene.hpp"

#include <cmath>

#include "core/errors.hpp"
#include "scene/primitives.hpp"

namespace penumbra {
namespace {

// Mesh (and material) indices of the forest's object kinds.
enum ForestMesh : uint32_t { kGround, kTrunk, kCrown, kRock };

// Segment counts chosen for kForestTrianglesPerTree: a UV sphere has segments * (2 * rings
// - 2) triangles (30 x 16 -> 900), a capped cylinder 4 * segments (22 -> 88), a box 12.
constexpr uint32_t kCrownSegments = 30;
constexpr uint32_t kCrownRings = 16;
constexpr uint32_t kTrunkSegments = 22;

// SplitMix64 (Steele et al. 2014): a tiny stateless hash, so placement depends on the tree
// index alone and is the same on every platform (std:: distributions are not portable).
float random01(uint64_t tree, uint64_t stream) {
    uint64_t z = tree * 0x9E3779B97F4A7C15ull + stream * 0xBF58476D1CE4E5B9ull + 0x94D049BB133111EBull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<float>(z >> 40) / static_cast<float>(1ull << 24);
}

float lerp(float a, float b, float t) { return a + (b - a) * t; }

void add_materials(Scene& scene) {
    const glm::vec4 colors[] = {{0.36f, 0.42f, 0.25f, 1.0f},  // ground
                                {0.33f, 0.24f, 0.15f, 1.0f},  // bark
                                {0.18f, 0.42f, 0.16f, 1.0f},  // foliage
                                {0.52f, 0.5f, 0.47f, 1.0f}};  // rock
    for (const glm::vec4& color : colors) scene.materials.push_back(Material{color});
}

void add_meshes(Scene& scene) {
    scene.meshes.push_back(make_plane(kForestSize + 40.0f, kForestSize + 40.0f));
    scene.meshes.push_back(make_cylinder(1.0f, 1.0f, kTrunkSegments));
    scene.meshes.push_back(make_sphere(1.0f, kCrownSegments, kCrownRings));
    scene.meshes.push_back(make_box(glm::vec3{1.0f}));
    for (uint32_t kind = 0; kind < scene.meshes.size(); ++kind) scene.meshes[kind].material = kind;
}

// Tree `index` sits in its own cell of an n x n grid over the square (cells spread evenly
// when count is not a square number), jittered inside the cell.
glm::vec2 tree_position(uint32_t index, uint32_t count) {
    const auto cells_per_side = static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<double>(count))));
    const uint64_t cell = uint64_t{index} * cells_per_side * cells_per_side / count;
    const float cell_size = kForestSize / static_cast<float>(cells_per_side);
    const float x = (static_cast<float>(cell % cells_per_side) + lerp(0.2f, 0.8f, random01(index, 0))) * cell_size;
    const float z = (static_cast<float>(cell / cells_per_side) + lerp(0.2f, 0.8f, random01(index, 1))) * cell_size;
    return glm::vec2{x, z} - 0.5f * kForestSize;
}

void add_tree(Scene& scene, uint32_t index, uint32_t count) {
    const glm::vec2 base = tree_position(index, count);
    const float trunk_height = lerp(3.0f, 6.0f, random01(index, 2));
    const float trunk_radius = lerp(0.18f, 0.35f, random01(index, 3));
    const float crown_radius = lerp(1.5f, 3.0f, random01(index, 4));
    const float crown_height = crown_radius * lerp(1.2f, 1.8f, random01(index, 5));
    const glm::vec3 zero{0.0f};
    scene.instances.push_back({kTrunk, compose_transform({base.x, 0.5f * trunk_height, base.y}, zero,
                                                         {trunk_radius, trunk_height, trunk_radius})});
    // The crown overlaps the trunk's top third, so the two read as one tree from afar.
    const float crown_center = trunk_height + 0.6f * crown_height;
    scene.instances.push_back(
        {kCrown, compose_transform({base.x, crown_center, base.y}, zero, {crown_radius, crown_height, crown_radius})});
    const float rock_angle = 6.2831853f * random01(index, 6);
    const float rock_distance = lerp(2.0f, 4.0f, random01(index, 7));
    const glm::vec3 rock_size{lerp(0.6f, 1.6f, random01(index, 8)), lerp(0.4f, 1.0f, random01(index, 9)),
                              lerp(0.6f, 1.4f, random01(index, 10))};
    const glm::vec3 rock_position{base.x + rock_distance * std::cos(rock_angle), 0.4f * rock_size.y,
                                  base.y + rock_distance * std::sin(rock_angle)};
    scene.instances.push_back(
        {kRock, compose_transform(rock_position, {0.0f, glm::degrees(rock_angle), 0.0f}, rock_size)});
}

}  // namespace

Scene make_forest_scene(uint32_t count) {
    Scene scene;
    // From inside the forest, looking across it: the shadow distance (150 m) is full of trees.
    scene.camera.eye = {0.0f, 20.0f, 90.0f};
    scene.camera.target = {0.0f, 3.0f, 0.0f};
    scene.camera.far_plane = 800.0f;
    Light sun;
    sun.color = {1.0f, 0.96f, 0.9f};
    scene.lights.push_back(sun);
    add_materials(scene);
    add_meshes(scene);
    scene.instances.reserve(1 + size_t{3} * count);
    scene.instances.push_back({kGround, glm::mat4{1.0f}});
    for (uint32_t index = 0; index < count; ++index) add_tree(scene, index, count);
    return scene;
}

uint32_t parse_forest_count(const std::string& query, const std::string& origin) {
    if (query.empty()) return kForestDefaultCount;
    const std::string expected = "expected count=N with N between 1 and " + std::to_string(kForestMaxCount);
    if (!query.starts_with("count=")) throw InputError(origin + ": " + expected + ", got \"" + query + "\"");
    const std::string digits = query.substr(6);
    const bool numeric =
        !digits.empty() && digits.size() <= 9 && digits.find_first_not_of("0123456789") == std::string::npos;
    const unsigned long count = numeric ? std::stoul(digits) : 0;
    if (count < 1 || count > kForestMaxCount) {
        throw InputError(origin + ": count: " + expected + ", got \"" + digits + "\"");
    }
    return static_cast<uint32_t>(count);
}

}  // namespace penumbra
