// Every Vulkan object a ShadowSystem creates is destroyed, and re-creating its resources
// (the viewer changes a filter or a resolution every few frames) does not accumulate any
// (issue 17: the viewer grew with every renderer re-creation); with VK_EXT_debug_utils each
// gets a debug name and each pass a command label. The objects are counted through the
// caller's loader entry point, DeviceDesc::get_instance_proc_addr, which the library must
// use for every Vulkan function: this one hands out counting wrappers of the create and
// destroy functions, and recording ones of the debug-utils naming and labelling functions.
#include <array>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

// Kinds of object counted: one per create/destroy pair (pool-owned command buffers and
// descriptor sets go with their pools).
enum Kind {
    kBuffer,
    kImage,
    kImageView,
    kMemory,
    kSampler,
    kShaderModule,
    kPipeline,
    kPipelineLayout,
    kDescriptorSetLayout,
    kDescriptorPool,
    kCommandPool,
    kFence,
    kSemaphore,
    kQueryPool,
    kKindCount
};
constexpr std::array<const char*, kKindCount> kKindNames{
    "VkBuffer",    "VkImage",          "VkImageView",           "VkDeviceMemory",   "VkSampler",     "VkShaderModule",
    "VkPipeline",  "VkPipelineLayout", "VkDescriptorSetLayout", "VkDescriptorPool", "VkCommandPool", "VkFence",
    "VkSemaphore", "VkQueryPool"};

using Counts = std::array<int64_t, kKindCount>;
Counts g_live{};
std::vector<std::pair<Kind, uint64_t>> g_created;  // every object created, in order
std::map<uint64_t, std::string> g_names;           // vkSetDebugUtilsObjectNameEXT, by handle
std::vector<std::string> g_labels;                 // vkCmdBeginDebugUtilsLabelEXT, in order
int g_open_labels = 0;                             // begun and not yet ended
std::map<std::string, PFN_vkVoidFunction> g_real;  // the real functions, by name
PFN_vkGetInstanceProcAddr g_real_get_instance_proc_addr = nullptr;

template <typename F>
F real(const char* name) {
    return reinterpret_cast<F>(g_real.at(name));
}

// vkCreateX(device, info, allocator, out) and vkDestroyX(device, handle, allocator).
template <Kind kind, typename Handle, typename Info, const char* name>
VKAPI_ATTR VkResult VKAPI_CALL counted_create(VkDevice device, const Info* info, const VkAllocationCallbacks* allocator,
                                              Handle* out) {
    using Create = VkResult(VKAPI_PTR*)(VkDevice, const Info*, const VkAllocationCallbacks*, Handle*);
    const VkResult result = real<Create>(name)(device, info, allocator, out);
    if (result == VK_SUCCESS) {
        ++g_live[kind];
        g_created.emplace_back(kind, reinterpret_cast<uint64_t>(*out));
    }
    return result;
}
template <Kind kind, typename Handle, const char* name>
VKAPI_ATTR void VKAPI_CALL counted_destroy(VkDevice device, Handle handle, const VkAllocationCallbacks* allocator) {
    using Destroy = void(VKAPI_PTR*)(VkDevice, Handle, const VkAllocationCallbacks*);
    if (handle != VK_NULL_HANDLE) --g_live[kind];
    real<Destroy>(name)(device, handle, allocator);
}

template <typename Info, const char* name>
VKAPI_ATTR VkResult VKAPI_CALL counted_pipelines(VkDevice device, VkPipelineCache cache, uint32_t count,
                                                 const Info* infos, const VkAllocationCallbacks* allocator,
                                                 VkPipeline* out) {
    using Create = VkResult(VKAPI_PTR*)(VkDevice, VkPipelineCache, uint32_t, const Info*, const VkAllocationCallbacks*,
                                        VkPipeline*);
    const VkResult result = real<Create>(name)(device, cache, count, infos, allocator, out);
    for (uint32_t i = 0; i < count; ++i) {
        if (out[i] == VK_NULL_HANDLE) continue;
        ++g_live[kPipeline];
        g_created.emplace_back(kPipeline, reinterpret_cast<uint64_t>(out[i]));
    }
    return result;
}

VKAPI_ATTR VkResult VKAPI_CALL recorded_name(VkDevice device, const VkDebugUtilsObjectNameInfoEXT* info) {
    g_names[info->objectHandle] = info->pObjectName ? info->pObjectName : "";
    return real<PFN_vkSetDebugUtilsObjectNameEXT>("vkSetDebugUtilsObjectNameEXT")(device, info);
}

VKAPI_ATTR void VKAPI_CALL recorded_label_begin(VkCommandBuffer cmd, const VkDebugUtilsLabelEXT* label) {
    g_labels.emplace_back(label->pLabelName);
    ++g_open_labels;
    real<PFN_vkCmdBeginDebugUtilsLabelEXT>("vkCmdBeginDebugUtilsLabelEXT")(cmd, label);
}

VKAPI_ATTR void VKAPI_CALL recorded_label_end(VkCommandBuffer cmd) {
    --g_open_labels;
    real<PFN_vkCmdEndDebugUtilsLabelEXT>("vkCmdEndDebugUtilsLabelEXT")(cmd);
}

#define NAME(function) constexpr char k_##function[] = #function
NAME(vkCreateBuffer);
NAME(vkDestroyBuffer);
NAME(vkCreateImage);
NAME(vkDestroyImage);
NAME(vkCreateImageView);
NAME(vkDestroyImageView);
NAME(vkAllocateMemory);
NAME(vkFreeMemory);
NAME(vkCreateSampler);
NAME(vkDestroySampler);
NAME(vkCreateShaderModule);
NAME(vkDestroyShaderModule);
NAME(vkCreateGraphicsPipelines);
NAME(vkCreateComputePipelines);
NAME(vkDestroyPipeline);
NAME(vkCreatePipelineLayout);
NAME(vkDestroyPipelineLayout);
NAME(vkCreateDescriptorSetLayout);
NAME(vkDestroyDescriptorSetLayout);
NAME(vkCreateDescriptorPool);
NAME(vkDestroyDescriptorPool);
NAME(vkCreateCommandPool);
NAME(vkDestroyCommandPool);
NAME(vkCreateFence);
NAME(vkDestroyFence);
NAME(vkCreateSemaphore);
NAME(vkDestroySemaphore);
NAME(vkCreateQueryPool);
NAME(vkDestroyQueryPool);
#undef NAME

// The wrappers by function name.
const std::map<std::string, PFN_vkVoidFunction>& wrappers() {
    using F = PFN_vkVoidFunction;
#define PAIR(Kind_, Handle, Info, create, destroy)                                      \
    {#create, reinterpret_cast<F>(&counted_create<Kind_, Handle, Info, k_##create>)}, { \
#destroy, reinterpret_cast < F>(&counted_destroy <Kind_, Handle, k_##destroy>)  \
    }
    static const std::map<std::string, F> table{
        PAIR(kBuffer, VkBuffer, VkBufferCreateInfo, vkCreateBuffer, vkDestroyBuffer),
        PAIR(kImage, VkImage, VkImageCreateInfo, vkCreateImage, vkDestroyImage),
        PAIR(kImageView, VkImageView, VkImageViewCreateInfo, vkCreateImageView, vkDestroyImageView),
        PAIR(kMemory, VkDeviceMemory, VkMemoryAllocateInfo, vkAllocateMemory, vkFreeMemory),
        PAIR(kSampler, VkSampler, VkSamplerCreateInfo, vkCreateSampler, vkDestroySampler),
        PAIR(kShaderModule, VkShaderModule, VkShaderModuleCreateInfo, vkCreateShaderModule, vkDestroyShaderModule),
        PAIR(kPipelineLayout, VkPipelineLayout, VkPipelineLayoutCreateInfo, vkCreatePipelineLayout,
             vkDestroyPipelineLayout),
        PAIR(kDescriptorSetLayout, VkDescriptorSetLayout, VkDescriptorSetLayoutCreateInfo, vkCreateDescriptorSetLayout,
             vkDestroyDescriptorSetLayout),
        PAIR(kDescriptorPool, VkDescriptorPool, VkDescriptorPoolCreateInfo, vkCreateDescriptorPool,
             vkDestroyDescriptorPool),
        PAIR(kCommandPool, VkCommandPool, VkCommandPoolCreateInfo, vkCreateCommandPool, vkDestroyCommandPool),
        PAIR(kFence, VkFence, VkFenceCreateInfo, vkCreateFence, vkDestroyFence),
        PAIR(kSemaphore, VkSemaphore, VkSemaphoreCreateInfo, vkCreateSemaphore, vkDestroySemaphore),
        PAIR(kQueryPool, VkQueryPool, VkQueryPoolCreateInfo, vkCreateQueryPool, vkDestroyQueryPool),
        {"vkCreateGraphicsPipelines",
         reinterpret_cast<F>(&counted_pipelines<VkGraphicsPipelineCreateInfo, k_vkCreateGraphicsPipelines>)},
        {"vkCreateComputePipelines",
         reinterpret_cast<F>(&counted_pipelines<VkComputePipelineCreateInfo, k_vkCreateComputePipelines>)},
        {"vkDestroyPipeline", reinterpret_cast<F>(&counted_destroy<kPipeline, VkPipeline, k_vkDestroyPipeline>)},
        {"vkSetDebugUtilsObjectNameEXT", reinterpret_cast<F>(&recorded_name)},
        {"vkCmdBeginDebugUtilsLabelEXT", reinterpret_cast<F>(&recorded_label_begin)},
        {"vkCmdEndDebugUtilsLabelEXT", reinterpret_cast<F>(&recorded_label_end)},
    };
#undef PAIR
    return table;
}

// Remembers the real function and hands out its wrapper, if it has one.
PFN_vkVoidFunction wrap(const char* name, PFN_vkVoidFunction function) {
    const auto wrapper = wrappers().find(name);
    if (function == nullptr || wrapper == wrappers().end()) return function;
    g_real[name] = function;
    return wrapper->second;
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL counting_get_device_proc_addr(VkDevice device, const char* name) {
    const auto real_get = reinterpret_cast<PFN_vkGetDeviceProcAddr>(g_real.at("vkGetDeviceProcAddr"));
    return wrap(name, real_get(device, name));
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL counting_get_instance_proc_addr(VkInstance instance, const char* name) {
    const PFN_vkVoidFunction function = g_real_get_instance_proc_addr(instance, name);
    if (std::strcmp(name, "vkGetDeviceProcAddr") == 0 && function != nullptr) {
        g_real[name] = function;
        return reinterpret_cast<PFN_vkVoidFunction>(&counting_get_device_proc_addr);
    }
    return wrap(name, function);
}

std::string describe(const Counts& counts) {
    std::string text;
    for (size_t kind = 0; kind < kKindCount; ++kind) {
        if (counts[kind] != 0) text += std::string(kKindNames[kind]) + " " + std::to_string(counts[kind]) + "; ";
    }
    return text.empty() ? "none" : text;
}

class ObjectLifetimes : public LibraryTest {
protected:
    void SetUp() override {
        LibraryTest::SetUp();
        g_live = {};
        g_real.clear();
        g_created.clear();
        g_names.clear();
        g_labels.clear();
        g_open_labels = 0;
        g_real_get_instance_proc_addr = device_.get_instance_proc_addr != nullptr
                                            ? device_.get_instance_proc_addr
                                            : reinterpret_cast<PFN_vkGetInstanceProcAddr>(&vkGetInstanceProcAddr);
    }

    ShadowSystemDesc counting_desc(const Settings& settings) const {
        ShadowSystemDesc desc = system_desc(settings);
        desc.device.get_instance_proc_addr = &counting_get_instance_proc_addr;
        return desc;
    }

    static Settings with_filter(ShadowFilter filter, uint32_t resolution) {
        Settings settings = test_settings();
        settings.shadow.filter.mode = filter;
        settings.shadow.cascades.resolution = resolution;
        return settings;
    }
};

// A sun and a shadowed point light, so that cascades and local maps are both made.
void add_lights(ShadowSystem& shadows) {
    LightDesc lights[2] = {LightDesc{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}},
                           LightDesc{LightType::Point}};
    lights[1].position = {0.5f, 7.0f, 0.5f};
    shadows.set_lights(lights);
}

// Systems created, used for a frame and destroyed, with every filter: nothing they created
// outlives them.
TEST_F(ObjectLifetimes, DestroyedSystemsLeaveNoVulkanObject) {
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    for (const ShadowFilter filter : {ShadowFilter::Hard, ShadowFilter::Pcss, ShadowFilter::Vsm, ShadowFilter::Msm}) {
        {
            ShadowSystem shadows(counting_desc(with_filter(filter, 512)));
            add_scene(shadows, box, ground);
            add_lights(shadows);
            render_visibility(shadows);
            EXPECT_GT(g_live[kPipeline], 0) << "the counting loader saw no pipeline: the library bypassed it";
            EXPECT_GT(g_live[kImage], 0);
        }
        EXPECT_EQ(describe(g_live), "none") << "left alive after ~ShadowSystem with filter " << int(filter);
    }
}

// One long-lived system whose contents keep changing, as in the viewer: a mesh uploaded from
// arrays, placed, removed; a point light's map resized; settings that may change between
// frames. Once the frames that could use the replaced objects are done, the live objects
// are exactly those of the first frames.
TEST_F(ObjectLifetimes, ReplacedResourcesDoNotAccumulate) {
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    ShadowSystem shadows(counting_desc(with_filter(ShadowFilter::Pcf, 512)));
    add_scene(shadows, box, ground);
    LightDesc lights[2] = {LightDesc{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}},
                           LightDesc{LightType::Point}};
    lights[1].position = {0.5f, 7.0f, 0.5f};
    shadows.set_lights(lights);
    for (int frame = 0; frame < 3; ++frame) render_visibility(shadows);  // past the frames in flight
    const Counts settled = g_live;

    const MeshArrays quad = quad_mesh(true);
    for (int change = 0; change < 12; ++change) {
        const MeshId mesh = shadows.add_mesh(quad.data());
        const InstanceId instance = shadows.add_instance({mesh, translation({2.0f, 1.0f, 0.0f})});
        lights[1].shadow_resolution = change % 2 == 0 ? 256 : 512;
        shadows.set_lights(lights);
        Settings settings = shadows.settings();
        settings.shadow.bias.slope = change % 2 == 0 ? 2.5f : 2.0f;
        shadows.update_settings(settings);
        render_visibility(shadows);
        shadows.remove_instance(instance);
        shadows.remove_mesh(mesh);
        render_visibility(shadows);
    }
    lights[1].shadow_resolution = 0;
    shadows.set_lights(lights);
    for (int frame = 0; frame < 3; ++frame) render_visibility(shadows);  // releases what was retired
    EXPECT_EQ(describe(g_live), describe(settled));
}

// With VK_EXT_debug_utils on the instance (the tests' context enables it with the validation
// layer), every object a system creates gets a name saying what it is for, and every pass a
// balanced command label, so that capture tools and validation messages name them: with
// cascades and a point light, and with the virtual shadow map.
TEST_F(ObjectLifetimes, EveryObjectIsNamedAndEveryPassLabelled) {
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    Settings virtual_settings = with_filter(ShadowFilter::Pcf, 512);
    virtual_settings.shadow.technique = ShadowTechnique::Virtual;
    for (const Settings& settings : {with_filter(ShadowFilter::Vsm, 512), virtual_settings}) {
        g_created.clear();
        g_names.clear();
        g_labels.clear();
        {
            ShadowSystem shadows(counting_desc(settings));
            add_scene(shadows, box, ground);
            add_lights(shadows);
            render_visibility(shadows);
        }
        ASSERT_FALSE(g_created.empty());
        std::set<std::string> purposes;
        for (const auto& [kind, handle] : g_created) {
            const auto name = g_names.find(handle);
            ASSERT_NE(name, g_names.end()) << kKindNames[kind] << " created without a debug name";
            EXPECT_EQ(name->second.rfind("penumbra ", 0), 0u) << name->second;
            purposes.insert(name->second.substr(0, name->second.find(':')));
        }
        EXPECT_TRUE(purposes.count("penumbra cascade maps")) << "named: " << testing::PrintToString(purposes);
        EXPECT_TRUE(purposes.count("penumbra visibility image")) << testing::PrintToString(purposes);
        const std::set<std::string> labels(g_labels.begin(), g_labels.end());
        EXPECT_TRUE(labels.count("penumbra visibility")) << testing::PrintToString(labels);
        EXPECT_TRUE(labels.count("penumbra shadow_local")) << testing::PrintToString(labels);
        if (settings.shadow.technique == ShadowTechnique::Virtual) {
            EXPECT_TRUE(purposes.count("penumbra virtual shadow map")) << testing::PrintToString(purposes);
            EXPECT_TRUE(labels.count("penumbra shadow_virtual_raster")) << testing::PrintToString(labels);
        } else {
            EXPECT_TRUE(labels.count("penumbra shadow_moments")) << testing::PrintToString(labels);
        }
        EXPECT_EQ(g_open_labels, 0) << "every label begun is ended";
    }
}

}  // namespace
}  // namespace penumbra::library_tests
