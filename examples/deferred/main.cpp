// Penumbra's deferred example: a screen-space shadow buffer from the application's depth.
//
// The application renders only depth (its own depth pass, forward Z: 0 near, 1 far) and
// asks Penumbra for the visibility of the sun at every pixel (ShadowSystem::
// record_visibility, a compute pass that reconstructs positions from the depth and the
// application's view-projection). Here Penumbra uploads the geometry itself: the meshes
// are given as CPU arrays. Between two frames the box moves (set_instance_transform) and
// both frames are written, so the shadow can be seen following it.
//
// Same scene as the minimal example; the second frame has the box at (3, 3, -2).
//
//   penumbra_deferred first.png second.png [--validate]
#include <penumbra/penumbra.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "example_vulkan.hpp"
#include "scene_geometry.hpp"

namespace {

constexpr uint32_t kWidth = 640;
constexpr uint32_t kHeight = 360;
constexpr penumbra::Vec3 kMovedBoxCentre{3.0f, 3.0f, -2.0f};

const uint32_t kDepthShader[] =
#include "depth.vert.inc"
    ;

// A forward-Z perspective into Vulkan clip space (depth 0 at the near plane, 1 at the far
// plane, Y flipped so that row 0 is the top): deliberately not Penumbra's reverse-Z, to
// show that record_visibility takes whatever projection the depth was rendered with.
penumbra::Mat4 forward_z_projection(const penumbra::ViewDesc& view) {
    const float focal = 1.0f / std::tan(view.fov_y_radians * 0.5f);
    const float aspect = static_cast<float>(view.width) / static_cast<float>(view.height);
    const float n = view.near_plane;
    const float f = view.far_plane;
    penumbra::Mat4 m;
    m(0, 0) = focal / aspect;
    m(1, 1) = -focal;
    m(2, 2) = f / (n - f);
    m(2, 3) = n * f / (n - f);
    m(3, 2) = -1.0f;
    m(3, 3) = 0.0f;
    return m;
}

struct PushConstants {
    penumbra::Mat4 view_projection;
    penumbra::Mat4 model;
};

// The application's depth-only pass over its own buffers.
struct DepthPipeline {
    VkDevice device = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;

    explicit DepthPipeline(const example::Device& owner) : device(owner.device) {
        const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(PushConstants)};
        VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        layout_info.pushConstantRangeCount = 1;
        layout_info.pPushConstantRanges = &push;
        EXAMPLE_CHECK(vkCreatePipelineLayout(device, &layout_info, nullptr, &layout));
        const VkShaderModule vertex = example::shader_module(owner, kDepthShader, sizeof(kDepthShader));
        std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
        stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
        stages[0].module = vertex;
        stages[0].pName = "main";
        pipeline = example::create_scene_pipeline(owner, layout, stages, VK_FORMAT_UNDEFINED, VK_COMPARE_OP_LESS, 1);
        vkDestroyShaderModule(device, vertex, nullptr);
    }
    ~DepthPipeline() {
        vkDestroyPipeline(device, pipeline, nullptr);
        vkDestroyPipelineLayout(device, layout, nullptr);
    }
};

// Penumbra's visibility image is in SHADER_READ_ONLY_OPTIMAL after record_visibility, its
// writes visible to shader reads. To copy it the application moves it to TRANSFER_SRC after
// the compute writes, and back afterwards (ShadowSystem's contract for its images).
void copy_visibility(VkCommandBuffer cmd, const penumbra::VisibilityImage& visibility, const example::Buffer& buffer) {
    example::barrier(cmd, visibility.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};  // layer 0: slots 0-3, the sun in red
    region.imageExtent = {visibility.width, visibility.height, 1};
    vkCmdCopyImageToBuffer(cmd, visibility.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.buffer, 1, &region);
    example::barrier(cmd, visibility.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_NONE);
    example::host_read_barrier(cmd);
}

class DeferredFrame {
public:
    explicit DeferredFrame(const example::Device& device)
        : device_(device),
          scene_(device),
          shadows_(shadow_system_desc(device)),
          pipeline_(device),
          depth_(device, VK_FORMAT_D32_SFLOAT, kWidth, kHeight,
                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_DEPTH_BIT),
          readback_(device, size_t{kWidth} * kHeight * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT) {
        // CPU arrays: Penumbra copies them into buffers of its own during the next recording.
        const std::vector<penumbra::Vec3> box_positions = scene_.positions(example::SceneMesh::Box);
        const std::vector<uint32_t> box_indices = scene_.indices(example::SceneMesh::Box);
        const std::vector<penumbra::Vec3> plane_positions = scene_.positions(example::SceneMesh::Plane);
        const std::vector<uint32_t> plane_indices = scene_.indices(example::SceneMesh::Plane);
        const penumbra::MeshId box = shadows_.add_mesh(penumbra::MeshData{box_positions, box_indices});
        const penumbra::MeshId plane = shadows_.add_mesh(penumbra::MeshData{plane_positions, plane_indices});
        box_ = shadows_.add_instance({box, example::translation(example::kBoxCentre)});
        shadows_.add_instance({plane, penumbra::Mat4{}});
        const penumbra::LightDesc sun{penumbra::LightType::Directional, example::kSunDirection};
        shadows_.set_lights({&sun, 1});
    }

    void move_box(const penumbra::Vec3& centre) {
        box_centre_ = centre;
        shadows_.set_instance_transform(box_, example::translation(centre));
    }

    // One frame: prepare, the application's depth pass, the resolve; the sun's visibility.
    std::vector<uint16_t> render() {
        const penumbra::ViewDesc view = example::camera_view(kWidth, kHeight);
        shadows_.prepare(view);
        const penumbra::Mat4 view_projection = example::multiply(forward_z_projection(view), view.view);
        device_.submit([&](VkCommandBuffer cmd) {
            shadows_.record_shadow_maps(cmd);
            example::begin_scene_pass(cmd, nullptr, depth_, kWidth, kHeight, 0.0f, 1.0f);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.pipeline);
            draw(cmd, example::SceneMesh::Box, view_projection, example::translation(box_centre_));
            draw(cmd, example::SceneMesh::Plane, view_projection, penumbra::Mat4{});
            vkCmdEndRendering(cmd);
            // The depth writes, made visible to the resolve's compute reads (the caller's part).
            example::barrier(cmd, depth_.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                             VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                             VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
            penumbra::ScreenInputs screen;
            screen.depth = depth_.view;
            screen.width = kWidth;
            screen.height = kHeight;
            screen.view_projection = view_projection;
            screen.background_depth = 1.0f;  // forward Z: the cleared far plane
            shadows_.record_visibility(cmd, screen);
            copy_visibility(cmd, shadows_.visibility_image(), readback_);
        });
        // Slot 0 (the sun) is the red channel of layer 0; written as 16 bits like --aov shadow.
        std::vector<uint16_t> visibility(size_t{kWidth} * kHeight);
        const auto* rgba = static_cast<const uint8_t*>(readback_.mapped);
        for (size_t i = 0; i < visibility.size(); ++i) visibility[i] = static_cast<uint16_t>(rgba[4 * i] * 257u);
        return visibility;
    }

private:
    static penumbra::ShadowSystemDesc shadow_system_desc(const example::Device& device) {
        penumbra::ShadowSystemDesc desc;
        desc.device = device.penumbra_desc();
        desc.frames_in_flight = 2;  // two slots: each frame here waits, which satisfies any count
        return desc;
    }

    void draw(VkCommandBuffer cmd, example::SceneMesh mesh, const penumbra::Mat4& view_projection,
              const penumbra::Mat4& model) const {
        const PushConstants constants{view_projection, model};
        vkCmdPushConstants(cmd, pipeline_.layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(constants), &constants);
        scene_.draw(cmd, mesh);
    }

    const example::Device& device_;
    example::SceneBuffers scene_;
    penumbra::ShadowSystem shadows_;
    DepthPipeline pipeline_;
    example::Image depth_;
    example::Buffer readback_;
    penumbra::InstanceId box_;
    penumbra::Vec3 box_centre_ = example::kBoxCentre;
};

int run(const std::string& first, const std::string& second, bool validate) {
    std::vector<uint16_t> before;
    std::vector<uint16_t> after;
    {
        const example::Device device(validate);
        DeferredFrame frame(device);
        before = frame.render();
        frame.move_box(kMovedBoxCentre);
        after = frame.render();
    }
    if (example::validation_message_count() > 0) {
        std::fprintf(stderr, "penumbra_deferred: the validation layer reported %u message(s)\n",
                     example::validation_message_count());
        return 3;
    }
    example::write_png16(first, kWidth, kHeight, before);
    example::write_png16(second, kWidth, kHeight, after);
    std::printf("penumbra_deferred: wrote %s and %s\n", first.c_str(), second.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: penumbra_deferred FIRST.png SECOND.png [--validate]\n");
        return 2;
    }
    const bool validate = argc > 3 && std::string(argv[3]) == "--validate";
    try {
        return run(argv[1], argv[2], validate);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "penumbra_deferred: %s\n", error.what());
        return 1;
    }
}
