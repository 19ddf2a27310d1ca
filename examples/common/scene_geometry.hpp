#pragma once
// The examples' fixed scene, in the application's own buffers: a 2 m box (centred on its
// origin, placed at kBoxCentre) and a 40 x 40 m plane at y = 0 facing +Y, as interleaved
// positions and normals with 16-bit indices; the camera and the sun; and the little
// rendering both examples share (a pipeline over those vertices, the start of a pass, a
// copy of a target into a buffer).
#include <penumbra/penumbra.hpp>

#include <array>
#include <vector>

#include "example_vulkan.hpp"

namespace example {

inline constexpr penumbra::Vec3 kBoxCentre{0.0f, 3.0f, 0.0f};
inline constexpr float kBoxHalfSize = 1.0f;
inline constexpr float kPlaneHalfSize = 20.0f;
inline constexpr penumbra::Vec3 kSunDirection{-0.4f, -1.0f, -0.3f};  // the direction the light travels

// Eye (0, 6, 12), target the origin, up +Y, 60 degrees vertically, near 0.1, far 200.
penumbra::ViewDesc camera_view(uint32_t width, uint32_t height);

penumbra::Mat4 translation(const penumbra::Vec3& offset);
penumbra::Mat4 multiply(const penumbra::Mat4& a, const penumbra::Mat4& b);

enum class SceneMesh { Box, Plane };

struct Vertex {
    penumbra::Vec3 position;
    penumbra::Vec3 normal;
};

class SceneBuffers {
public:
    explicit SceneBuffers(const Device& device);

    // The meshes as Penumbra takes them: ranges of these buffers.
    penumbra::MeshDesc box_mesh() const { return mesh(SceneMesh::Box); }
    penumbra::MeshDesc plane_mesh() const { return mesh(SceneMesh::Plane); }
    // The same geometry as arrays, for Penumbra to upload itself.
    const std::vector<Vertex>& vertices() const { return vertices_; }
    std::vector<penumbra::Vec3> positions(SceneMesh mesh) const;
    std::vector<uint32_t> indices(SceneMesh mesh) const;

    // Binds the buffers and draws one mesh (positions at location 0, normals at 1).
    void draw(VkCommandBuffer cmd, SceneMesh mesh) const;

private:
    struct Range {
        uint32_t first_index;
        uint32_t index_count;
        int32_t vertex_offset;
        uint32_t vertex_count;
    };
    struct Geometry {
        std::vector<Vertex> vertices;
        std::vector<uint16_t> indices;
        std::array<Range, 2> ranges{};
    };
    static Geometry build_geometry();
    SceneBuffers(const Device& device, Geometry geometry);
    penumbra::MeshDesc mesh(SceneMesh mesh) const;
    const Range& range(SceneMesh mesh) const { return ranges_[mesh == SceneMesh::Box ? 0 : 1]; }

    std::vector<Vertex> vertices_;
    std::vector<uint16_t> indices_;
    std::array<Range, 2> ranges_{};
    Buffer vertex_buffer_;
    Buffer index_buffer_;
};

// A pipeline over SceneBuffers' vertices with dynamic rendering: `color_format` (or
// VK_FORMAT_UNDEFINED for depth only) and a D32 depth test with `depth_compare`. With a
// vertex stage alone (stage_count 1) the pipeline reads positions only (location 0).
VkPipeline create_scene_pipeline(const Device& device, VkPipelineLayout layout,
                                 const std::array<VkPipelineShaderStageCreateInfo, 2>& stages, VkFormat color_format,
                                 VkCompareOp depth_compare, uint32_t stage_count = 2);

// Moves `color` (may be null) and `depth` into attachment layouts and begins rendering with
// the clear values given, viewport and scissor over width x height.
void begin_scene_pass(VkCommandBuffer cmd, const Image* color, const Image& depth, uint32_t width, uint32_t height,
                      float clear_color, float clear_depth);

// Copies a colour attachment (in COLOR_ATTACHMENT_OPTIMAL after its writes) into a host buffer.
void copy_to_buffer(VkCommandBuffer cmd, const Image& image, uint32_t width, uint32_t height, const Buffer& buffer);

}  // namespace example
