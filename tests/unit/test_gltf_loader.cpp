// glTF loading from small hand-made fixtures (tests/data/gltf/make_fixtures.py): geometry,
// index types, containers, node transforms, materials and textures.
#include <gtest/gtest.h>

#include <cctype>
#include <glm/gtc/matrix_transform.hpp>

#include <filesystem>

#include "gltf_writer.hpp"
#include "penumbra/scene/loader.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

using testing::test_data;

Scene load_fixture(const std::string& name, const std::vector<glm::mat4>& placements = {glm::mat4{1.0f}}) {
    Scene scene;
    append_gltf(scene, test_data("gltf/" + name), placements);
    return scene;
}

glm::vec3 transform_point(const glm::mat4& transform, const glm::vec3& point) {
    return glm::vec3{transform * glm::vec4{point, 1.0f}};
}

// World-space normal of every triangle of an instance, from its winding.
std::vector<glm::vec3> world_face_normals(const Scene& scene, const Instance& instance) {
    const Mesh& mesh = scene.meshes[instance.mesh];
    std::vector<glm::vec3> normals;
    for (size_t first = 0; first + 2 < mesh.indices.size(); first += 3) {
        const glm::vec3 a = transform_point(instance.world, mesh.vertices[mesh.indices[first]].position);
        const glm::vec3 b = transform_point(instance.world, mesh.vertices[mesh.indices[first + 1]].position);
        const glm::vec3 c = transform_point(instance.world, mesh.vertices[mesh.indices[first + 2]].position);
        normals.push_back(glm::normalize(glm::cross(b - a, c - a)));
    }
    return normals;
}

void expect_upward_faces(const Scene& scene, const Instance& instance) {
    for (const glm::vec3& normal : world_face_normals(scene, instance)) EXPECT_GT(normal.y, 0.99f);
}

class GltfQuadContainers : public ::testing::TestWithParam<std::string> {};

// The same quad as embedded JSON, external .bin, .glb, and with 8/16/32-bit indices.
TEST_P(GltfQuadContainers, LoadTheSameQuad) {
    const Scene scene = load_fixture(GetParam());
    ASSERT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(scene.instances.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    EXPECT_EQ(mesh.vertices.size(), 4u);
    EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(mesh.bounds.min, glm::vec3(-0.5f, 0.0f, -0.5f));
    EXPECT_EQ(mesh.bounds.max, glm::vec3(0.5f, 0.0f, 0.5f));
    EXPECT_EQ(mesh.vertices[2].uv, glm::vec2(1.0f, 1.0f));
    for (const Vertex& vertex : mesh.vertices) EXPECT_EQ(vertex.normal, glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(glm::vec3{scene.instances[0].world[3]}, glm::vec3(1.0f, 2.0f, 3.0f)) << "node translation";
    expect_upward_faces(scene, scene.instances[0]);
}

INSTANTIATE_TEST_SUITE_P(GltfLoader, GltfQuadContainers,
                         ::testing::Values("quad.gltf", "quad_external.gltf", "quad.glb", "quad_u8.gltf",
                                           "quad_u32.gltf"),
                         [](const auto& test_info) {
                             std::string name = test_info.param;
                             for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                             return name;
                         });

TEST(GltfLoader, ReadsMaterialProperties) {
    const Scene scene = load_fixture("quad.gltf");
    ASSERT_EQ(scene.materials.size(), 1u);
    const Material& material = scene.materials[scene.meshes[0].material];
    EXPECT_EQ(material.base_color, glm::vec4(0.5f, 0.25f, 1.0f, 0.8f));
    EXPECT_EQ(material.alpha_mode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(material.alpha_cutoff, 0.3f);
    EXPECT_TRUE(material.double_sided);
    EXPECT_FLOAT_EQ(material.roughness, 0.4f);
    EXPECT_FLOAT_EQ(material.metallic, 0.1f);
    EXPECT_EQ(material.base_color_texture, -1);
}

TEST(GltfLoader, GeneratesIndicesAndSmoothNormals) {
    const Scene scene = load_fixture("unindexed_no_normals.gltf");
    const Mesh& mesh = scene.meshes.at(0);
    EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
    for (const Vertex& vertex : mesh.vertices) {
        EXPECT_NEAR(vertex.normal.y, 1.0f, 1e-6f);
        EXPECT_NEAR(glm::length(vertex.normal), 1.0f, 1e-6f);
    }
}

TEST(GltfLoader, ConvertsStripsAndFansKeepingTheWinding) {
    for (const char* name : {"strip.gltf", "fan.gltf"}) {
        SCOPED_TRACE(name);
        const Scene scene = load_fixture(name);
        ASSERT_EQ(scene.instances.size(), 1u);
        EXPECT_EQ(scene.meshes[0].indices.size(), 6u);
        expect_upward_faces(scene, scene.instances[0]);
    }
}

TEST(GltfLoader, SkipsPointAndLinePrimitives) {
    const Scene scene = load_fixture("points_lines_triangles.gltf");
    EXPECT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.triangle_count(), 2u);
}

TEST(GltfLoader, ComposesTheNodeHierarchyOfTheDefaultScene) {
    const Scene scene = load_fixture("hierarchy.gltf");
    ASSERT_EQ(scene.instances.size(), 2u) << "node 3 is not in the scene";
    // Node 1: parent translation (10, 0, 0) * matrix (scale 2, translation (0, 5, 0)).
    const glm::mat4& scaled = scene.instances[0].world;
    EXPECT_EQ(transform_point(scaled, glm::vec3{0.0f}), glm::vec3(10.0f, 5.0f, 0.0f));
    EXPECT_EQ(transform_point(scaled, glm::vec3{0.5f, 0.0f, 0.0f}), glm::vec3(11.0f, 5.0f, 0.0f));
    // Node 2: mirrored in X.
    EXPECT_EQ(transform_point(scene.instances[1].world, glm::vec3{0.5f, 0.0f, 0.0f}), glm::vec3(9.5f, 0.0f, 0.0f));
}

TEST(GltfLoader, MirroredNodesGetAReversedWindingCopy) {
    const Scene scene = load_fixture("hierarchy.gltf");
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_NE(scene.instances[0].mesh, scene.instances[1].mesh);
    EXPECT_LT(glm::determinant(glm::mat3{scene.instances[1].world}), 0.0f);
    // Both placements still show counter-clockwise front faces towards +Y in the world.
    expect_upward_faces(scene, scene.instances[0]);
    expect_upward_faces(scene, scene.instances[1]);
}

TEST(GltfLoader, WithoutScenesEveryRootNodeIsPlaced) {
    const Scene scene = load_fixture("no_scene.gltf");
    EXPECT_EQ(scene.instances.size(), 3u);
}

TEST(GltfLoader, EachPlacementInstancesTheWholeModel) {
    const glm::mat4 moved = glm::translate(glm::mat4{1.0f}, glm::vec3{0.0f, 0.0f, -20.0f});
    const Scene scene = load_fixture("hierarchy.gltf", {glm::mat4{1.0f}, moved});
    ASSERT_EQ(scene.instances.size(), 4u);
    EXPECT_EQ(scene.meshes.size(), 2u) << "placements share meshes";
    EXPECT_EQ(transform_point(scene.instances[2].world, glm::vec3{0.0f}), glm::vec3(10.0f, 5.0f, -20.0f));
}

TEST(GltfLoader, AppendsAfterExistingContent) {
    Scene scene = load_fixture("textured.gltf");
    append_gltf(scene, test_data("gltf/textured.gltf"), {glm::mat4{1.0f}});
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_EQ(scene.meshes[1].material, 1u);
    EXPECT_EQ(scene.instances[1].mesh, 1u);
    EXPECT_EQ(scene.materials[1].base_color_texture, 1);
    EXPECT_EQ(scene.textures.size(), 2u);
}

TEST(GltfLoader, DecodesTheBaseColourTextureAsRgba8) {
    const Scene scene = load_fixture("textured.gltf");
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.materials[0].base_color_texture, 0);
    const Texture& texture = scene.textures[0];
    EXPECT_EQ(texture.width, 2u);
    EXPECT_EQ(texture.height, 2u);
    EXPECT_EQ(texture.rgba8, (std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0, 255, 255, 255, 255}));
}

TEST(GltfLoader, ConvertsSixteenBitGreyAlphaToRgba8) {
    const Scene scene = load_fixture("textured_grey_alpha16.gltf");
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.textures[0].rgba8,
              (std::vector<uint8_t>{255, 255, 255, 0x80, 0x12, 0x12, 0x12, 0, 0, 0, 0, 255, 0x80, 0x80, 0x80, 0x40}));
}

// COLOR_0 is kept per vertex as 8-bit linear RGB (alpha not applied), and white without it.
TEST(GltfLoader, KeepsVertexColours) {
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "penumbra_vertex_colours.gltf";
    testing::GltfTestPrimitive box = testing::test_box(glm::vec3{0.0f}, 1.0f);
    box.colors.assign(box.positions.size(), glm::vec4{0.8f, 0.2f, 0.4f, 0.5f});
    testing::write_test_gltf(file,
                             {{"Coloured", "", {box}}, {"Plain", "", {testing::test_box(glm::vec3{3.0f}, 1.0f)}}});
    Scene scene;
    append_gltf(scene, file, {glm::mat4{1.0f}});
    std::filesystem::remove(file);
    std::filesystem::remove(std::filesystem::path(file).replace_extension(".bin"));
    ASSERT_EQ(scene.meshes.size(), 2u);
    for (const Vertex& vertex : scene.meshes[0].vertices) EXPECT_EQ(vertex.color, glm::u8vec4(204, 51, 102, 255));
    for (const Vertex& vertex : scene.meshes[1].vertices) EXPECT_EQ(vertex.color, glm::u8vec4(255, 255, 255, 255));
}

}  // namespace
}  // namespace penumbra
