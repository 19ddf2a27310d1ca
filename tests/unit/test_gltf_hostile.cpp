// Hostile glTF files made to exhaust the loader (issue 17): a node chain as deep as the file
// is long, JSON nested thousands of levels deep (.gltf and .glb), a buffer uri naming a
// FIFO, a model placed more often than a scene can hold. Each must be one InputError, in
// well under a second, with no crash, hang or memory blow-up.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "scene_test_support.hpp"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::input_error_message;
using testing::test_data;

class GltfHostile : public testing::ScratchFolderTest {
protected:
    static std::string load_error(const fs::path& file, size_t placements = 1) {
        return input_error_message([&] {
            Scene scene;
            append_gltf(scene, file, std::vector<glm::mat4>(placements, glm::mat4{1.0f}));
        });
    }
};

// The quad fixture's text with its "nodes" array replaced.
std::string quad_with_nodes(const std::string& nodes_json) {
    std::ifstream file(test_data("gltf/quad.gltf"));
    std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const size_t start = text.find("\"nodes\": [\n  {");
    const size_t end = text.find("\n ],", start);
    EXPECT_NE(start, std::string::npos);
    EXPECT_NE(end, std::string::npos);
    return text.substr(0, start) + "\"nodes\": " + nodes_json + text.substr(end + 3);
}

// 100,000 nodes, each the only child of the one before: a recursive walk overflows the stack
// (it did at ~20 k). Loaded iteratively, the chain's one mesh at its end is placed once.
TEST_F(GltfHostile, DeepNodeChainLoads) {
    constexpr int kDepth = 100000;
    std::string nodes = "[";
    for (int i = 0; i < kDepth - 1; ++i) nodes += "{\"children\":[" + std::to_string(i + 1) + "]},";
    nodes += "{\"mesh\":0,\"translation\":[0,1,0]}]";
    Scene scene;
    append_gltf(scene, write("chain.gltf", quad_with_nodes(nodes)), {glm::mat4{1.0f}});
    ASSERT_EQ(scene.instances.size(), 1u);
    EXPECT_EQ(scene.instances[0].world[3][1], 1.0f);
}

std::string nested_extras(int depth) {
    return "{\"asset\":{\"version\":\"2.0\",\"extras\":" + std::string(static_cast<size_t>(depth), '[') +
           std::string(static_cast<size_t>(depth), ']') + "}}";
}

TEST_F(GltfHostile, DeeplyNestedJsonIsRefused) {
    EXPECT_THAT(load_error(write("deep.gltf", nested_extras(20000))),
                HasSubstr("its JSON nests arrays and objects more than 256 levels deep"));
    // Brackets inside strings are not nesting.
    const std::string in_string = "{\"asset\":{\"version\":\"2.0\",\"extras\":\"" + std::string(20000, '[') + "\"}}";
    Scene scene;
    EXPECT_NO_THROW(append_gltf(scene, write("string.gltf", in_string), {glm::mat4{1.0f}}));
}

TEST_F(GltfHostile, DeeplyNestedJsonInAGlbIsRefused) {
    std::string json = nested_extras(20000);
    json.resize((json.size() + 3) / 4 * 4, ' ');  // chunks are 4-byte aligned
    std::string glb(20, '\0');
    const auto put = [&glb](size_t offset, uint32_t value) { std::memcpy(glb.data() + offset, &value, 4); };
    std::memcpy(glb.data(), "glTF", 4);
    put(4, 2);
    put(8, static_cast<uint32_t>(20 + json.size()));
    put(12, static_cast<uint32_t>(json.size()));
    put(16, 0x4E4F534Au);  // "JSON"
    glb += json;
    EXPECT_THAT(load_error(write("deep.glb", glb)), HasSubstr("more than 256 levels deep"));
}

// Opening a FIFO for reading waits for a writer: a uri naming one must be refused, not read.
TEST_F(GltfHostile, BufferUriNamingAFifoIsRefused) {
    ASSERT_EQ(::mkfifo((dir_ / "fifo.bin").c_str(), 0600), 0);
    std::ifstream file(test_data("gltf/truncated_buffer.gltf"));
    std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    text.replace(text.find("truncated.bin"), std::strlen("truncated.bin"), "fifo.bin");
    EXPECT_THAT(load_error(write("fifo.gltf", text)), HasSubstr("fifo.bin"));
}

// A model placed more than a million times over (placements times placed primitives) is
// refused before any instance is made.
TEST_F(GltfHostile, TooManyInstancesAreRefused) {
    EXPECT_THAT(load_error(test_data("gltf/quad.gltf"), 1'000'001),
                HasSubstr("1000001 placement(s) of 1 placed primitive(s) exceed 1000000 instances"));
    Scene scene;
    EXPECT_NO_THROW(append_gltf(scene, test_data("gltf/quad.gltf"), std::vector<glm::mat4>(1000, glm::mat4{1.0f})));
    EXPECT_EQ(scene.instances.size(), 1000u);
}

// The quad fixture that reads its buffer from a file, with that file's uri replaced.
std::string quad_with_buffer_uri(const std::string& uri) {
    std::ifstream file(test_data("gltf/quad_external.gltf"));
    std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    text.replace(text.find("\"quad.bin\""), std::strlen("\"quad.bin\""), "\"" + uri + "\"");
    return text;
}

// Restores the current directory when it goes out of scope.
struct CurrentDirectory {
    explicit CurrentDirectory(const fs::path& dir) : saved(fs::current_path()) { fs::current_path(dir); }
    ~CurrentDirectory() { fs::current_path(saved); }
    fs::path saved;
};

// glTF uris are data: URIs or paths relative to the model (issue 17): an absolute path or a
// scheme is refused saying so, even where the file exists (tinygltf said "File not found");
// a `../` path to an unrelated file is refused without that file's size; a file missing
// beside the model is not looked for in the current directory.
TEST_F(GltfHostile, UrisSayPlainlyWhatIsRefused) {
    fs::copy_file(test_data("gltf/quad.bin"), dir_ / "quad.bin");
    const std::string absolute = (dir_ / "quad.bin").string();
    EXPECT_THAT(load_error(write("abs.gltf", quad_with_buffer_uri(absolute))),
                HasSubstr("buffers[0].uri \"" + absolute +
                          "\": an absolute path; glTF uris name files relative to the model's folder"));
    EXPECT_THAT(load_error(write("encoded.gltf", quad_with_buffer_uri("%2F" + absolute.substr(1)))),
                HasSubstr("an absolute path"));
    for (const std::string& uri : {"file://" + absolute, std::string("http://example.com/quad.bin")}) {
        EXPECT_THAT(load_error(write("scheme.gltf", quad_with_buffer_uri(uri))),
                    HasSubstr("a URI with a scheme; Penumbra reads data: URIs and files named relative to the model"));
    }
    EXPECT_THAT(load_error(write("bad.gltf", quad_with_buffer_uri("quad%zz.bin"))),
                HasSubstr("malformed percent-encoding in \"quad%zz.bin\""));
    EXPECT_THAT(load_error(write("nul.gltf", quad_with_buffer_uri("quad.bin%00.txt"))),
                HasSubstr("the path holds a control character"));

    fs::create_directories(dir_ / "model");
    write("unrelated.txt", std::string(1221, 'x'));
    const std::string escaped = load_error(write("model/up.gltf", quad_with_buffer_uri("../unrelated.txt")));
    EXPECT_THAT(escaped, HasSubstr("\"../unrelated.txt\": the file is not the buffer's byteLength (140 bytes) long"));
    EXPECT_THAT(escaped, ::testing::Not(HasSubstr("1221")));
    Scene scene;  // the right file reached through ../ is read
    EXPECT_NO_THROW(
        append_gltf(scene, write("model/good.gltf", quad_with_buffer_uri("../quad.bin")), {glm::mat4{1.0f}}));

    const CurrentDirectory in_dir(dir_);  // quad.bin is in the current directory, not beside the model
    EXPECT_THAT(load_error(write("model/cwd.gltf", quad_with_buffer_uri("quad.bin"))),
                HasSubstr("\"quad.bin\": no such file relative to the model's folder"));
}

// An image uri gets the same checks as a buffer's.
TEST_F(GltfHostile, AbsoluteImageUriIsRefused) {
    std::string text = quad_with_buffer_uri("quad.bin");
    text.replace(text.find("\"buffers\""), std::strlen("\"buffers\""),
                 "\"images\": [{\"uri\": \"/etc/hostname\"}], \"buffers\"");
    fs::copy_file(test_data("gltf/quad.bin"), dir_ / "quad.bin");
    EXPECT_THAT(load_error(write("image.gltf", text)), HasSubstr("images[0].uri \"/etc/hostname\": an absolute path"));
}

// A node translation a double holds but the float math cannot (issue 17): refused, naming
// the node, rather than placing the mesh at infinity.
TEST_F(GltfHostile, NodeTranslationBeyondTheFloatMathIsRefused) {
    EXPECT_THAT(load_error(write("far.gltf", quad_with_nodes("[{\"mesh\":0,\"translation\":[1e308,0,0]}]"))),
                HasSubstr("nodes[0]: transform holds a number that is not finite or beyond 1e9 in magnitude"));
}

// The quad fixture's text with the first `from` replaced by `to`.
std::string quad_with(const std::string& from, const std::string& to) {
    std::ifstream file(test_data("gltf/quad.gltf"));
    std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// Indices that name no element (issue 32, item 3): tinygltf reads them into an int, so 2^32
// named element 0 and a material of 2^31 read as "none". Each is refused, naming the JSON
// path, the index and how many elements there are; so is an int-sized enum beyond an int.
TEST_F(GltfHostile, IndicesThatNameNoElementAreRefused) {
    const struct {
        std::string from, to, message;
    } cases[] = {
        {"\"mesh\": 0", "\"mesh\": 4294967296",
         "nodes[0].mesh: mesh 4294967296 does not exist (the file has 1 meshes)"},
        {"\"scene\": 0", "\"scene\": 4294967296", ": scene: scene 4294967296 does not exist (the file has 1 scenes)"},
        {"[\n    0\n   ]", "[4294967296]", "scenes[0].nodes[0]: node 4294967296 does not exist (the file has 1 nodes)"},
        {"\"material\": 0", "\"material\": 2147483648",
         "meshes[0].primitives[0].material: material 2147483648 does not exist (the file has 1 materials)"},
        {"\"material\": 0", "\"material\": 4294967296",
         "meshes[0].primitives[0].material: material 4294967296 does not exist"},
        {"\"material\": 0", "\"material\": 1", "meshes[0].primitives[0].material: material 1 does not exist"},
        {"\"indices\": 3", "\"indices\": 18446744073709551615",
         "meshes[0].primitives[0].indices: accessor 18446744073709551615 does not exist (the file has 4 accessors)"},
        {"\"POSITION\": 0", "\"POSITION\": 4294967296",
         "meshes[0].primitives[0].attributes.POSITION: accessor 4294967296 does not exist"},
        {"\"buffer\": 0", "\"buffer\": 4294967296",
         "bufferViews[0].buffer: buffer 4294967296 does not exist (the file has 1 buffers)"},
        {"\"bufferView\": 0", "\"bufferView\": 4294967296",
         "accessors[0].bufferView: bufferView 4294967296 does not exist (the file has 4 buffer views)"},
        {"\"componentType\": 5126", "\"componentType\": 4294972422",
         "accessors[0].componentType: expected an integer from 0 to 2147483647, got 4294972422"},
        {"\"indices\": 3", "\"indices\": 3, \"mode\": 4294967300",
         "meshes[0].primitives[0].mode: expected an integer from 0 to 2147483647, got 4294967300"},
        {"\"roughnessFactor\"", "\"baseColorTexture\": {\"index\": 4294967296}, \"roughnessFactor\"",
         "materials[0].pbrMetallicRoughness.baseColorTexture.index: texture 4294967296 does not exist (the file has "
         "0 textures)"},
        {"\"mesh\": 0", "\"mesh\": 0, \"extensions\": {\"KHR_lights_punctual\": {\"light\": 4294967296}}",
         "nodes[0].extensions.KHR_lights_punctual.light: light 4294967296 does not exist (the file has 0 lights)"},
    };
    for (const auto& c : cases) {
        EXPECT_THAT(load_error(write("index.gltf", quad_with(c.from, c.to))), HasSubstr(c.message)) << c.to;
    }
}

// tinygltf reads a GLB of any container version as version 2.
TEST_F(GltfHostile, GlbOfAnotherVersionIsRefused) {
    std::ifstream file(test_data("gltf/quad.glb"), std::ios::binary);
    std::string glb((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    ASSERT_GT(glb.size(), 12u);
    const uint32_t version = 1;
    std::memcpy(glb.data() + 4, &version, sizeof(version));
    EXPECT_THAT(load_error(write("v1.glb", glb)), HasSubstr("GLB container version 1 (glTF 2.0 files are version 2)"));
}

// A BIN chunk that says 8 bytes more than follow its header: tinygltf measures the chunk's
// data against the container without its 8-byte header and reads past the end (found by
// fuzz_glb through a Draco file, whose JSON the loader rewrites).
TEST_F(GltfHostile, GlbChunkLongerThanTheContainerIsRefused) {
    std::ifstream file(test_data("gltf/quad.glb"), std::ios::binary);
    std::string glb((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    ASSERT_GT(glb.size(), 40u);
    glb.resize(glb.size() - 8);
    const auto length = static_cast<uint32_t>(glb.size());
    std::memcpy(glb.data() + 8, &length, sizeof(length));
    EXPECT_THAT(load_error(write("overrun.glb", glb)), HasSubstr("GLB chunk 1 says"));

    const uint32_t claimed = length + 8;
    std::memcpy(glb.data() + 8, &claimed, sizeof(claimed));
    EXPECT_THAT(load_error(write("truncated.glb", glb)),
                HasSubstr("the GLB header says " + std::to_string(length + 8) + " bytes, the file has " +
                          std::to_string(length) + " (truncated?)"));
}

}  // namespace
}  // namespace penumbra
