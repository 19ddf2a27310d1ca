#pragma once
// Small GLB models with compressed geometry, made by the tests from the repository's own
// sphere (make_sphere): its positions, octahedral normals and indices compressed with
// meshoptimizer's encoders (EXT_meshopt_compression, the placeholder buffer without a uri
// that the extension's "Fallback buffers" describe), or with Draco's encoder
// (KHR_draco_mesh_compression, positions quantized to 14 bits). The fuzz corpus's seeds
// tests/fuzz/corpus/glb/seed_*_sphere.glb are these files.
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>

#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "penumbra/scene/primitives.hpp"

namespace penumbra::testing {

// A GLB of `json` and one BIN chunk (glTF 2.0, 4.4), each padded to 4 bytes.
inline std::string glb_file(const nlohmann::json& json, std::string bin) {
    std::string text = json.dump();
    text.resize((text.size() + 3) / 4 * 4, ' ');
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    std::string glb;
    const auto word = [&](uint32_t value) { glb.append(reinterpret_cast<const char*>(&value), 4); };
    glb.append("glTF");
    word(2);
    word(static_cast<uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
    word(static_cast<uint32_t>(text.size()));
    word(0x4E4F534Au);  // JSON
    glb += text;
    word(static_cast<uint32_t>(bin.size()));
    word(0x004E4942u);  // BIN
    glb += bin;
    return glb;
}

// The sphere every compressed test model holds.
inline Mesh compressed_test_sphere() { return make_sphere(1.0f, 16, 8); }

// The JSON every test model shares: one node placing mesh 0, whose primitive has
// accessors 0 (POSITION), 1 (NORMAL) and 2 (indices).
inline nlohmann::json sphere_document(const Mesh& sphere) {
    nlohmann::json document;
    document["asset"] = {{"version", "2.0"}};
    document["scene"] = 0;
    document["scenes"] = {{{"nodes", {0}}}};
    document["nodes"] = {{{"mesh", 0}}};
    const Aabb& bounds = sphere.bounds;
    document["accessors"] = {
        {{"componentType", 5126},
         {"count", sphere.vertices.size()},
         {"type", "VEC3"},
         {"min", {bounds.min.x, bounds.min.y, bounds.min.z}},
         {"max", {bounds.max.x, bounds.max.y, bounds.max.z}}},
        {{"componentType", 5120}, {"normalized", true}, {"count", sphere.vertices.size()}, {"type", "VEC3"}},
        {{"componentType", 5125}, {"count", sphere.indices.size()}, {"type", "SCALAR"}}};
    return document;
}

// EXT_meshopt_compression: positions without a filter (12-byte elements), normals with the
// OCTAHEDRAL filter (4 bytes: 8-bit x, y, z and a zero), indices in TRIANGLES mode. Every
// compressed view is in the GLB's BIN chunk (buffer 0); the views themselves name buffer 1,
// a placeholder without a uri. `cut_position_bytes` shortens the compressed positions'
// byteLength, as a truncated file would.
inline std::string meshopt_sphere_glb(size_t cut_position_bytes = 0) {
    const Mesh sphere = compressed_test_sphere();
    const size_t count = sphere.vertices.size();
    std::vector<float> positions;
    std::vector<float> normals;  // 4 floats per vector, as meshopt_encodeFilterOct reads them
    for (const Vertex& vertex : sphere.vertices) {
        positions.insert(positions.end(), {vertex.position.x, vertex.position.y, vertex.position.z});
        normals.insert(normals.end(), {vertex.normal.x, vertex.normal.y, vertex.normal.z, 0.0f});
    }
    std::vector<int8_t> octahedral(count * 4);
    meshopt_encodeFilterOct(octahedral.data(), count, 4, 8, normals.data());

    std::string bin;
    nlohmann::json views = nlohmann::json::array();
    size_t fallback_offset = 0;
    const auto add_view = [&](const std::vector<unsigned char>& encoded, size_t stride, size_t elements,
                              const char* mode, const char* filter) {
        nlohmann::json compressed = {{"buffer", 0},          {"byteOffset", bin.size()}, {"byteLength", encoded.size()},
                                     {"byteStride", stride}, {"count", elements},        {"mode", mode}};
        if (filter != nullptr) compressed["filter"] = filter;
        nlohmann::json view = {{"buffer", 1},
                               {"byteOffset", fallback_offset},
                               {"byteLength", stride * elements},
                               {"extensions", {{"EXT_meshopt_compression", compressed}}}};
        if (std::string(mode) == "ATTRIBUTES") view["byteStride"] = stride;
        views.push_back(view);
        bin.append(reinterpret_cast<const char*>(encoded.data()), encoded.size());
        bin.resize((bin.size() + 3) / 4 * 4, '\0');
        fallback_offset += stride * elements;
    };
    const auto encode_vertices = [](const void* data, size_t elements, size_t stride) {
        std::vector<unsigned char> encoded(meshopt_encodeVertexBufferBound(elements, stride));
        encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), data, elements, stride));
        return encoded;
    };
    add_view(encode_vertices(positions.data(), count, 12), 12, count, "ATTRIBUTES", nullptr);
    add_view(encode_vertices(octahedral.data(), count, 4), 4, count, "ATTRIBUTES", "OCTAHEDRAL");
    std::vector<unsigned char> indices(meshopt_encodeIndexBufferBound(sphere.indices.size(), count));
    indices.resize(
        meshopt_encodeIndexBuffer(indices.data(), indices.size(), sphere.indices.data(), sphere.indices.size()));
    add_view(indices, 4, sphere.indices.size(), "TRIANGLES", nullptr);
    views[0]["extensions"]["EXT_meshopt_compression"]["byteLength"] =
        views[0]["extensions"]["EXT_meshopt_compression"]["byteLength"].get<size_t>() - cut_position_bytes;

    nlohmann::json document = sphere_document(sphere);
    for (int i = 0; i < 3; ++i) document["accessors"][i]["bufferView"] = i;
    document["bufferViews"] = views;
    document["buffers"] = {
        {{"byteLength", (bin.size() + 3) / 4 * 4}},
        {{"byteLength", fallback_offset}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
    document["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}}}}}};
    document["extensionsUsed"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    document["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    return glb_file(document, bin);
}

// KHR_draco_mesh_compression: the sphere's positions (and normals) as one Draco mesh. The
// accessors' counts are the decoded mesh's (Draco may merge or reorder points), read back
// with Draco's decoder. `damage` overwrites the compressed bytes from its offset, and
// declares `missing_indices` fewer indices than the mesh has.
struct DracoDamage {
    size_t offset = 0;
    std::string bytes;
    size_t missing_indices = 0;
};
inline std::string draco_sphere_glb(const DracoDamage& damage = {}) {
    const Mesh sphere = compressed_test_sphere();
    const int faces = static_cast<int>(sphere.indices.size() / 3);
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(faces);
    const int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int normal = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    for (int face = 0; face < faces; ++face) {
        const auto corner = [&](int c) -> const Vertex& {
            return sphere.vertices[sphere.indices[size_t(face) * 3 + size_t(c)]];
        };
        builder.SetAttributeValuesForFace(position, draco::FaceIndex(face), &corner(0).position, &corner(1).position,
                                          &corner(2).position);
        builder.SetAttributeValuesForFace(normal, draco::FaceIndex(face), &corner(0).normal, &corner(1).normal,
                                          &corner(2).normal);
    }
    const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    draco::EncoderBuffer encoded;
    if (!encoder.EncodeMeshToBuffer(*mesh, &encoded).ok()) return {};
    draco::DecoderBuffer readback;
    readback.Init(encoded.data(), encoded.size());
    draco::Decoder decoder;
    const std::unique_ptr<draco::Mesh> decoded = decoder.DecodeMeshFromBuffer(&readback).value();

    std::string bin(encoded.data(), encoded.size());
    bin.replace(damage.offset, damage.bytes.size(), damage.bytes);
    nlohmann::json document = sphere_document(sphere);
    document["accessors"][0]["count"] = decoded->num_points();
    document["accessors"][1]["count"] = decoded->num_points();
    document["accessors"][1]["componentType"] = 5126;
    document["accessors"][1].erase("normalized");
    document["accessors"][2]["count"] = decoded->num_faces() * 3 - damage.missing_indices;
    document["bufferViews"] = {{{"buffer", 0}, {"byteLength", bin.size()}}};
    document["buffers"] = {{{"byteLength", (bin.size() + 3) / 4 * 4}}};
    const nlohmann::json draco_attributes = {{"POSITION", mesh->attribute(position)->unique_id()},
                                             {"NORMAL", mesh->attribute(normal)->unique_id()}};
    document["meshes"] = {
        {{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}},
            {"indices", 2},
            {"extensions",
             {{"KHR_draco_mesh_compression", {{"bufferView", 0}, {"attributes", draco_attributes}}}}}}}}}};
    document["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    document["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    return glb_file(document, bin);
}

}  // namespace penumbra::testing
