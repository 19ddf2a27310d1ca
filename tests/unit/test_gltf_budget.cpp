// The load budget (issue 32, items 6 and 7): image headers and accessor counts are read
// before anything is decoded or expanded, so decompression and geometry bombs are refused
// in a time proportional to the file, and the counting agrees with what loading makes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <string>

#include "scene/gltf_internal.hpp"
#include "scene_test_support.hpp"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::input_error_message;
using testing::test_data;

std::string read_file(const fs::path& file) {
    std::ifstream stream(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

std::span<const unsigned char> as_bytes(const std::string& text) {
    return {reinterpret_cast<const unsigned char*>(text.data()), text.size()};
}

std::string big_endian(uint32_t value, size_t size) {
    std::string bytes;
    for (size_t i = size; i-- > 0;) bytes += static_cast<char>((value >> (8 * i)) & 0xFF);
    return bytes;
}

// The start of a PNG: signature and IHDR (8-bit RGBA) declaring width x height; the CRC is
// not checked before decoding, and decoding never starts.
std::string png_header(uint32_t width, uint32_t height) {
    return std::string("\x89PNG\r\n\x1a\n", 8) + big_endian(13, 4) + "IHDR" + big_endian(width, 4) +
           big_endian(height, 4) + std::string("\x08\x06\x00\x00\x00", 5) + big_endian(0, 4);
}

// SOI, an APP0 segment to skip (with fill bytes before the next marker), then a baseline
// frame header declaring width x height.
std::string jpeg_header(uint32_t width, uint32_t height) {
    return std::string("\xFF\xD8\xFF\xE0", 4) + big_endian(16, 2) + std::string(14, 'j') + "\xFF\xFF\xFF\xC0" +
           big_endian(17, 2) + "\x08" + big_endian(height, 2) + big_endian(width, 2) + std::string(12, '\x01');
}

TEST(ImageHeader, ReadsPngAndJpegSizesBeforeDecoding) {
    const std::optional<ImageHeader> png = read_image_header(as_bytes(png_header(16384, 32767)));
    ASSERT_TRUE(png);
    EXPECT_EQ(png->width, 16384u);
    EXPECT_EQ(png->height, 32767u);
    const std::optional<ImageHeader> jpeg = read_image_header(as_bytes(jpeg_header(640, 480)));
    ASSERT_TRUE(jpeg);
    EXPECT_EQ(jpeg->width, 640u);
    EXPECT_EQ(jpeg->height, 480u);
    const std::string baseline =
        read_file(test_data("../../../shared/assets/AlphaBlendModeTest/glTF/"
                            "MatBed_baseColor.jpg"));
    if (!baseline.empty()) {
        EXPECT_TRUE(read_image_header(as_bytes(baseline)));
    }
}

TEST(ImageHeader, RefusesOtherFormatsAndCutHeaders) {
    EXPECT_FALSE(read_image_header(as_bytes("GIF89a\x01\x00\x01\x00")));
    EXPECT_FALSE(read_image_header(as_bytes("")));
    EXPECT_FALSE(read_image_header(as_bytes(png_header(4, 4).substr(0, 20))));
    EXPECT_FALSE(read_image_header(as_bytes(jpeg_header(4, 4).substr(0, 30))));     // cut inside the frame header
    EXPECT_FALSE(read_image_header(as_bytes(std::string("\xFF\xD8\xFF\xDA", 4))));  // a scan before any frame
    EXPECT_FALSE(read_image_header(as_bytes(std::string("\xFF\xD8\xFF\xE0\x00\x01", 6))));  // length below 2
}

TEST(LoadBudgetArithmetic, SaturatesInsteadOfWrapping) {
    constexpr uint64_t kMax = std::numeric_limits<uint64_t>::max();
    EXPECT_EQ(saturating_add(kMax - 1, 2), kMax);
    EXPECT_EQ(saturating_add(3, 4), 7u);
    EXPECT_EQ(saturating_multiply(uint64_t{1} << 40, uint64_t{1} << 30), kMax);
    EXPECT_EQ(saturating_multiply(0, kMax), 0u);
    EXPECT_EQ(saturating_multiply(6, 7), 42u);
}

class GltfBudget : public testing::ScratchFolderTest {
protected:
    // The InputError of loading `file` once, and how long it took to refuse.
    std::string load_error(const fs::path& file, const LoadBudget& budget = {}, size_t placements = 1) {
        const auto start = std::chrono::steady_clock::now();
        std::string message = input_error_message([&] {
            Scene scene;
            GltfImportOptions options;
            options.budget = budget;
            append_gltf(scene, file, std::vector<glm::mat4>(placements, glm::mat4{1.0f}), options);
        });
        seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return message;
    }

    double seconds_ = 0.0;
};

// The textured quad fixture reading its base colour image from `image_file` beside it.
std::string textured_quad_reading(const std::string& image_file) {
    std::string text = read_file(test_data("gltf/textured.gltf"));
    const size_t start = text.find("\"data:image/png;base64,");
    const size_t end = text.find('"', start + 1);
    EXPECT_NE(start, std::string::npos);
    return text.replace(start, end - start + 1, "\"" + image_file + "\"");
}

// Issue 32, item 6: a 0.5 MB PNG declaring 16384 x 32767 pixels peaked at 6.4 GB. Its header
// alone now refuses it, saying it is refused (not downscaled), before any pixel is decoded.
TEST_F(GltfBudget, DecompressionBombsAreRefusedFromTheirHeaders) {
    write("bomb.png", png_header(16384, 32767) + std::string(1000, '\0'));
    EXPECT_THAT(
        load_error(write("png.gltf", textured_quad_reading("bomb.png"))),
        HasSubstr("images[0]: 16384 x 32767 pixels (2147418112 bytes as RGBA8) would take the scene past the "
                  "load budget of 1073741824 bytes (LoadBudget::max_bytes raises it); refused before decoding"));
    EXPECT_LT(seconds_, 1.0);
    write("bomb.jpg", jpeg_header(65535, 65535));
    EXPECT_THAT(load_error(write("jpeg.gltf", textured_quad_reading("bomb.jpg"))),
                HasSubstr("images[0]: 65535 x 65535 pixels (17179344900 bytes as RGBA8)"));
    write("image.gif", "GIF89a\x01\x00\x01\x00");
    EXPECT_THAT(load_error(write("gif.gltf", textured_quad_reading("image.gif"))),
                HasSubstr("images[0]: not a PNG or JPEG image, or its header is cut short"));
}

// A model whose `primitives` primitives read one accessor of `count` VEC3s without a buffer
// view, placed by `nodes` nodes. Without `sparse` the accessor is all zeros (about 250
// bytes describing 5.6 M triangles); with it, its first three elements are a triangle's
// corners read from sparse.bin (48 bytes: the indices 0, 1, 2 and three points), so the
// count's triangles are real to the counting and one of them has area.
std::string zeros_model(int primitives, int nodes, size_t count, bool sparse = false) {
    std::string text = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[)";
    for (int n = 0; n < nodes; ++n) text += (n ? "," : "") + std::to_string(n);
    text += "]}],\"nodes\":[";
    for (int n = 0; n < nodes; ++n) text += std::string(n ? "," : "") + R"({"mesh":0})";
    text += R"(],"meshes":[{"primitives":[)";
    for (int p = 0; p < primitives; ++p) text += std::string(p ? "," : "") + R"({"attributes":{"POSITION":0}})";
    text += R"(]}],"accessors":[{"componentType":5126,"count":)" + std::to_string(count) + R"(,"type":"VEC3")";
    if (!sparse) return text + "}]}";
    return text +
           R"(,"sparse":{"count":3,"indices":{"bufferView":0,"componentType":5125},"values":{"bufferView":1}}}],)"
           R"("buffers":[{"uri":"sparse.bin","byteLength":48}],"bufferViews":[)"
           R"({"buffer":0,"byteLength":12},{"buffer":0,"byteOffset":12,"byteLength":36}]})";
}

std::string sparse_triangle_bytes() {
    const std::array<uint32_t, 3> indices = {0, 1, 2};
    const std::array<float, 9> corners = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    std::string bytes(reinterpret_cast<const char*>(indices.data()), sizeof(indices));
    return bytes + std::string(reinterpret_cast<const char*>(corners.data()), sizeof(corners));
}

constexpr size_t kZeros = (size_t{1} << 24) - 1;  // whole triangles: 5,592,405

// Issue 32, item 7: a primitive of 2^24 zeros made 5.6 M triangles and 2.3 GB; 8 made 9.8
// GB; 64 nodes placing one ran past 2 minutes. An accessor of zeros alone makes triangles
// without area, which draw nothing: it is skipped unread. With a few sparse points over the
// zeros the counts are refused before expanding, in well under a second.
TEST_F(GltfBudget, GeometryBombsAreRefusedBeforeExpanding) {
    write("sparse.bin", sparse_triangle_bytes());
    EXPECT_THAT(load_error(write("eight.gltf", zeros_model(8, 1, kZeros, true))),
                HasSubstr("meshes: would make 44739240 triangles as placed, over the load budget of 33554432 "
                          "(LoadBudget::max_triangles raises it); refused before converting them"));
    EXPECT_LT(seconds_, 1.0);
    EXPECT_THAT(load_error(write("nodes.gltf", zeros_model(1, 64, kZeros, true))),
                HasSubstr("would make 357913920 triangles as placed"));
    EXPECT_LT(seconds_, 1.0);
    // Two primitives stay under the triangles but not the bytes: 2 x (2^24 - 1) vertices of
    // 36 bytes and 2 x 16,777,215 indices of 4.
    EXPECT_THAT(load_error(write("two.gltf", zeros_model(2, 1, kZeros, true))),
                HasSubstr("meshes: images and meshes would take 1342177200 bytes, over the load budget of "
                          "1073741824 bytes (LoadBudget::max_bytes raises it)"));
    EXPECT_LT(seconds_, 1.0);
}

// Triangles without area rasterise nothing: the loader keeps only those with area and the
// vertices they use, so the sparse bomb within the budget holds one triangle, and the zeros
// alone, however often placed, hold nothing and are not read.
TEST_F(GltfBudget, TrianglesWithoutAreaAreNotKept) {
    write("sparse.bin", sparse_triangle_bytes());
    Scene scene;
    append_gltf(scene, write("one.gltf", zeros_model(1, 1, kZeros, true)), {glm::mat4{1.0f}});
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2}));
    ASSERT_EQ(scene.meshes[0].vertices.size(), 3u);
    EXPECT_EQ(scene.meshes[0].vertices[2].position, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(scene.triangle_count(), 1u);

    const auto start = std::chrono::steady_clock::now();
    Scene zeros;
    append_gltf(zeros, write("zeros.gltf", zeros_model(8, 64, kZeros)), {glm::mat4{1.0f}});
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    EXPECT_TRUE(zeros.meshes.empty());
    EXPECT_EQ(zeros.triangle_count(), 0u);
}

// The budget counts each placement's triangles, and what the scene held before the model.
TEST_F(GltfBudget, CountsPlacementsAndWhatTheSceneHeld) {
    LoadBudget budget;
    budget.max_triangles = 1999;
    EXPECT_THAT(load_error(test_data("gltf/quad.gltf"), budget, 1000),
                HasSubstr("would make 2000 triangles as placed, over the load budget of 1999"));
    Scene scene;
    GltfImportOptions options;
    options.budget.max_triangles = 3;
    append_gltf(scene, test_data("gltf/quad.gltf"), {glm::mat4{1.0f}}, options);
    EXPECT_THAT(
        input_error_message([&] { append_gltf(scene, test_data("gltf/quad.gltf"), {glm::mat4{1.0f}}, options); }),
        HasSubstr("would make 2 triangles as placed (the scene held 2 before), over the load budget of 3"));
    EXPECT_EQ(scene.instances.size(), 1u) << "a refused model leaves the scene as it was";
}

// The counting is exact: every fixture, placed as is and mirrored (a mirrored placement
// gets its own copy of each mesh), loads with a budget of exactly what it makes
// (Scene::triangle_count(), its meshes' and textures' bytes) and is refused with one less.
TEST_F(GltfBudget, CountsExactlyWhatLoadingMakes) {
    const std::vector<glm::mat4> placements = {glm::mat4{1.0f},
                                               glm::scale(glm::mat4{1.0f}, glm::vec3{-1.0f, 1.0f, 1.0f})};
    for (const char* name : {"quad.gltf", "quad.glb", "quad_u8.gltf", "strip.gltf", "fan.gltf", "hierarchy.gltf",
                             "points_lines_triangles.gltf", "sparse.gltf", "morph_node_weights.gltf",
                             "morph_mesh_weights.gltf", "alpha_mirrored.gltf", "textured.gltf",
                             "unindexed_no_normals.gltf", "textured_grey_alpha16.gltf", "quantized.gltf"}) {
        SCOPED_TRACE(name);
        const fs::path file = test_data(std::string("gltf/") + name);
        const auto load = [&](const LoadBudget& budget) {
            Scene scene;
            GltfImportOptions options;
            options.budget = budget;
            append_gltf(scene, file, placements, options);
            return scene;
        };
        const GltfCost made = scene_cost(load({}));
        ASSERT_GT(made.triangles, 0u);
        LoadBudget exact;
        exact.max_triangles = made.triangles;
        exact.max_bytes = made.bytes;
        EXPECT_NO_THROW(load(exact));
        LoadBudget fewer_triangles = exact;
        --fewer_triangles.max_triangles;
        EXPECT_THAT(input_error_message([&] { load(fewer_triangles); }), HasSubstr("triangles as placed"));
        LoadBudget fewer_bytes = exact;
        --fewer_bytes.max_bytes;
        EXPECT_THAT(input_error_message([&] { load(fewer_bytes); }), HasSubstr("bytes"));
    }
}

}  // namespace
}  // namespace penumbra
