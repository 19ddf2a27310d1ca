// The library's error contract: a device that lacks something, invalid values and calls
// out of order each throw one typed error naming the problem, and leave the ShadowSystem
// usable and unchanged.
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

using DeviceChecks = LibraryTest;

TEST_F(DeviceChecks, NullFeatureChainIsAnInputError) {
    ShadowSystemDesc desc = system_desc();
    desc.device.enabled_features = nullptr;
    expect_error<InputError>([&] { ShadowSystem shadows(desc); }, "enabled_features");
}

TEST_F(DeviceChecks, NullHandlesAreInputErrors) {
    ShadowSystemDesc desc = system_desc();
    desc.device.queue = VK_NULL_HANDLE;
    expect_error<InputError>([&] { ShadowSystem shadows(desc); }, "DeviceDesc::queue");
}

// Penumbra reads what the device was created with from the chain the caller passes: a
// chain without a required feature must be refused, naming it.
TEST_F(DeviceChecks, MissingSynchronization2IsNamed) {
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.dynamicRendering = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features13};
    ShadowSystemDesc desc = system_desc();
    desc.device.enabled_features = &features;
    expect_error<DeviceError>([&] { ShadowSystem shadows(desc); }, "synchronization2");
}

TEST_F(DeviceChecks, MissingDynamicRenderingIsNamed) {
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.synchronization2 = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features13};
    ShadowSystemDesc desc = system_desc();
    desc.device.enabled_features = &features;
    expect_error<DeviceError>([&] { ShadowSystem shadows(desc); }, "dynamicRendering");
}

// The same two features through the Vulkan 1.3 promoted extension structs are accepted.
TEST_F(DeviceChecks, ExtensionFeatureStructsAreUnderstood) {
    VkPhysicalDeviceSynchronization2Features sync2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES};
    sync2.synchronization2 = VK_TRUE;
    VkPhysicalDeviceDynamicRenderingFeatures dynamic{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES,
                                                     &sync2};
    dynamic.dynamicRendering = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &dynamic};
    ShadowSystemDesc desc = system_desc();
    desc.device.enabled_features = &features;
    EXPECT_NO_THROW(ShadowSystem shadows(desc));
}

TEST_F(DeviceChecks, OldInstanceVersionIsRefused) {
    ShadowSystemDesc desc = system_desc();
    desc.device.instance_api_version = VK_API_VERSION_1_2;
    expect_error<DeviceError>([&] { ShadowSystem shadows(desc); }, "needs 1.3");
}

TEST_F(DeviceChecks, UnknownQueueFamilyIsAnInputError) {
    ShadowSystemDesc desc = system_desc();
    desc.device.queue_family = 1000;
    expect_error<InputError>([&] { ShadowSystem shadows(desc); }, "queue_family 1000");
}

// A device created with only the features Penumbra requires refuses `desc`'s strategy with
// a DeviceError naming `named`.
void expect_refused_with_required_features_only(ShadowSystemDesc desc, const char* named) {
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.dynamicRendering = VK_TRUE;
    features13.synchronization2 = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features13};
    desc.device.enabled_features = &features;
    expect_error<DeviceError>([&] { ShadowSystem shadows(desc); }, named);
}

// The multiview strategy needs the optional multiview feature: without it in the chain,
// asking for the strategy names the feature.
TEST_F(DeviceChecks, MultiviewStrategyWithoutTheFeatureIsNamed) {
    Settings settings = test_settings();
    settings.shadow.strategy = ShadowStrategy::Multiview;
    expect_refused_with_required_features_only(system_desc(settings), "multiview");
}

// The layered strategy needs the GPU-driven features (indirect counts, first instance,
// shaderOutputLayer): a chain without them names them.
TEST_F(DeviceChecks, LayeredStrategyWithoutTheGpuDrivenFeaturesIsNamed) {
    Settings settings = test_settings();
    settings.shadow.strategy = ShadowStrategy::Layered;
    expect_refused_with_required_features_only(system_desc(settings), "drawIndirectCount and shaderOutputLayer");
}

// The virtual shadow map draws each caster into its page's layer and viewport of the pool:
// a chain with the GPU-driven features but without multiViewport and
// shaderOutputViewportIndex names those two.
TEST_F(DeviceChecks, VirtualTechniqueWithoutItsViewportFeaturesIsNamed) {
    Settings settings = test_settings();
    settings.shadow.technique = ShadowTechnique::Virtual;
    ShadowSystemDesc desc = system_desc(settings);
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.dynamicRendering = VK_TRUE;
    features13.synchronization2 = VK_TRUE;
    VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &features13};
    features12.drawIndirectCount = VK_TRUE;
    features12.shaderOutputLayer = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features12};
    features.features.multiDrawIndirect = VK_TRUE;
    features.features.drawIndirectFirstInstance = VK_TRUE;
    desc.device.enabled_features = &features;
    expect_error<DeviceError>([&] { ShadowSystem shadows(desc); }, "multiViewport");
    expect_error<DeviceError>([&] { ShadowSystem shadows(desc); }, "shaderOutputViewportIndex");
}

TEST_F(DeviceChecks, FramesInFlightOutOfRange) {
    expect_error<InputError>([&] { ShadowSystem shadows(system_desc(test_settings(), 0)); }, "frames_in_flight");
    expect_error<InputError>([&] { ShadowSystem shadows(system_desc(test_settings(), 9)); }, "frames_in_flight");
}

TEST_F(DeviceChecks, InvalidSettingsNameTheSetting) {
    Settings settings = test_settings();
    settings.shadow.cascades.resolution = 100;
    expect_error<InputError>([&] { ShadowSystem shadows(system_desc(settings)); }, "shadow_resolution");
}

// Every Vulkan function Penumbra calls comes through the caller's vkGetInstanceProcAddr.
std::atomic<int> g_lookups{0};
std::atomic<bool> g_device_lookup{false};
VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL counting_lookup(VkInstance instance, const char* name) {
    ++g_lookups;
    if (std::string(name) == "vkGetDeviceProcAddr") g_device_lookup = true;
    return vkGetInstanceProcAddr(instance, name);
}

TEST_F(DeviceChecks, CallersLoaderEntryPointIsUsed) {
    ShadowSystemDesc desc = system_desc();
    desc.device.get_instance_proc_addr = counting_lookup;
    ShadowSystem shadows(desc);
    EXPECT_GT(g_lookups.load(), 10);
    EXPECT_TRUE(g_device_lookup.load());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    expect_box_shadow_of_the_sun(render_visibility(shadows));
}

using ApiMisuse = LibraryTest;

TEST_F(ApiMisuse, RecordingBeforePrepareIsAUsageError) {
    ShadowSystem shadows(system_desc());
    submit([&](VkCommandBuffer cmd) {
        expect_error<UsageError>([&] { shadows.record_shadow_maps(cmd); }, "prepare() first");
        ScreenInputs screen;
        screen.depth = depth_->view;
        screen.width = screen.height = kScreen;
        expect_error<UsageError>([&] { shadows.record_visibility(cmd, screen); }, "prepare() first");
    });
}

TEST_F(ApiMisuse, RecordingTwiceOrOutOfOrderIsAUsageError) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    shadows.prepare(top_down_view());
    submit([&](VkCommandBuffer cmd) {
        ScreenInputs screen;
        screen.depth = depth_->view;
        screen.width = screen.height = kScreen;
        expect_error<UsageError>([&] { shadows.record_visibility(cmd, screen); }, "record_shadow_maps()");
        shadows.record_shadow_maps(cmd);
        expect_error<UsageError>([&] { shadows.record_shadow_maps(cmd); }, "already recorded");
        record_ground_visibility(cmd, shadows, nullptr, NormalEncoding::SignedFloat);
        expect_error<UsageError>([&] { record_ground_visibility(cmd, shadows, nullptr, NormalEncoding::SignedFloat); },
                                 "once per frame");
    });
    // The failed calls changed nothing: the frame's visibility is the box's shadow.
    expect_box_shadow_of_the_sun(read_visibility(shadows, 0));
}

TEST_F(ApiMisuse, BadScreenInputsAreInputErrors) {
    ShadowSystem shadows(system_desc());
    shadows.prepare(top_down_view());
    submit([&](VkCommandBuffer cmd) {
        shadows.record_shadow_maps(cmd);
        ScreenInputs screen;
        screen.width = screen.height = kScreen;
        expect_error<InputError>([&] { shadows.record_visibility(cmd, screen); }, "ScreenInputs::depth");
        screen.depth = depth_->view;
        screen.width = 0;
        expect_error<InputError>([&] { shadows.record_visibility(cmd, screen); }, "width/height");
        screen.width = kScreen;
        screen.view_projection.m.fill(0.0f);
        expect_error<InputError>([&] { shadows.record_visibility(cmd, screen); }, "not invertible");
    });
}

TEST_F(ApiMisuse, UnknownHandlesAreUsageErrors) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshId mesh = shadows.add_mesh(box.data());
    expect_error<UsageError>([&] { shadows.add_instance({MeshId{mesh.value + 100}, Mat4{}}); }, "mesh");
    const InstanceId instance = shadows.add_instance({mesh, Mat4{}});
    expect_error<UsageError>([&] { shadows.set_instance_transform(InstanceId{instance.value + 100}, Mat4{}); },
                             "instance");
    expect_error<UsageError>([&] { shadows.set_instance_flags(InstanceId{}, 0); }, "instance");
    shadows.remove_instance(instance);
    expect_error<UsageError>([&] { shadows.remove_instance(instance); }, "instance");
    expect_error<UsageError>([&] { shadows.set_instance_transform(instance, Mat4{}); }, "instance");
}

TEST_F(ApiMisuse, MeshInUseCannotBeRemoved) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshId mesh = shadows.add_mesh(box.data());
    const InstanceId instance = shadows.add_instance({mesh, Mat4{}});
    expect_error<UsageError>([&] { shadows.remove_mesh(mesh); }, "still used");
    shadows.remove_instance(instance);
    EXPECT_NO_THROW(shadows.remove_mesh(mesh));
    expect_error<UsageError>([&] { shadows.remove_mesh(mesh); }, "mesh");
}

TEST_F(ApiMisuse, InvalidMeshDataIsAnInputError) {
    ShadowSystem shadows(system_desc());
    MeshArrays mesh = box_mesh();
    mesh.indices.pop_back();
    expect_error<InputError>([&] { shadows.add_mesh(mesh.data()); }, "multiple of 3");
    mesh = box_mesh();
    mesh.indices[4] = static_cast<uint32_t>(mesh.positions.size());
    expect_error<InputError>([&] { shadows.add_mesh(mesh.data()); }, "indices");
    mesh = box_mesh();
    mesh.positions[2].y = std::numeric_limits<float>::quiet_NaN();
    expect_error<InputError>([&] { shadows.add_mesh(mesh.data()); }, "positions");
    expect_error<InputError>([&] { shadows.add_mesh(MeshData{}); }, "positions: is empty");
    mesh = box_mesh();
    const std::vector<Vec2> uvs(3);
    MeshData with_uvs = mesh.data();
    with_uvs.uvs = uvs;
    expect_error<InputError>([&] { shadows.add_mesh(with_uvs); }, "uvs");
}

TEST_F(ApiMisuse, InvalidMeshDescIsAnInputError) {
    ShadowSystem shadows(system_desc());
    HostBuffer vertices(device_, 1024, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    HostBuffer indices(device_, 1024, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    MeshDesc desc;
    desc.positions = {vertices.buffer, 0, 12, VK_FORMAT_R32G32B32_SFLOAT};
    desc.index_buffer = indices.buffer;
    desc.index_count = 36;
    desc.bounds = {{-1, -1, -1}, {1, 1, 1}};
    MeshDesc bad = desc;
    bad.positions.buffer = VK_NULL_HANDLE;
    expect_error<InputError>([&] { shadows.add_mesh(bad); }, "positions");
    bad = desc;
    bad.positions.format = VK_FORMAT_R8G8B8A8_UINT;
    expect_error<InputError>([&] { shadows.add_mesh(bad); },  // the format by its name, not its number
                             "ShadowSystem::add_mesh: positions.format: VK_FORMAT_R8G8B8A8_UINT is not supported");
    bad.positions.format = static_cast<VkFormat>(1000999999);  // no format of the core API
    expect_error<InputError>([&] { shadows.add_mesh(bad); }, "positions.format: VkFormat 1000999999 is not supported");
    bad = desc;
    bad.index_count = 35;
    expect_error<InputError>([&] { shadows.add_mesh(bad); }, "index_count");
    bad = desc;
    bad.bounds = {{1, 1, 1}, {-1, -1, -1}};
    expect_error<InputError>([&] { shadows.add_mesh(bad); }, "bounds");
    bad = desc;
    bad.alpha_mask = AlphaMaskDesc{};
    expect_error<InputError>([&] { shadows.add_mesh(bad); }, "alpha_mask.view");
    EXPECT_NO_THROW(shadows.add_mesh(desc));
}

TEST_F(ApiMisuse, InvalidLightsAreRefusedAndTheOldOnesKept) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    add_scene(shadows, box, ground);
    LightDesc zero{LightType::Directional, {0.0f, 0.0f, 0.0f}};
    expect_error<InputError>([&] { shadows.set_lights({&zero, 1}); }, "direction");
    LightDesc spot{LightType::Spot, {0.0f, -1.0f, 0.0f}, {0.0f, 5.0f, 0.0f}};
    spot.inner_angle_degrees = 40.0f;
    spot.outer_angle_degrees = 30.0f;
    expect_error<InputError>([&] { shadows.set_lights({&spot, 1}); }, "angle");
    spot = LightDesc{LightType::Point, {0.0f, -1.0f, 0.0f}, {0.0f, 5.0f, 0.0f}};
    spot.range = -1.0f;
    expect_error<InputError>([&] { shadows.set_lights({&spot, 1}); }, "range");
    const std::vector<LightDesc> too_many(kMaxLights + 1);
    expect_error<InputError>([&] { shadows.set_lights(too_many); }, "at most");
    // Still the sun of add_scene().
    expect_box_shadow_of_the_sun(render_visibility(shadows));
}

// Values beyond the header's contract (issue 32, item 8): coordinates beyond
// kMaxWorldMagnitude, singular or projective transforms, flags and light types the enums do
// not define. Each is an InputError naming the call and the argument, and changes nothing.
TEST_F(ApiMisuse, ValuesBeyondTheContractAreRefused) {
    ShadowSystem shadows(system_desc());
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    const InstanceId instance = add_scene(shadows, box, ground);
    const MeshId mesh = shadows.add_mesh(box.data());

    Mat4 huge_scale = translation(kBoxCentre);
    huge_scale(0, 0) = huge_scale(1, 1) = huge_scale(2, 2) = 1e30f;
    expect_error<InputError>(
        [&] {
            shadows.add_instance({mesh, huge_scale});
        },
        "ShadowSystem::add_instance: world: places the mesh at");
    const Mat4 far_away = translation({1e30f, 0.0f, 0.0f});
    expect_error<InputError>([&] { shadows.set_instance_transform(instance, far_away); },
                             "ShadowSystem::set_instance_transform: world: places the mesh at (1e+30");
    Mat4 singular = translation(kBoxCentre);
    singular(1, 1) = 0.0f;
    expect_error<InputError>([&] { shadows.add_instance({mesh, singular}); }, "world: is not invertible");
    Mat4 projective;
    projective(3, 2) = -1.0f;
    expect_error<InputError>([&] { shadows.set_instance_transform(instance, projective); },
                             "world: is not affine: its bottom row is (0, 0, -1, 1), not (0, 0, 0, 1)");
    expect_error<InputError>(
        [&] {
            shadows.add_instance({mesh, Mat4{}, kInstanceCastsShadows | (1u << 4)});
        },
        "ShadowSystem::add_instance: flags: 0x11 holds bits InstanceFlags does not define");
    expect_error<InputError>([&] { shadows.set_instance_flags(instance, 0x80000000u); }, "set_instance_flags: flags");

    MeshArrays far_mesh = box_mesh();
    far_mesh.positions[3] = {3e38f, 0.0f, 0.0f};
    expect_error<InputError>([&] { shadows.add_mesh(far_mesh.data()); },
                             "ShadowSystem::add_mesh: positions[3]: (3e+38, 0, 0) is beyond 1e+09 in magnitude");

    LightDesc unknown_type{static_cast<LightType>(9), {0.0f, -1.0f, 0.0f}};
    expect_error<InputError>(
        [&] {
            shadows.set_lights({&unknown_type, 1});
        },
        "ShadowSystem::set_lights: lights[0].type: 9 is not a LightType");
    LightDesc far_light{LightType::Point, {0.0f, -1.0f, 0.0f}, {0.0f, 2e9f, 0.0f}};
    expect_error<InputError>([&] { shadows.set_lights({&far_light, 1}); }, "lights[0].position: (0, 2e+09, 0)");

    // The limit itself, a mirror and all the defined flags are fine.
    Mat4 mirror = translation(kBoxCentre);
    mirror(0, 0) = -1.0f;
    EXPECT_NO_THROW(shadows.remove_instance(shadows.add_instance({mesh, mirror, kInstanceAllFlags})));
    // Nothing changed: the box of add_scene() still casts its shadow.
    expect_box_shadow_of_the_sun(render_visibility(shadows));
}

TEST_F(ApiMisuse, InvalidViewIsAnInputError) {
    ShadowSystem shadows(system_desc());
    ViewDesc view = top_down_view();
    view.near_plane = 0.0f;
    expect_error<InputError>([&] { shadows.prepare(view); }, "near_plane");
    view = top_down_view();
    view.far_plane = std::numeric_limits<float>::infinity();
    expect_error<InputError>([&] { shadows.prepare(view); }, "far_plane");
    view = top_down_view();
    view.width = 0;
    expect_error<InputError>([&] { shadows.prepare(view); }, "width/height");
    view = top_down_view();
    view.view.m.fill(0.0f);
    expect_error<InputError>([&] { shadows.prepare(view); }, "not invertible");
}

// Every valid setting is taken (SettingsChanges covers what each rebuilds), from the next
// prepare(); an invalid one is an InputError that changes nothing.
TEST_F(ApiMisuse, SettingsApplyFromTheNextPrepareInvalidOnesChangeNothing) {
    ShadowSystem shadows(system_desc());
    Settings bigger = test_settings();
    bigger.shadow.cascades.resolution = 4096;
    EXPECT_EQ(shadows.update_settings(bigger).effect, SettingEffect::Resource);
    EXPECT_EQ(shadows.settings().shadow.cascades.resolution, 4096u);
    Settings invalid = bigger;
    invalid.shadow.bias.slope = -1.0f;
    expect_error<InputError>([&] { shadows.update_settings(invalid); }, "slope_bias");
    EXPECT_EQ(shadows.settings().shadow.bias.slope, bigger.shadow.bias.slope);
    EXPECT_EQ(shadows.update_settings(test_settings()).effect, SettingEffect::Resource);

    const float before = shadows.prepare(top_down_view()).shadow_distance;
    Settings nearer = test_settings();
    nearer.shadow.cascades.max_distance = 40.0f;
    shadows.update_settings(nearer);
    const FrameInfo& info = shadows.prepare(top_down_view());
    EXPECT_GT(before, 60.0f);
    EXPECT_LE(info.shadow_distance, 40.0f);
    EXPECT_FLOAT_EQ(info.cascades.back().split_far, info.shadow_distance);
}

}  // namespace
}  // namespace penumbra::library_tests
