#include <glm/geometric.hpp>
#include <numeric>

#include "scene/gltf_internal.hpp"
#include "scene/mesh_tools.hpp"

namespace penumbra {
namespace {

// glTF's "mode" -1 means the property was absent: the default is TRIANGLES.
bool is_point_or_line_mode(int mode) {
    return mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
           mode == TINYGLTF_MODE_LINE_STRIP;
}

// Strip and fan vertex orders from the glTF 2.0 specification (section 3.7.2.1), which keep
// every triangle's winding consistent with the first one.
std::vector<uint32_t> strip_to_list(const std::vector<uint32_t>& strip) {
    std::vector<uint32_t> list;
    for (size_t i = 0; i + 2 < strip.size(); ++i) {
        const bool odd = i % 2 == 1;
        list.insert(list.end(), {strip[i], strip[i + (odd ? 2 : 1)], strip[i + (odd ? 1 : 2)]});
    }
    return list;
}

std::vector<uint32_t> fan_to_list(const std::vector<uint32_t>& fan) {
    std::vector<uint32_t> list;
    for (size_t i = 0; i + 2 < fan.size(); ++i) list.insert(list.end(), {fan[i + 1], fan[i + 2], fan[0]});
    return list;
}

int find_attribute(const tinygltf::Primitive& primitive, const std::string& name) {
    const auto found = primitive.attributes.find(name);
    return found == primitive.attributes.end() ? -1 : found->second;
}

// The primitive's vertex indices as a triangle list; non-indexed primitives use 0..n-1.
std::vector<uint32_t> read_triangle_list(const GltfSource& source, const tinygltf::Primitive& primitive,
                                         size_t vertex_count, const std::string& where) {
    std::vector<uint32_t> indices;
    if (primitive.indices >= 0) {
        indices = read_index_accessor(source, primitive.indices, where + ".indices");
        for (size_t i = 0; i < indices.size(); ++i) {
            if (indices[i] >= vertex_count) {
                source.fail(where + ".indices", "index " + std::to_string(indices[i]) + " at position " +
                                                    std::to_string(i) + " is out of range (the primitive has " +
                                                    std::to_string(vertex_count) + " vertices)");
            }
        }
    } else {
        indices.resize(vertex_count);
        std::iota(indices.begin(), indices.end(), 0u);
    }
    if (primitive.mode == TINYGLTF_MODE_TRIANGLE_STRIP) return strip_to_list(indices);
    if (primitive.mode == TINYGLTF_MODE_TRIANGLE_FAN) return fan_to_list(indices);
    if (indices.size() % 3 != 0) {
        source.fail(where, std::to_string(indices.size()) + " vertex indices do not form whole triangles");
    }
    return indices;
}

void require_same_count(const GltfSource& source, size_t count, size_t vertex_count, const std::string& where) {
    if (count != vertex_count) {
        source.fail(where, std::to_string(count) + " elements, but POSITION has " + std::to_string(vertex_count));
    }
}

}  // namespace

namespace {

// glTF 2.0, 3.7.2.2: the static pose is the base plus each target's deltas times its weight.
void apply_morph_targets(const GltfSource& source, const tinygltf::Primitive& primitive,
                         const std::vector<double>& weights, std::vector<glm::vec3>& positions,
                         std::optional<std::vector<glm::vec3>>& normals, const std::string& where) {
    for (size_t t = 0; t < primitive.targets.size() && t < weights.size(); ++t) {
        const auto weight = static_cast<float>(weights[t]);
        if (weight == 0.0f) continue;
        const std::string target = where + ".targets[" + std::to_string(t) + "]";
        for (const auto& [name, accessor] : primitive.targets[t]) {
            const bool is_position = name == "POSITION";
            if (!is_position && (name != "NORMAL" || !normals)) continue;  // tangents and the rest shape no shadow
            std::vector<glm::vec3>& base = is_position ? positions : *normals;
            const std::vector<glm::vec3> deltas = read_vec3_accessor(
                source, accessor, is_position ? GltfAttribute::PositionDelta : GltfAttribute::NormalDelta,
                target + "." + name);
            require_same_count(source, deltas.size(), base.size(), target + "." + name);
            for (size_t i = 0; i < base.size(); ++i) base[i] += weight * deltas[i];
        }
    }
    if (normals) {
        for (glm::vec3& normal : *normals) {
            const float length = glm::length(normal);
            if (length > 0.0f) normal /= length;
        }
    }
}

}  // namespace

std::optional<Mesh> convert_gltf_primitive(const GltfSource& source, const tinygltf::Primitive& primitive,
                                           const GltfPrimitiveOptions& options, const std::string& where) {
    if (is_point_or_line_mode(primitive.mode)) return std::nullopt;
    const bool triangles = primitive.mode == -1 || primitive.mode == TINYGLTF_MODE_TRIANGLES ||
                           primitive.mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
                           primitive.mode == TINYGLTF_MODE_TRIANGLE_FAN;
    if (!triangles) source.fail(where + ".mode", "unknown primitive mode " + std::to_string(primitive.mode));

    const int position_accessor = find_attribute(primitive, "POSITION");
    if (position_accessor < 0) source.fail(where + ".attributes", "no POSITION attribute");
    // Checked before reading: such an accessor's count is not bounded by the file's size.
    if (positions_all_at_origin(source.model, primitive)) return std::nullopt;
    std::vector<glm::vec3> positions =
        read_vec3_accessor(source, position_accessor, GltfAttribute::Position, where + ".attributes.POSITION");
    std::optional<std::vector<glm::vec3>> normals;
    if (const int normal_accessor = find_attribute(primitive, "NORMAL"); normal_accessor >= 0) {
        normals = read_vec3_accessor(source, normal_accessor, GltfAttribute::Normal, where + ".attributes.NORMAL");
        require_same_count(source, normals->size(), positions.size(), where + ".attributes.NORMAL");
    }
    apply_morph_targets(source, primitive, options.morph_weights, positions, normals, where);

    Mesh mesh;
    mesh.indices = read_triangle_list(source, primitive, positions.size(), where);
    const std::optional<std::vector<uint32_t>> kept = drop_degenerate_triangles(positions, mesh.indices);
    if (mesh.indices.empty()) return std::nullopt;  // nothing to draw; spare the renderer empty buffers
    // The accessor element each vertex of the mesh comes from.
    const auto element = [&](size_t vertex) { return kept ? size_t{(*kept)[vertex]} : vertex; };
    mesh.vertices.resize(kept ? kept->size() : positions.size());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) mesh.vertices[i].position = positions[element(i)];

    if (normals) {
        for (size_t i = 0; i < mesh.vertices.size(); ++i) mesh.vertices[i].normal = (*normals)[element(i)];
    } else {
        // glTF says flat normals when NORMAL is absent; smooth ones look better on the
        // organic models we load and make no difference to shadows.
        compute_smooth_normals(mesh.vertices, mesh.indices);
    }
    // The one set of texture coordinates Penumbra keeps is the one the material's base
    // colour (alpha) texture reads: textureInfo.texCoord.
    const std::string uv_name = "TEXCOORD_" + std::to_string(options.uv_set);
    if (const int uv_accessor = find_attribute(primitive, uv_name); uv_accessor >= 0) {
        const std::vector<glm::vec2> uvs =
            read_texcoord_accessor(source, uv_accessor, where + ".attributes." + uv_name);
        require_same_count(source, uvs.size(), positions.size(), where + ".attributes." + uv_name);
        for (size_t i = 0; i < mesh.vertices.size(); ++i) {
            mesh.vertices[i].uv = glm::vec2{options.uv_transform * glm::vec3{uvs[element(i)], 1.0f}};
        }
    } else if (options.uv_set != 0) {
        source.fail(where + ".attributes",
                    "the material's base colour texture reads " + uv_name + ", which the primitive does not have");
    }
    if (const int color_accessor = find_attribute(primitive, "COLOR_0"); color_accessor >= 0) {
        const std::vector<glm::vec4> colors =
            read_color_accessor(source, color_accessor, where + ".attributes.COLOR_0");
        require_same_count(source, colors.size(), positions.size(), where + ".attributes.COLOR_0");
        for (size_t i = 0; i < mesh.vertices.size(); ++i) {
            const glm::vec3 rgb = glm::clamp(glm::vec3{colors[element(i)]}, 0.0f, 1.0f);
            mesh.vertices[i].color = glm::u8vec4{glm::round(rgb * 255.0f), 255};
        }
    }
    mesh.bounds = compute_mesh_bounds(mesh.vertices);
    return mesh;
}

Texture convert_gltf_image(const GltfSource& source, const tinygltf::Image& image, int index) {
    const bool sane_header = image.width > 0 && image.height > 0 && image.component >= 1 && image.component <= 4 &&
                             (image.bits == 8 || image.bits == 16);
    const size_t texel_count = sane_header ? static_cast<size_t>(image.width) * static_cast<size_t>(image.height) : 0;
    const size_t bytes_per_channel = image.bits == 16 ? 2 : 1;
    const size_t channels = sane_header ? static_cast<size_t>(image.component) : 0;
    if (!sane_header || image.image.size() != texel_count * channels * bytes_per_channel) {
        source.fail(gltf_image_name(source.model, index),
                    "could not be read or decoded (missing file or unsupported format); Penumbra reads it (" +
                        gltf_image_uses(source.model, index) + ")");
    }
    Texture texture;
    texture.width = static_cast<uint32_t>(image.width);
    texture.height = static_cast<uint32_t>(image.height);
    texture.rgba8.resize(texel_count * 4);
    for (size_t texel = 0; texel < texel_count; ++texel) {
        // 16-bit channels are little-endian; their high byte is the 8-bit value.
        auto channel = [&](size_t c) {
            return image.image[(texel * channels + c) * bytes_per_channel + bytes_per_channel - 1];
        };
        uint8_t* out = &texture.rgba8[texel * 4];
        const bool grey = channels <= 2;
        out[0] = channel(0);
        out[1] = grey ? channel(0) : channel(1);
        out[2] = grey ? channel(0) : channel(2);
        out[3] = channels == 2 ? channel(1) : channels == 4 ? channel(3) : uint8_t{255};
    }
    return texture;
}

}  // namespace penumbra
