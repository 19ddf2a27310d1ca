#include "library/device_context.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <optional>

#include "penumbra/errors.hpp"
#include "penumbra/gpu/check.hpp"

namespace penumbra::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// Where a Context's messenger delivers: its log and its callback.
VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                     void* user_data) {
    const auto* context = static_cast<const Context*>(user_data);
    const bool is_error = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0;
    std::string message = std::string(is_error ? "validation error: " : "validation warning: ") +
                          (data->pMessage ? data->pMessage : "(no message)");
    context->report_validation_message(std::move(message));
    return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(const Context* context) {
    VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = on_validation_message;
    // The callback only reads the context, but the field is not const.
    info.pUserData = const_cast<Context*>(context);
    return info;
}

bool layer_available(const VulkanFunctions& vk, const char* name) {
    uint32_t count = 0;
    vk.vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vk.vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(),
                       [name](const VkLayerProperties& layer) { return std::strcmp(layer.layerName, name) == 0; });
}

VkInstance create_bare_instance(const VulkanFunctions& vk, const void* next, const std::vector<const char*>& layers,
                                const std::vector<const char*>& extensions) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "penumbra";
    app.pEngineName = "penumbra";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pNext = next;
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkInstance instance = VK_NULL_HANDLE;
    const VkResult result = vk.vkCreateInstance(&info, nullptr, &instance);
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER || result == VK_ERROR_INITIALIZATION_FAILED) {
        throw DeviceError("no Vulkan driver found (vkCreateInstance returned " + std::string(result_name(result)) +
                          "); install a Vulkan driver, e.g. mesa-vulkan-drivers for the lavapipe CPU device");
    }
    if (result == VK_ERROR_LAYER_NOT_PRESENT) {
        throw DeviceError(std::string(kValidationLayer) +
                          " is installed but failed to load (vkCreateInstance returned " + result_name(result) + ")");
    }
    if (result != VK_SUCCESS)
        throw_vk_failure("vkCreateInstance(&info, nullptr, &instance)", result, __FILE__, __LINE__);
    return instance;
}

std::vector<VkPhysicalDevice> enumerate_physical_devices(const VulkanFunctions& vk, VkInstance instance) {
    uint32_t count = 0;
    PENUMBRA_VK_CHECK(vk.vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    PENUMBRA_VK_CHECK(vk.vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    return devices;
}

int device_type_rank(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return 3;
        default:
            return 4;
    }
}

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
    return text;
}

constexpr const char* kUsableDevice =
    "Vulkan 1.3 with dynamic rendering, synchronization2 and a graphics + compute queue";

// Index of the device the selector names ("" = the best usable device by type).
uint32_t select_device(const std::vector<DeviceInfo>& devices, const std::string& selector) {
    if (selector.empty()) {
        std::optional<uint32_t> best;
        for (const DeviceInfo& device : devices) {
            if (!device.usable) continue;
            if (!best || device_type_rank(device.type) < device_type_rank(devices[*best].type)) best = device.index;
        }
        if (!best) throw DeviceError(std::string("no device with ") + kUsableDevice + " was found");
        return *best;
    }
    const bool numeric = std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); });
    for (const DeviceInfo& device : devices) {
        const bool match = numeric ? std::to_string(device.index) == selector
                                   : lowercase(device.name).find(lowercase(selector)) != std::string::npos;
        if (!match) continue;
        if (!device.usable) {
            throw DeviceError("device selector \"" + selector + "\": device " + device.name + " does not support " +
                              kUsableDevice);
        }
        return device.index;
    }
    throw DeviceError("device selector \"" + selector +
                      "\": no Vulkan device matches (run `penumbra devices` to list them)");
}

// The layer's absence is the caller's to report: the helper only says what is missing.
void require_validation_layer(const VulkanFunctions& vk) {
    if (!layer_available(vk, kValidationLayer)) {
        throw DeviceError(std::string("validation: the layer ") + kValidationLayer +
                          " is not installed (Debian package vulkan-validationlayers)");
    }
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
    VulkanFunctions vk = load_global_functions(loader_instance_proc_addr());
    VkInstance instance = create_bare_instance(vk, nullptr, {}, {});
    std::vector<DeviceInfo> result;
    try {
        load_instance_functions(vk, instance);
        const auto devices = enumerate_physical_devices(vk, instance);
        for (uint32_t i = 0; i < devices.size(); ++i) result.push_back(describe_physical_device(vk, devices[i], i));
    } catch (...) {
        vk.vkDestroyInstance(instance, nullptr);
        throw;
    }
    vk.vkDestroyInstance(instance, nullptr);
    if (result.empty()) throw DeviceError("no Vulkan device found");
    return result;
}

Context::Context(const ContextOptions& options)
    : validation_log_(options.log ? options.log : std::make_shared<ValidationLog>()),
      on_message_(options.on_message),
      presentation_(options.presentation) {
    try {
        vk_ = load_global_functions(loader_instance_proc_addr());
        create_instance(options.validation, options.best_practices);
        const uint32_t index = pick_physical_device(options.device_selector);
        if (presentation_) pick_present_queue_family();
        if (options.async_compute) pick_async_compute_family();
        const EnabledFeatures features = create_device();
        VkQueue queue = VK_NULL_HANDLE;
        vk_.vkGetDeviceQueue(device_, queue_family_, 0, &queue);
        if (compute_family_ != VK_QUEUE_FAMILY_IGNORED)
            vk_.vkGetDeviceQueue(device_, compute_family_, 0, &compute_queue_);
        initialize({instance_, physical_device_, device_, queue, queue_family_}, features, index);
    } catch (...) {
        release();
        throw;
    }
}

Context::~Context() { release(); }

void Context::release() {
    if (device_) {
        vk_.vkDeviceWaitIdle(device_);
        vk_.vkDestroyDevice(device_, nullptr);
        device_ = VK_NULL_HANDLE;
    }
    if (messenger_ && vk_.vkDestroyDebugUtilsMessengerEXT) {
        vk_.vkDestroyDebugUtilsMessengerEXT(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_) vk_.vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
}

void Context::create_instance(bool validation, bool best_practices) {
    std::vector<const char*> extensions;
    if (presentation_) {
        for (const std::string& name : presentation_->instance_extensions) extensions.push_back(name.c_str());
    }
    if (!validation) {
        instance_ = create_bare_instance(vk_, nullptr, {}, extensions);
        load_instance_functions(vk_, instance_);
        return;
    }
    require_validation_layer(vk_);
    // Synchronization validation finds missing or wrong barriers (hazards), which the
    // default validation does not check.
    // Best practices (optional) warns of valid but wasteful use: small allocations,
    // redundant barriers, clears that could be load operations.
    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT,
                                                    VK_VALIDATION_FEATURE_ENABLE_BEST_PRACTICES_EXT};
    VkDebugUtilsMessengerCreateInfoEXT messenger = messenger_info(this);
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT, &messenger};
    features.enabledValidationFeatureCount = best_practices ? 2 : 1;
    features.pEnabledValidationFeatures = enables;
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    instance_ = create_bare_instance(vk_, &features, {kValidationLayer}, extensions);
    load_instance_functions(vk_, instance_);
    PENUMBRA_VK_CHECK(vk_.vkCreateDebugUtilsMessengerEXT(instance_, &messenger, nullptr, &messenger_));
    validation_enabled_ = true;
}

uint32_t Context::pick_physical_device(const std::string& selector) {
    const auto devices = enumerate_physical_devices(vk_, instance_);
    if (devices.empty()) throw DeviceError("no Vulkan device found");
    std::vector<DeviceInfo> infos;
    for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe_physical_device(vk_, devices[i], i));
    const uint32_t chosen = select_device(infos, selector);
    physical_device_ = devices[chosen];
    find_graphics_compute_family(vk_, physical_device_, queue_family_);
    return chosen;
}

// A window needs a graphics queue that can also present, and VK_KHR_swapchain.
void Context::pick_present_queue_family() {
    const std::string name = describe_physical_device(vk_, physical_device_, 0).name;
    uint32_t count = 0;
    vk_.vkEnumerateDeviceExtensionProperties(physical_device_, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vk_.vkEnumerateDeviceExtensionProperties(physical_device_, nullptr, &count, extensions.data());
    const bool has_swapchain = std::any_of(extensions.begin(), extensions.end(), [](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, VK_KHR_SWAPCHAIN_EXTENSION_NAME) == 0;
    });
    if (!has_swapchain) throw DeviceError("device " + name + " does not support " VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    const std::vector<VkQueueFamilyProperties> families = queue_families(vk_, physical_device_);
    constexpr VkQueueFlags kWanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (uint32_t family = 0; family < families.size(); ++family) {
        if ((families[family].queueFlags & kWanted) == kWanted &&
            (!presentation_->can_present || presentation_->can_present(instance_, physical_device_, family))) {
            queue_family_ = family;
            return;
        }
    }
    throw DeviceError("device " + name + " has no graphics queue that can present to the window");
}

// The queues that run beside graphics work: a family with compute and without graphics.
void Context::pick_async_compute_family() {
    const std::vector<VkQueueFamilyProperties> families = queue_families(vk_, physical_device_);
    for (uint32_t family = 0; family < families.size(); ++family) {
        const VkQueueFlags flags = families[family].queueFlags;
        if ((flags & VK_QUEUE_COMPUTE_BIT) != 0 && (flags & VK_QUEUE_GRAPHICS_BIT) == 0) {
            compute_family_ = family;
            return;
        }
    }
}

// Exactly the features Penumbra uses (docs/library.md): the required Vulkan 1.3 ones, and
// every optional one the device supports.
EnabledFeatures Context::create_device() {
    VkPhysicalDeviceVulkan12Features supported12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan11Features supported11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &supported12};
    VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &supported11};
    vk_.vkGetPhysicalDeviceFeatures2(physical_device_, &supported);
    EnabledFeatures enabled;
    enabled.multiview = supported11.multiview == VK_TRUE;
    enabled.depth_clamp = supported.features.depthClamp == VK_TRUE;
    enabled.depth_bias_clamp = supported.features.depthBiasClamp == VK_TRUE;
    enabled.gpu_driven = supported.features.multiDrawIndirect == VK_TRUE &&
                         supported.features.drawIndirectFirstInstance == VK_TRUE &&
                         supported12.drawIndirectCount == VK_TRUE && supported12.shaderOutputLayer == VK_TRUE;
    enabled.virtual_pages = enabled.gpu_driven && supported.features.multiViewport == VK_TRUE &&
                            supported12.shaderOutputViewportIndex == VK_TRUE;

    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.dynamicRendering = VK_TRUE;
    features13.synchronization2 = VK_TRUE;
    VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &features13};
    features12.drawIndirectCount = enabled.gpu_driven ? VK_TRUE : VK_FALSE;
    features12.shaderOutputLayer = enabled.gpu_driven ? VK_TRUE : VK_FALSE;
    features12.shaderOutputViewportIndex = enabled.virtual_pages ? VK_TRUE : VK_FALSE;
    VkPhysicalDeviceVulkan11Features features11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &features12};
    features11.multiview = enabled.multiview ? VK_TRUE : VK_FALSE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features11};
    features.features.depthClamp = enabled.depth_clamp ? VK_TRUE : VK_FALSE;
    features.features.depthBiasClamp = enabled.depth_bias_clamp ? VK_TRUE : VK_FALSE;
    features.features.multiDrawIndirect = enabled.gpu_driven ? VK_TRUE : VK_FALSE;
    features.features.drawIndirectFirstInstance = enabled.gpu_driven ? VK_TRUE : VK_FALSE;
    features.features.multiViewport = enabled.virtual_pages ? VK_TRUE : VK_FALSE;

    const float priority = 1.0f;
    std::array<VkDeviceQueueCreateInfo, 2> queue_infos{};
    for (VkDeviceQueueCreateInfo& queue_info : queue_infos) {
        queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
    }
    queue_infos[0].queueFamilyIndex = queue_family_;
    queue_infos[1].queueFamilyIndex = compute_family_;
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
    info.queueCreateInfoCount = compute_family_ != VK_QUEUE_FAMILY_IGNORED ? 2u : 1u;
    info.pQueueCreateInfos = queue_infos.data();
    const char* swapchain_extension = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    if (presentation_) {
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = &swapchain_extension;
    }
    PENUMBRA_VK_CHECK(vk_.vkCreateDevice(physical_device_, &info, nullptr, &device_));
    load_device_functions(vk_, device_);
    return enabled;
}

void Context::report_validation_message(std::string message) const {
    if (on_message_) on_message_(message);
    validation_log_->messages.push_back(std::move(message));
}

}  // namespace penumbra::gpu
