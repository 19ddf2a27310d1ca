#pragma once
// Pieces of the glTF loader (gltf_loader.cpp) shared by its source files. tinygltf parses
// the JSON and decodes buffers and images but does not check that accessors, buffer views
// and indices stay inside their buffers, so everything read from a model goes through the
// checked readers below: a malformed file is an InputError, never an out-of-bounds read.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <tiny_gltf.h>
#include <nlohmann/json_fwd.hpp>

#include "penumbra/scene/loader.hpp"
#include "penumbra/scene/scene.hpp"

namespace penumbra {

// The loaded model and the name used in its error messages.
struct GltfSource {
    const tinygltf::Model& model;
    std::string origin;

    // Throws InputError("<origin>: <where>: <problem>"); `where` is a JSON path such as
    // "meshes[0].primitives[1].indices".
    [[noreturn]] void fail(const std::string& where, const std::string& problem) const;
    // Whether extensionsUsed or extensionsRequired lists `name`.
    bool uses_extension(const std::string& name) const;
};

// How deep a glTF's JSON may nest arrays and objects (real files nest about ten levels;
// tinygltf's recursive conversion overflows the stack at a few thousand).
inline constexpr size_t kMaxGltfJsonDepth = 256;
// How many instances one model may add to a scene (its placements times the primitives its
// nodes place): beyond, a file is more likely an attack than a scene.
inline constexpr size_t kMaxGltfInstances = 1'000'000;

// What decoding a model's images may add to the scene: tinygltf decodes every image while
// it parses, so the budget is checked from each image's header before its pixels are.
struct GltfImageAllowance {
    uint64_t bytes = 0;       // the load budget's bytes less what the scene already holds
    uint64_t max_bytes = 0;   // the whole budget, and how to raise it, for the message
    std::string budget_name;  // LoadBudget::max_bytes_name
};

// Parses a .gltf or .glb file (gltf_file.cpp): InputError for an unknown extension, a
// missing or non-regular file, JSON nested deeper than kMaxGltfJsonDepth, an image that is
// not a PNG or JPEG or whose RGBA8 pixels would exceed `images.bytes` (all images
// together), or whatever tinygltf refuses; uris must name regular files.
tinygltf::Model read_gltf_model(const std::filesystem::path& file, const std::string& origin,
                                const GltfImageAllowance& images);

// What tinygltf 2.7 refuses but the compression extensions allow is stood in for before it
// reads the JSON, and put back after (gltf_compression.cpp):
// - EXT_meshopt_compression's placeholder buffers without a uri (the extension's "Fallback
//   buffers"; in a GLB, buffer 0 without a uri is the BIN chunk, not one): tinygltf refuses
//   a buffer without a uri, so each gets a one-byte data: uri, and is left without uri and
//   data after;
// - KHR_draco_mesh_compression's index accessors, which have no bufferView (the data is in
//   the Draco mesh): tinygltf refuses indices without one, so each names the primitive's
//   Draco bufferView, and none again after.
// json_with_stand_ins returns nullopt when the file needs none.
struct GltfStandIns {
    std::string json;
    std::vector<size_t> placeholder_buffers;
    std::vector<size_t> draco_index_accessors;
};
std::optional<GltfStandIns> json_with_stand_ins(std::string_view json, bool binary);
void remove_stand_ins(tinygltf::Model& model, const GltfStandIns& stand_ins);
inline bool is_placeholder_buffer(const tinygltf::Buffer& buffer) { return buffer.uri.empty() && buffer.data.empty(); }

// An image's size from its header, read before decoding: a PNG's IHDR or a JPEG's first
// start-of-frame marker (gltf_budget.cpp). nullopt when the bytes are neither format or the
// header is cut short.
struct ImageHeader {
    uint32_t width = 0;
    uint32_t height = 0;
};
std::optional<ImageHeader> read_image_header(std::span<const unsigned char> bytes);

// Triangles drawn and bytes held, for the load budget (LoadBudget), counted before anything
// is expanded. Sums saturate at the largest uint64_t, so a hostile count cannot wrap.
struct GltfCost {
    uint64_t triangles = 0;
    uint64_t bytes = 0;
};
// Whether every vertex of the primitive lies at the origin: its POSITION accessor has neither
// a bufferView nor sparse values (glTF 2.0, 3.6.2.3: such an accessor is all zeros) and no
// morph target moves it. Its triangles have no area, so converting it makes nothing and
// nothing is read or expanded.
bool positions_all_at_origin(const tinygltf::Model& model, const tinygltf::Primitive& primitive);
// What converting a primitive makes, from its accessors' counts alone: its triangles (a
// list's indices / 3, a strip's or fan's indices - 2, none for points and lines) and the
// bytes of its vertices and 32-bit index list. Accessors that do not exist count nothing:
// converting the primitive reports them.
GltfCost primitive_cost(const tinygltf::Model& model, const tinygltf::Primitive& primitive);
// What a scene already holds: its instances' triangles, its meshes' and textures' bytes.
GltfCost scene_cost(const Scene& scene);
uint64_t saturating_add(uint64_t a, uint64_t b);
uint64_t saturating_multiply(uint64_t a, uint64_t b);
// What decoding compressed geometry may hold: the load budget's bytes less what the scene
// and the model's decoded images already take. Each decoded buffer view or Draco primitive
// takes its share, from its declared size, before it is decoded.
struct GltfDecodeAllowance {
    uint64_t bytes = 0;
    uint64_t max_bytes = 0;
    std::string budget_name;
};
// Takes `bytes` from the allowance, or refuses (InputError at `where`) what would exceed it.
void take_decoded_bytes(const GltfSource& source, GltfDecodeAllowance& allowance, uint64_t bytes,
                        const std::string& where);

// Decodes the model's compressed geometry in place, so that the rest of the loader reads
// plain accessors (gltf_compression.cpp): EXT_meshopt_compression buffer views first
// (gltf_meshopt.cpp), then KHR_draco_mesh_compression primitives (gltf_draco.cpp), whose
// decoded attributes and indices become new FLOAT and UNSIGNED_INT accessors. A buffer
// left as a placeholder (json_with_placeholder_buffers) may only be named by views that
// were decoded. InputError naming the JSON path for anything malformed, corrupt or over
// the allowance.
void decode_compressed_geometry(tinygltf::Model& model, const std::string& origin, GltfDecodeAllowance& allowance);
void decode_meshopt_buffer_views(tinygltf::Model& model, const GltfSource& source, GltfDecodeAllowance& allowance);
void decode_draco_primitives(tinygltf::Model& model, const GltfSource& source, GltfDecodeAllowance& allowance);

// A required integer >= 0 or string property of a compression extension's object (the JSON
// checks have held its integers to 0..2^31 - 1); InputError at "<where>.<key>" otherwise.
size_t extension_integer(const GltfSource& source, const tinygltf::Value& object, const char* key,
                         const std::string& where, std::optional<size_t> fallback = std::nullopt);
std::string extension_string(const GltfSource& source, const tinygltf::Value& object, const char* key,
                             const std::string& where, std::optional<std::string> fallback = std::nullopt);

// Refuses (InputError naming the model, the counts, the limit and how to raise it) a model
// whose `added` cost takes a scene holding `held` past the budget.
void check_load_budget(const GltfSource& source, const GltfCost& held, const GltfCost& added, const LoadBudget& budget);

// The deepest nesting of arrays and objects in JSON text (strings skipped); the scan stops
// once it exceeds stop_beyond.
size_t json_nesting_depth(std::string_view text, size_t stop_beyond);

// Refuses indices, counts, offsets and strides of the wrong JSON type or sign, which
// tinygltf would skip or misread silently, and checks every buffer and image uri with
// check_gltf_uri (gltf_json_checks.cpp); JSON it cannot parse is left for tinygltf to report.
// `folder` is the model's folder, absolute.
// The values' JSON types and the specification's ranges (gltf_json_values.cpp): a node's
// transform, a material's factors and modes, a punctual light, a sampler, an accessor's
// type, a camera, the asset's version. InputError naming the JSON path.
void check_gltf_json_values(const nlohmann::json& document, const std::string& origin);
void check_gltf_json(std::string_view json, const std::string& origin, const std::filesystem::path& folder);

// A buffer's or an image's uri, where it was written ("buffers[0].uri") and, for a buffer,
// the byteLength its file must have.
struct GltfUri {
    std::string text;
    std::string where;
    std::filesystem::path folder;
    std::optional<uint64_t> byte_length;
};

// Refuses (InputError, naming the uri and the reason) a uri with a scheme other than data:,
// an absolute path, malformed percent-encoding or a control character; for a buffer, also a
// file that is missing from the model's folder, not a regular file, or not byteLength long
// (without saying the size it has: the path may reach outside the model's folder).
void check_gltf_uri(const GltfUri& uri, const std::string& origin);
bool is_data_uri(const std::string& uri);
// Percent-decodes a uri the way tinygltf does before opening the file.
std::string decode_gltf_uri(const std::string& uri, const std::string& origin, const std::string& where);

// Finite, and within what the float math downstream carries (kMaxNumberMagnitude): every
// number read from a model's JSON passes this.
inline bool within_float_math(double value) { return std::isfinite(value) && std::abs(value) <= kMaxNumberMagnitude; }

// The root nodes of the model's default scene (or every parentless node without scenes),
// after checking that the nodes form disjoint strict trees (gltf_hierarchy.cpp).
std::vector<int> checked_root_nodes(const GltfSource& source);

// How many elements an accessor without a bufferView (all zeros, or sparse over zeros) may
// have: its data is not in the file, so its count is not bounded by the file's size.
inline constexpr size_t kMaxGltfElementsWithoutData = size_t{1} << 24;

// What an accessor is read for; each accepts the component types glTF 2.0 allows for it,
// plus KHR_mesh_quantization's integer types when the file declares that extension.
enum class GltfAttribute { Position, Normal, Texcoord, PositionDelta, NormalDelta, Color };

// Reads the whole accessor (sparse substitution applied, integer components normalised
// where the accessor says so), converting to floats. Each throws unless the accessor's
// component and element types are among those allowed for the use, or a value is not
// finite or beyond kMaxNumberMagnitude.
std::vector<glm::vec3> read_vec3_accessor(const GltfSource& source, int accessor, GltfAttribute use,
                                          const std::string& where);
std::vector<glm::vec2> read_texcoord_accessor(const GltfSource& source, int accessor, const std::string& where);
// COLOR_n: VEC3 (alpha 1) or VEC4.
std::vector<glm::vec4> read_color_accessor(const GltfSource& source, int accessor, const std::string& where);
// Indices: unsigned byte, short or int scalars.
std::vector<uint32_t> read_index_accessor(const GltfSource& source, int accessor, const std::string& where);
// Number of elements of a checked accessor (throws like the readers when malformed).
size_t accessor_count(const GltfSource& source, int accessor, const std::string& where);

// How a node places a primitive.
struct GltfPrimitiveOptions {
    int uv_set = 0;                     // the TEXCOORD_n its material's base colour texture reads
    glm::mat3 uv_transform{1.0f};       // its KHR_texture_transform, applied to the UVs at load
    std::vector<double> morph_weights;  // node.weights, else mesh.weights; missing ones are 0
};

// Converts one glTF primitive to a triangle-list Mesh (material left 0 for the caller), in
// the pose of `options.morph_weights`. Returns nullopt for points and lines, which cast no
// shadow, and for primitives without triangles; strips and fans become lists.
std::optional<Mesh> convert_gltf_primitive(const GltfSource& source, const tinygltf::Primitive& primitive,
                                           const GltfPrimitiveOptions& options, const std::string& where);

// A node that places a KHR_lights_punctual light, with its model-space transform.
struct GltfPlacedLight {
    int light = -1;
    int node = -1;
    glm::mat4 transform{1.0f};
};

// The light a node places (its KHR_lights_punctual extension), checked to exist
// (gltf_lights.cpp).
std::optional<int> punctual_light_of(const GltfSource& source, const tinygltf::Node& node, int node_index);

// Appends one Light per (placed light, placement) to `lights`: glTF lights shine along the
// node's -Z; intensities (lux, candela) are taken as Penumbra's intensities; a spot or point
// light without a range gets the distance where its irradiance falls to 1/100 of its value
// at 1 m (docs/scene-format.md).
void append_gltf_lights(const GltfSource& source, const std::vector<GltfPlacedLight>& placed,
                        const std::vector<glm::mat4>& placements, std::vector<Light>& lights);

// KHR_texture_transform of a textureInfo as a matrix on (u, v, 1): translation * rotation
// * scale, the extension's order; its texCoord, when given, replaces `uv_set`
// (gltf_texture_transform.cpp).
glm::mat3 read_texture_transform(const GltfSource& source, const tinygltf::Value& extension, const std::string& where,
                                 int& uv_set);

// The emissive part of a glTF material (glTF 2.0 3.9.2, gltf_emissive.cpp): emissiveFactor
// times KHR_materials_emissive_strength's emissiveStrength, and the emissiveTexture with
// the UV set and KHR_texture_transform it is read with. InputError for factors that are
// not 3 finite numbers >= 0 or a strength that is not a finite number >= 0.
// A material's textureInfo (glTF 2.0 5.22): the texture, and the UV set and
// KHR_texture_transform it is read with.
struct GltfTextureReference {
    int texture = -1;  // glTF texture index, -1 for none
    int uv_set = 0;
    glm::mat3 uv_transform{1.0f};
    std::string where;  // the textureInfo's JSON path
};
GltfTextureReference read_texture_reference(const GltfSource& source, int texture, int tex_coord,
                                            const tinygltf::ExtensionMap& extensions, const std::string& where);

struct GltfEmissive {
    glm::vec3 factor{0.0f};
    GltfTextureReference texture;
};
GltfEmissive read_gltf_emissive(const GltfSource& source, int material);

// Converts decoded image `index` (1 to 4 channels, 8 or 16 bits) to RGBA8; throws when the
// image holds no pixels (it failed to load) or its size does not match its header.
Texture convert_gltf_image(const GltfSource& source, const tinygltf::Image& image, int index);

// What refers to image `image`: "baseColorTexture of materials[0], normalTexture of
// materials[2]" (the material slots of glTF 2.0), or "no material texture".
std::string gltf_image_uses(const tinygltf::Model& model, int image);
// `images[3] "helmet_normal.png"` (the uri, else the name, when there is one).
std::string gltf_image_name(const tinygltf::Model& model, int image);
// One warning per image that did not load and that loading the model did not need (those it
// needs stop the load in convert_gltf_image).
void warn_unloaded_images(const GltfSource& source, std::vector<std::string>& warnings);

}  // namespace penumbra
