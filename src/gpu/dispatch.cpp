#include "penumbra/gpu/dispatch.hpp"

#include <string>

#include "penumbra/errors.hpp"

// The one declaration of a loader entry point: everything else goes through the table.
extern "C" VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkGetInstanceProcAddr(VkInstance instance, const char* name);

namespace penumbra::gpu {
namespace {

// Instance extension functions that may be absent (the extension was not enabled).
bool optional_instance_function(const std::string& name) { return name.ends_with("EXT") || name.ends_with("KHR"); }

template <typename Function>
void require(Function function, const char* name) {
    if (function == nullptr) {
        throw DeviceError(std::string("the Vulkan driver does not provide ") + name +
                          " (Penumbra needs a Vulkan 1.3 device)");
    }
}

}  // namespace

PFN_vkGetInstanceProcAddr loader_instance_proc_addr() { return &::vkGetInstanceProcAddr; }

VulkanFunctions load_global_functions(PFN_vkGetInstanceProcAddr get_instance_proc_addr) {
    VulkanFunctions functions;
    functions.vkGetInstanceProcAddr = get_instance_proc_addr;
#define PENUMBRA_VK_LOAD(name)                                                             \
    functions.name = reinterpret_cast<PFN_##name>(get_instance_proc_addr(nullptr, #name)); \
    require(functions.name, #name);
    PENUMBRA_VK_GLOBAL_FUNCTIONS(PENUMBRA_VK_LOAD)
#undef PENUMBRA_VK_LOAD
    return functions;
}

void load_instance_functions(VulkanFunctions& functions, VkInstance instance) {
#define PENUMBRA_VK_LOAD(name)                                                                       \
    functions.name = reinterpret_cast<PFN_##name>(functions.vkGetInstanceProcAddr(instance, #name)); \
    if (!optional_instance_function(#name)) require(functions.name, #name);
    PENUMBRA_VK_INSTANCE_FUNCTIONS(PENUMBRA_VK_LOAD)
#undef PENUMBRA_VK_LOAD
}

void load_device_functions(VulkanFunctions& functions, VkDevice device) {
#define PENUMBRA_VK_LOAD(name)                                                                   \
    functions.name = reinterpret_cast<PFN_##name>(functions.vkGetDeviceProcAddr(device, #name)); \
    require(functions.name, #name);
    PENUMBRA_VK_DEVICE_FUNCTIONS(PENUMBRA_VK_LOAD)
#undef PENUMBRA_VK_LOAD
#define PENUMBRA_VK_LOAD(name) \
    functions.name = reinterpret_cast<PFN_##name>(functions.vkGetDeviceProcAddr(device, #name));
    PENUMBRA_VK_DEVICE_EXTENSION_FUNCTIONS(PENUMBRA_VK_LOAD)
#undef PENUMBRA_VK_LOAD
}

}  // namespace penumbra::gpu
