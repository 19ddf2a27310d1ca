// glTF 2.0 features that shape a shadow (issue 19), each in a small fixture that must load
// to exactly what a plain equivalent loads to (tests/data/gltf/make_fixtures.py,
// write_conformance_fixtures): sparse accessors (with and without a bufferView, positions
// and indices), textureInfo.texCoord = 1, morph targets posed by mesh and node weights,
// KHR_mesh_quantization; and the clear errors for their malformed or undeclared forms.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene/loader.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

using ::testing::HasSubstr;
using testing::input_error_message;
using testing::test_data;

Scene load_fixture(const std::string& name) {
    Scene scene;
    append_gltf(scene, test_data("gltf/" + name), {glm::mat4{1.0f}});
    return scene;
}

std::string load_error(const std::string& name) {
    return input_error_message([&] { load_fixture(name); });
}

// Each triangle's world-space corners, normals and texture coordinates, in index order:
// equal lists mean the same shadow caster whatever the vertex layout or node transform.
struct WorldTriangles {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
};

WorldTriangles world_triangles(const Scene& scene) {
    WorldTriangles triangles;
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[instance.mesh];
        const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3{instance.world}));
        for (const uint32_t index : mesh.indices) {
            const Vertex& vertex = mesh.vertices[index];
            triangles.positions.push_back(glm::vec3{instance.world * glm::vec4{vertex.position, 1.0f}});
            triangles.normals.push_back(glm::normalize(normal_matrix * vertex.normal));
            triangles.uvs.push_back(vertex.uv);
        }
    }
    return triangles;
}

void expect_same_triangles(const std::string& fixture, const std::string& equivalent) {
    SCOPED_TRACE(fixture + " against " + equivalent);
    const WorldTriangles expected = world_triangles(load_fixture(equivalent));
    const WorldTriangles actual = world_triangles(load_fixture(fixture));
    ASSERT_EQ(actual.positions.size(), expected.positions.size());
    ASSERT_FALSE(actual.positions.empty());
    for (size_t i = 0; i < actual.positions.size(); ++i) {
        EXPECT_LE(glm::distance(actual.positions[i], expected.positions[i]), 1e-6f) << "corner " << i;
        EXPECT_LE(glm::distance(actual.normals[i], expected.normals[i]), 1e-6f) << "normal " << i;
        EXPECT_LE(glm::distance(actual.uvs[i], expected.uvs[i]), 1e-6f) << "uv " << i;
    }
}

TEST(GltfConformance, SparsePositionsAndIndicesLoadAsTheDenseQuad) {
    expect_same_triangles("sparse.gltf", "quad.gltf");
    expect_same_triangles("sparse_without_buffer_view.gltf", "quad.gltf");
}

TEST(GltfConformance, AlphaTextureReadsTheTexcoordSetItNames) {
    expect_same_triangles("texcoord1.gltf", "textured.gltf");
    const Scene scene = load_fixture("texcoord1.gltf");
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.materials.at(scene.meshes[0].material).base_color_texture, 0);
}

// KHR_texture_transform decides which texels of an alpha mask cut the shadow: applied to the
// UVs at load (offset and scale; rotation in the direction of KhronosGroup/glTF#1563).
TEST(GltfConformance, TextureTransformIsAppliedToTheAlphaTextureCoordinates) {
    expect_same_triangles("texture_transform.gltf", "textured.gltf");
    expect_same_triangles("texture_transform_rotation.gltf", "textured.gltf");
}

// KHR_materials_pbrSpecularGlossiness: the diffuse factor and texture are the base colour
// (and so the alpha mask), as the metallic-roughness equivalent's.
TEST(GltfConformance, SpecularGlossinessDiffuseIsTheBaseColour) {
    expect_same_triangles("spec_gloss.gltf", "textured.gltf");
    const Scene expected = load_fixture("textured.gltf");
    const Scene actual = load_fixture("spec_gloss.gltf");
    const Material& material = actual.materials.at(actual.meshes[0].material);
    EXPECT_EQ(material.base_color, expected.materials.at(expected.meshes[0].material).base_color);
    ASSERT_EQ(material.base_color_texture, 0);
    EXPECT_EQ(actual.textures[0].rgba8, expected.textures[0].rgba8);
    EXPECT_TRUE(actual.warnings.empty());
}

TEST(GltfConformance, MorphTargetsPoseTheMeshWithMeshOrNodeWeights) {
    expect_same_triangles("morph_mesh_weights.gltf", "quad.gltf");
    expect_same_triangles("morph_node_weights.gltf", "quad.gltf");
}

TEST(GltfConformance, QuantizedAttributesLoadAsTheFloatQuad) {
    expect_same_triangles("quantized.gltf", "quad.gltf");
    EXPECT_TRUE(load_fixture("quantized.gltf").warnings.empty()) << "KHR_mesh_quantization is read, not ignored";
}

TEST(GltfConformance, MalformedOrUndeclaredFormsAreClearErrors) {
    EXPECT_THAT(load_error("sparse_index_out_of_range.gltf"),
                HasSubstr(".sparse.indices: index 2 at position 1 is out of range (the accessor has 2 elements)"));
    EXPECT_THAT(load_error("quantized_undeclared.gltf"),
                HasSubstr("attributes.POSITION: 3 components of SHORT needs the KHR_mesh_quantization extension"));
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// KHR_lights_punctual (issue 19): lights placed by nodes, imported only when asked, in
// world space through the placement, with glTF's units and defaults mapped as documented.
TEST(GltfLights, PunctualLightsAreImportedThroughTheirNodesAndPlacement) {
    Scene without;
    append_gltf(without, test_data("gltf/lights.gltf"), {glm::mat4{1.0f}});
    EXPECT_TRUE(without.lights.empty()) << "lights are imported only with import_lights";
    // Extensions Penumbra does not read are named in one warning line per file.
    ASSERT_EQ(without.warnings.size(), 1u);
    EXPECT_THAT(without.warnings[0],
                HasSubstr("lights.gltf: ignores the glTF extension(s) KHR_lights_punctual (import_lights = true reads "
                          "its lights)"));

    Scene scene;
    const glm::mat4 placement = glm::translate(glm::mat4{1.0f}, glm::vec3{10.0f, 0.0f, 0.0f});
    append_gltf(scene, test_data("gltf/lights.gltf"), {placement}, {.import_lights = true});
    ASSERT_EQ(scene.lights.size(), 3u);
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    const Light& spot = scene.lights[0];
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_LE(glm::distance(spot.position, glm::vec3(10.0f, 5.0f, 0.0f)), 1e-5f);
    EXPECT_LE(glm::distance(spot.direction, glm::vec3(0.0f, -1.0f, 0.0f)), 1e-5f);
    EXPECT_EQ(spot.color, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_FLOAT_EQ(spot.intensity, 40.0f);
    EXPECT_FLOAT_EQ(spot.range, 12.0f);
    EXPECT_NEAR(spot.inner_angle_degrees, 11.4592f, 1e-3f);
    EXPECT_NEAR(spot.outer_angle_degrees, 34.3775f, 1e-3f);
    EXPECT_EQ(spot.radius, 0.0f);
    const Light& point = scene.lights[1];
    EXPECT_EQ(point.type, LightType::Point);
    EXPECT_LE(glm::distance(point.position, glm::vec3(12.0f, 3.0f, 0.0f)), 1e-5f);
    EXPECT_FLOAT_EQ(point.range, 20.0f) << "no range: where 4 cd / d^2 falls to 1/100 of its 1 m value";
    const Light& sun = scene.lights[2];
    EXPECT_EQ(sun.type, LightType::Directional);
    EXPECT_LE(glm::distance(sun.direction, glm::vec3(0.0f, -1.0f, 0.0f)), 1e-5f);
    EXPECT_FLOAT_EQ(sun.intensity, 2.5f);
}

// From a scene file: `import_lights = true`; the scene's own lights come first, so the
// file's directional light is the sun only when the scene has none.
TEST(GltfLights, SceneFileImportsAfterItsOwnLights) {
    const std::string object = "[[objects]]\ntype = \"gltf\"\nfile = \"" + test_data("gltf/lights.gltf").string() +
                               "\"\nimport_lights = true\n";
    const Scene with_sun =
        testing::parse_scene_text("[[lights]]\ntype = \"directional\"\ndirection = [1.0, -1.0, 0.0]\n\n" + object);
    ASSERT_EQ(with_sun.lights.size(), 4u);
    EXPECT_EQ(with_sun.lights[0].type, LightType::Directional);
    EXPECT_GT(with_sun.lights[0].direction.x, 0.5f);
    EXPECT_EQ(testing::parse_scene_text(object).lights.size(), 3u);
    EXPECT_THAT(testing::scene_error(object + "import_lights = \"yes\"\n"), HasSubstr("import_lights"));
}

// Emission: emissiveFactor times KHR_materials_emissive_strength, and the emissive texture
// when it reads the UVs the mesh keeps (the base colour's); one read with other UVs is left
// out with a warning naming it, and its factor is kept.
TEST(GltfConformance, EmissiveFactorStrengthAndTexture) {
    const Scene scene = load_fixture("emissive.gltf");
    ASSERT_EQ(scene.materials.size(), 1u);
    const Material& material = scene.materials[0];
    EXPECT_EQ(material.emissive, glm::vec3(4.0f, 2.0f, 1.0f));
    EXPECT_EQ(material.emissive_texture, material.base_color_texture);
    EXPECT_GE(material.emissive_texture, 0);
    EXPECT_TRUE(scene.warnings.empty()) << "KHR_materials_emissive_strength is read, not ignored";

    const Scene other_uvs = load_fixture("emissive_other_uvs.gltf");
    EXPECT_EQ(other_uvs.materials[0].emissive, glm::vec3(1.0f));
    EXPECT_EQ(other_uvs.materials[0].emissive_texture, -1);
    ASSERT_EQ(other_uvs.warnings.size(), 1u);
    EXPECT_THAT(other_uvs.warnings[0], HasSubstr("materials[0].emissiveTexture: ignored"));
}

TEST(GltfConformance, MalformedEmissionIsNamed) {
    EXPECT_THAT(load_error("emissive_negative.gltf"),
                HasSubstr("materials[0].emissiveFactor[1]: expected a number in [0.0, 1.0], got -0.5"));
    EXPECT_THAT(load_error("emissive_bad_strength.gltf"),
                HasSubstr("materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength: expected a "
                          "number >= 0.0, got \"bright\""));
}

}  // namespace
}  // namespace penumbra
