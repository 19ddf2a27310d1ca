#include "scene_geometry.hpp"

#include <cstddef>

namespace example {
namespace {

void add_quad(std::vector<Vertex>& vertices, std::vector<uint16_t>& indices,
              const std::array<penumbra::Vec3, 4>& corners, const penumbra::Vec3& normal) {
    const auto base = static_cast<uint16_t>(vertices.size());
    for (const penumbra::Vec3& corner : corners) vertices.push_back({corner, normal});
    // Counter-clockwise seen from the side the normal points to.
    for (const uint16_t i : {0, 1, 2, 0, 2, 3}) indices.push_back(static_cast<uint16_t>(base + i));
}

}  // namespace

penumbra::ViewDesc camera_view(uint32_t width, uint32_t height) {
    return penumbra::look_at_view({0.0f, 6.0f, 12.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                  60.0f * 3.14159265358979f / 180.0f, 0.1f, 200.0f, width, height);
}

penumbra::Mat4 translation(const penumbra::Vec3& offset) {
    penumbra::Mat4 m;
    m(0, 3) = offset.x;
    m(1, 3) = offset.y;
    m(2, 3) = offset.z;
    return m;
}

penumbra::Mat4 multiply(const penumbra::Mat4& a, const penumbra::Mat4& b) {
    penumbra::Mat4 result;
    for (int row = 0; row < 4; ++row) {
        for (int column = 0; column < 4; ++column) {
            float sum = 0.0f;
            for (int k = 0; k < 4; ++k) sum += a(row, k) * b(k, column);
            result(row, column) = sum;
        }
    }
    return result;
}

SceneBuffers::Geometry SceneBuffers::build_geometry() {
    Geometry g;
    const float h = kBoxHalfSize;
    using V = penumbra::Vec3;
    // The box's six faces, each with its outward normal.
    add_quad(g.vertices, g.indices, {V{h, -h, h}, V{h, -h, -h}, V{h, h, -h}, V{h, h, h}}, {1, 0, 0});
    add_quad(g.vertices, g.indices, {V{-h, -h, -h}, V{-h, -h, h}, V{-h, h, h}, V{-h, h, -h}}, {-1, 0, 0});
    add_quad(g.vertices, g.indices, {V{-h, h, h}, V{h, h, h}, V{h, h, -h}, V{-h, h, -h}}, {0, 1, 0});
    add_quad(g.vertices, g.indices, {V{-h, -h, -h}, V{h, -h, -h}, V{h, -h, h}, V{-h, -h, h}}, {0, -1, 0});
    add_quad(g.vertices, g.indices, {V{-h, -h, h}, V{h, -h, h}, V{h, h, h}, V{-h, h, h}}, {0, 0, 1});
    add_quad(g.vertices, g.indices, {V{h, -h, -h}, V{-h, -h, -h}, V{-h, h, -h}, V{h, h, -h}}, {0, 0, -1});
    g.ranges[0] = {0, static_cast<uint32_t>(g.indices.size()), 0, static_cast<uint32_t>(g.vertices.size())};
    // The plane's indices start at its own first vertex (vkCmdDrawIndexed's vertexOffset does the rest).
    const float p = kPlaneHalfSize;
    std::vector<Vertex> plane_vertices;
    std::vector<uint16_t> plane_indices;
    add_quad(plane_vertices, plane_indices, {V{-p, 0, p}, V{p, 0, p}, V{p, 0, -p}, V{-p, 0, -p}}, {0, 1, 0});
    g.ranges[1] = {static_cast<uint32_t>(g.indices.size()), static_cast<uint32_t>(plane_indices.size()),
                   static_cast<int32_t>(g.vertices.size()), static_cast<uint32_t>(plane_vertices.size())};
    g.vertices.insert(g.vertices.end(), plane_vertices.begin(), plane_vertices.end());
    g.indices.insert(g.indices.end(), plane_indices.begin(), plane_indices.end());
    return g;
}

SceneBuffers::SceneBuffers(const Device& device) : SceneBuffers(device, build_geometry()) {}

SceneBuffers::SceneBuffers(const Device& device, Geometry geometry)
    : vertices_(std::move(geometry.vertices)),
      indices_(std::move(geometry.indices)),
      ranges_(geometry.ranges),
      vertex_buffer_(device, vertices_.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, vertices_.data()),
      index_buffer_(device, indices_.size() * sizeof(uint16_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, indices_.data()) {}

penumbra::MeshDesc SceneBuffers::mesh(SceneMesh which) const {
    const Range& r = range(which);
    penumbra::MeshDesc desc;
    desc.positions = {vertex_buffer_.buffer, offsetof(Vertex, position), sizeof(Vertex), VK_FORMAT_R32G32B32_SFLOAT};
    desc.index_buffer = index_buffer_.buffer;
    desc.index_offset = VkDeviceSize{r.first_index} * sizeof(uint16_t);
    desc.index_type = VK_INDEX_TYPE_UINT16;
    desc.index_count = r.index_count;
    desc.vertex_offset = r.vertex_offset;
    const float h = which == SceneMesh::Box ? kBoxHalfSize : kPlaneHalfSize;
    desc.bounds = which == SceneMesh::Box ? penumbra::Bounds{{-h, -h, -h}, {h, h, h}}
                                          : penumbra::Bounds{{-h, 0.0f, -h}, {h, 0.0f, h}};
    return desc;
}

std::vector<penumbra::Vec3> SceneBuffers::positions(SceneMesh which) const {
    const Range& r = range(which);
    std::vector<penumbra::Vec3> result;
    for (uint32_t v = 0; v < r.vertex_count; ++v) result.push_back(vertices_[r.vertex_offset + v].position);
    return result;
}

std::vector<uint32_t> SceneBuffers::indices(SceneMesh which) const {
    const Range& r = range(which);
    return {indices_.begin() + r.first_index, indices_.begin() + r.first_index + r.index_count};
}

void SceneBuffers::draw(VkCommandBuffer cmd, SceneMesh which) const {
    const Range& r = range(which);
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer_.buffer, &offset);
    vkCmdBindIndexBuffer(cmd, index_buffer_.buffer, 0, VK_INDEX_TYPE_UINT16);
    vkCmdDrawIndexed(cmd, r.index_count, 1, r.first_index, r.vertex_offset, 0);
}

VkPipeline create_scene_pipeline(const Device& device, VkPipelineLayout layout,
                                 const std::array<VkPipelineShaderStageCreateInfo, 2>& stages, VkFormat color_format,
                                 VkCompareOp depth_compare, uint32_t stage_count) {
    const VkVertexInputBindingDescription binding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    const std::array<VkVertexInputAttributeDescription, 2> attributes{{
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, static_cast<uint32_t>(offsetof(Vertex, position))},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, static_cast<uint32_t>(offsetof(Vertex, normal))},
    }};
    VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertex_input.vertexBindingDescriptionCount = 1;
    vertex_input.pVertexBindingDescriptions = &binding;
    // A depth-only pipeline (a vertex stage alone) reads positions only.
    vertex_input.vertexAttributeDescriptionCount = stage_count == 1 ? 1u : static_cast<uint32_t>(attributes.size());
    vertex_input.pVertexAttributeDescriptions = attributes.data();
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = VK_TRUE;
    depth.depthWriteEnable = VK_TRUE;
    depth.depthCompareOp = depth_compare;
    VkPipelineColorBlendAttachmentState blend_attachment{};
    blend_attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT;
    VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    const bool has_color = color_format != VK_FORMAT_UNDEFINED;
    blend.attachmentCount = has_color ? 1 : 0;
    blend.pAttachments = &blend_attachment;
    const std::array<VkDynamicState, 2> dynamic_states{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = static_cast<uint32_t>(dynamic_states.size());
    dynamic.pDynamicStates = dynamic_states.data();
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = has_color ? 1 : 0;
    rendering.pColorAttachmentFormats = &color_format;
    rendering.depthAttachmentFormat = VK_FORMAT_D32_SFLOAT;
    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    info.stageCount = stage_count;
    info.pStages = stages.data();
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    EXAMPLE_CHECK(vkCreateGraphicsPipelines(device.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    return pipeline;
}

void begin_scene_pass(VkCommandBuffer cmd, const Image* color, const Image& depth, uint32_t width, uint32_t height,
                      float clear_color, float clear_depth) {
    VkRenderingAttachmentInfo color_attachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    if (color) {
        barrier(cmd, color->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
        color_attachment.imageView = color->view;
        color_attachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        color_attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        color_attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        color_attachment.clearValue.color = {{clear_color, 0.0f, 0.0f, 0.0f}};
    }
    barrier(cmd, depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
            VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
            VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
            VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    VkRenderingAttachmentInfo depth_attachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth_attachment.imageView = depth.view;
    depth_attachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth_attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth_attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth_attachment.clearValue.depthStencil = {clear_depth, 0};
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {width, height}};
    info.layerCount = 1;
    info.colorAttachmentCount = color ? 1 : 0;
    info.pColorAttachments = &color_attachment;
    info.pDepthAttachment = &depth_attachment;
    vkCmdBeginRendering(cmd, &info);
    const VkViewport viewport{0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {width, height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void copy_to_buffer(VkCommandBuffer cmd, const Image& image, uint32_t width, uint32_t height, const Buffer& buffer) {
    barrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
            VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
            VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width, height, 1};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.buffer, 1, &region);
    host_read_barrier(cmd);
}

}  // namespace example
