// Penumbra's minimal example: forward shading with Penumbra's GLSL shadow library.
//
// The application owns everything Vulkan: its instance and device (created with exactly
// the features Penumbra requires), its vertex and index buffers, its forward pipeline and
// its command buffer. Penumbra gets the device, the application's buffers as meshes, the
// instances, the sun and the camera; per frame it fits and culls (prepare), records its
// shadow maps into the application's command buffer, and the application's own fragment
// shader samples them through Penumbra's descriptor set (set 0 here): forward.frag, or with
// --hlsl the same shader in HLSL, forward.frag.hlsl (Penumbra's HLSL library; same image).
//
// Fixed scene: a 2 m box centred at (0, 3, 0) over a 40 x 40 m plane at y = 0, camera at
// (0, 6, 12) looking at the origin (60 degrees vertically, 640 x 360), sun travelling
// along (-0.4, -1, -0.3). Writes the sun's visibility as a 16-bit PNG: 65535 lit (and
// where there is no geometry), 0 in shadow and on faces turned away from the sun.
//
//   penumbra_minimal out.png [--validate] [--hlsl]
#include <penumbra/penumbra.hpp>

#include <array>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "example_vulkan.hpp"
#include "scene_geometry.hpp"

namespace {

constexpr uint32_t kWidth = 640;
constexpr uint32_t kHeight = 360;

const uint32_t kVertexShader[] =
#include "forward.vert.inc"
    ;
const uint32_t kFragmentShader[] =
#include "forward.frag.inc"
    ;
const uint32_t kHlslFragmentShader[] =
#include "forward.frag.hlsl.inc"
    ;

struct PushConstants {
    penumbra::Mat4 view_projection;
    penumbra::Mat4 model;
};

// The application's forward pipeline: its vertices (position, normal), its push constants,
// and Penumbra's descriptor set layout at set 0 with Penumbra's specialization constants.
struct ForwardPipeline {
    VkDevice device = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;

    ForwardPipeline(const example::Device& owner, const penumbra::ShadowSystem& shadows, bool hlsl)
        : device(owner.device) {
        const VkDescriptorSetLayout set_layout = shadows.descriptor_set_layout();
        const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(PushConstants)};
        VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        layout_info.setLayoutCount = 1;
        layout_info.pSetLayouts = &set_layout;
        layout_info.pushConstantRangeCount = 1;
        layout_info.pPushConstantRanges = &push;
        EXAMPLE_CHECK(vkCreatePipelineLayout(device, &layout_info, nullptr, &layout));

        const VkShaderModule vertex = example::shader_module(owner, kVertexShader, sizeof(kVertexShader));
        const VkShaderModule fragment =
            hlsl ? example::shader_module(owner, kHlslFragmentShader, sizeof(kHlslFragmentShader))
                 : example::shader_module(owner, kFragmentShader, sizeof(kFragmentShader));
        const penumbra::ShaderSpecialization specialization = shadows.shader_specialization(0);
        const VkSpecializationInfo specialization_info = specialization.info();
        std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
        stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
        stages[0].module = vertex;
        stages[0].pName = "main";
        stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
        stages[1].module = fragment;
        stages[1].pName = "main";
        stages[1].pSpecializationInfo = &specialization_info;
        pipeline = example::create_scene_pipeline(owner, layout, stages, VK_FORMAT_R16_UNORM, VK_COMPARE_OP_GREATER);
        vkDestroyShaderModule(device, vertex, nullptr);
        vkDestroyShaderModule(device, fragment, nullptr);
    }
    ~ForwardPipeline() {
        vkDestroyPipeline(device, pipeline, nullptr);
        vkDestroyPipelineLayout(device, layout, nullptr);
    }
};

std::vector<uint16_t> render(const example::Device& device, bool hlsl) {
    const example::SceneBuffers scene(device);
    std::vector<uint16_t> visibility;
    {
        penumbra::ShadowSystemDesc desc;
        desc.device = device.penumbra_desc();
        desc.frames_in_flight = 1;  // this example waits for its one frame
        penumbra::ShadowSystem shadows(desc);

        // The application's own buffers, given as they are: nothing is copied.
        const penumbra::MeshId box = shadows.add_mesh(scene.box_mesh());
        const penumbra::MeshId plane = shadows.add_mesh(scene.plane_mesh());
        shadows.add_instance({box, example::translation(example::kBoxCentre)});
        shadows.add_instance({plane, penumbra::Mat4{}});
        const penumbra::LightDesc sun{penumbra::LightType::Directional, example::kSunDirection};
        shadows.set_lights({&sun, 1});

        const penumbra::ViewDesc view = example::camera_view(kWidth, kHeight);
        const penumbra::FrameInfo& frame = shadows.prepare(view);
        const ForwardPipeline forward(device, shadows, hlsl);
        const example::Image target(device, VK_FORMAT_R16_UNORM, kWidth, kHeight,
                                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                    VK_IMAGE_ASPECT_COLOR_BIT);
        const example::Image depth(device, VK_FORMAT_D32_SFLOAT, kWidth, kHeight,
                                   VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
        const example::Buffer readback(device, size_t{kWidth} * kHeight * sizeof(uint16_t),
                                       VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        // Penumbra's reverse-Z projection for the camera; any projection would do here.
        const penumbra::Mat4 view_projection = example::multiply(penumbra::reverse_z_projection(view), view.view);

        device.submit([&](VkCommandBuffer cmd) {
            shadows.record_shadow_maps(cmd);  // leaves the maps ready for fragment shaders
            example::begin_scene_pass(cmd, &target, depth, kWidth, kHeight, 1.0f, 0.0f);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, forward.pipeline);
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, forward.layout, 0, 1, &frame.descriptor_set,
                                    0, nullptr);
            for (const auto& [mesh, model] :
                 {std::pair{example::SceneMesh::Box, example::translation(example::kBoxCentre)},
                  std::pair{example::SceneMesh::Plane, penumbra::Mat4{}}}) {
                const PushConstants constants{view_projection, model};
                vkCmdPushConstants(cmd, forward.layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(constants), &constants);
                scene.draw(cmd, mesh);
            }
            vkCmdEndRendering(cmd);
            example::copy_to_buffer(cmd, target, kWidth, kHeight, readback);
        });
        visibility.resize(size_t{kWidth} * kHeight);
        std::memcpy(visibility.data(), readback.mapped, visibility.size() * sizeof(uint16_t));
    }  // the ShadowSystem goes before the buffers it was given
    return visibility;
}

int run(const std::string& output, bool validate, bool hlsl) {
    std::vector<uint16_t> visibility;
    {
        const example::Device device(validate);
        visibility = render(device, hlsl);
    }
    if (example::validation_message_count() > 0) {
        std::fprintf(stderr, "penumbra_minimal: the validation layer reported %u message(s)\n",
                     example::validation_message_count());
        return 3;
    }
    example::write_png16(output, kWidth, kHeight, visibility);
    std::printf("penumbra_minimal: wrote %s\n", output.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    bool validate = false;
    bool hlsl = false;
    bool usage_error = argc < 2;
    for (int i = 2; i < argc; ++i) {
        const std::string flag = argv[i];
        validate = validate || flag == "--validate";
        hlsl = hlsl || flag == "--hlsl";
        usage_error = usage_error || (flag != "--validate" && flag != "--hlsl");
    }
    if (usage_error) {
        std::fprintf(stderr, "usage: penumbra_minimal OUT.png [--validate] [--hlsl]\n");
        return 2;
    }
    try {
        return run(argv[1], validate, hlsl);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "penumbra_minimal: %s\n", error.what());
        return 1;
    }
}
