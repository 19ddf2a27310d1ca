// Penumbra's commands under the validation layer's best-practices checks as well: its
// timestamps, barriers, placeholder images and memory allocations are not only valid but
// as the layer recommends. What the layer reports about the test harness itself, and about
// glslang's SPIR-V, is listed below with the reason; anything else fails the test.
#include <string>
#include <vector>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

// Messages that are not about Penumbra's use of Vulkan.
bool reported_of_the_harness(const std::string& message) {
    // The test's VulkanContext enables VK_EXT_debug_utils to receive these messages.
    if (message.find("BestPractices-vkCreateInstance-specialuse-extension-debugging") != std::string::npos) return true;
    // glslang declares the WorkgroupSize built-in in every compute module; it is deprecated
    // only from SPIR-V 1.6, whose LocalSizeId needs maintenance4, which Penumbra does not
    // ask of the caller's device (its modules are SPIR-V 1.5).
    if (message.find("BestPractices-SpirvDeprecated_WorkgroupSize") != std::string::npos) return true;
    // The harness's own 160 x 160 depth image and readback buffers (102400 bytes), one
    // allocation each; Penumbra's come from its block allocator.
    const bool small = message.find("BestPractices-vkAllocateMemory-small-allocation") != std::string::npos ||
                       message.find("BestPractices-vkBindMemory-small-dedicated-allocation") != std::string::npos;
    return small && (message.find(" 102400") != std::string::npos);
}

class BestPractices : public LibraryTest {
protected:
    bool best_practices() const override { return true; }
    void TearDown() override {
        if (context_) vkDeviceWaitIdle(device_.device);
        std::erase_if(log_->messages, reported_of_the_harness);
        LibraryTest::TearDown();
    }
};

// The sun, a spot and a point light, three frames each: cascades per cascade and layered
// (GPU culling), and the virtual shadow map; the footprint is checked so that the frames
// are the real thing.
TEST_F(BestPractices, FramesOfEveryTechniqueFollowTheLayersAdvice) {
    for (const char* variant : {"cascades", "layered", "virtual"}) {
        SCOPED_TRACE(variant);
        Settings settings = test_settings();
        if (std::string(variant) == "layered") settings.shadow.strategy = ShadowStrategy::Layered;
        if (std::string(variant) == "virtual") settings.shadow.technique = ShadowTechnique::Virtual;
        ShadowSystem shadows(system_desc(settings));
        const MeshArrays box = box_mesh();
        const MeshArrays ground = ground_mesh();
        add_scene(shadows, box, ground);
        std::vector<LightDesc> lights{{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}},
                                      {LightType::Spot, {0.0f, -1.0f, 0.0f}, {1.0f, 8.0f, 0.0f}},
                                      {LightType::Point, {0.0f, -1.0f, 0.0f}, {-2.0f, 7.0f, 1.0f}}};
        shadows.set_lights(lights);
        for (int frame = 0; frame < 2; ++frame) render_visibility(shadows);
        expect_box_shadow_of_the_sun(render_visibility(shadows));
    }
}

// Frames without local lights bind a placeholder local map; it is cleared once, not made
// readable from undefined contents every frame.
TEST_F(BestPractices, FramesWithoutLocalLightsFollowTheLayersAdvice) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    for (int frame = 0; frame < 3; ++frame) render_visibility(shadows);
}

}  // namespace
}  // namespace penumbra::library_tests
