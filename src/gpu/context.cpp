#include "gpu/context.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <optional>

#include "gpu/check.hpp"
#include "penumbra/errors.hpp"

namespace penumbra::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                     void* user_data) {
    auto* log = static_cast<ValidationLog*>(user_data);
    const bool is_error = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0;
    std::string message = std::string(is_error ? "validation error: " : "validation warning: ") +
                          (data->pMessage ? data->pMessage : "(no message)");
    std::fprintf(stderr, "penumbra: %s\n", message.c_str());
    log->messages.push_back(std::move(message));
    return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(ValidationLog* log) {
    VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = on_validation_message;
    info.pUserData = log;
    return info;
}

bool layer_available(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(),
                       [name](const VkLayerProperties& layer) { return std::strcmp(layer.layerName, name) == 0; });
}

VkInstance create_bare_instance(const void* next, const std::vector<const char*>& layers,
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
    const VkResult result = vkCreateInstance(&info, nullptr, &instance);
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

std::vector<VkPhysicalDevice> enumerate_physical_devices(VkInstance instance) {
    uint32_t count = 0;
    PENUMBRA_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    PENUMBRA_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    return devices;
}

std::optional<uint32_t> graphics_queue_family(VkPhysicalDevice device) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    for (uint32_t i = 0; i < count; ++i) {
        if (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) return i;
    }
    return std::nullopt;
}

DeviceInfo describe_device(VkPhysicalDevice device, uint32_t index) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
    vkGetPhysicalDeviceProperties2(device, &properties);
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features13};
    if (properties.properties.apiVersion >= VK_API_VERSION_1_3) vkGetPhysicalDeviceFeatures2(device, &features);

    DeviceInfo info;
    info.index = index;
    info.name = properties.properties.deviceName;
    info.type = properties.properties.deviceType;
    info.driver = std::string(driver.driverName) + " (" + driver.driverInfo + ")";
    info.api_version = properties.properties.apiVersion;
    info.usable = properties.properties.apiVersion >= VK_API_VERSION_1_3 && features13.dynamicRendering &&
                  features13.synchronization2 && graphics_queue_family(device).has_value();
    return info;
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

// Index of the device the selector names ("" = the best usable device by type).
uint32_t select_device(const std::vector<DeviceInfo>& devices, const std::string& selector) {
    if (selector.empty()) {
        std::optional<uint32_t> best;
        for (const DeviceInfo& device : devices) {
            if (!device.usable) continue;
            if (!best || device_type_rank(device.type) < device_type_rank(devices[*best].type)) best = device.index;
        }
        if (!best) throw DeviceError("no Vulkan 1.3 device with dynamic rendering and synchronization2 was found");
        return *best;
    }
    const bool numeric = std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); });
    for (const DeviceInfo& device : devices) {
        const bool match = numeric ? std::to_string(device.index) == selector
                                   : lowercase(device.name).find(lowercase(selector)) != std::string::npos;
        if (!match) continue;
        if (!device.usable) {
            throw DeviceError("--device " + selector + ": device " + device.name +
                              " does not support Vulkan 1.3 with dynamic rendering and synchronization2");
        }
        return device.index;
    }
    throw DeviceError("--device " + selector + ": no Vulkan device matches (run `penumbra devices` to list them)");
}

}  // namespace

const char* device_type_name(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return "discrete";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return "integrated";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return "virtual";
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return "cpu";
        default:
            return "other";
    }
}

std::string api_version_string(uint32_t version) {
    return std::to_string(VK_API_VERSION_MAJOR(version)) + "." + std::to_string(VK_API_VERSION_MINOR(version)) + "." +
           std::to_string(VK_API_VERSION_PATCH(version));
}

std::vector<DeviceInfo> list_devices() {
    VkInstance instance = create_bare_instance(nullptr, {}, {});
    std::vector<DeviceInfo> result;
    try {
        const auto devices = enumerate_physical_devices(instance);
        for (uint32_t i = 0; i < devices.size(); ++i) result.push_back(describe_device(devices[i], i));
    } catch (...) {
        vkDestroyInstance(instance, nullptr);
        throw;
    }
    vkDestroyInstance(instance, nullptr);
    if (result.empty()) throw DeviceError("no Vulkan device found");
    return result;
}

Context::Context(const ContextOptions& options)
    : validation_log_(options.log ? options.log : std::make_shared<ValidationLog>()),
      presentation_(options.presentation) {
    try {
        create_instance(options.validation);
        pick_physical_device(options.device_selector);
        if (presentation_) pick_present_queue_family();
        create_device();
    } catch (...) {
        release();
        throw;
    }
}

Context::~Context() { release(); }

void Context::release() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        if (command_pool_) vkDestroyCommandPool(device_, command_pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
        device_ = VK_NULL_HANDLE;
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
}

void Context::create_instance(bool validation) {
    std::vector<const char*> extensions;
    if (presentation_) {
        for (const std::string& name : presentation_->instance_extensions) extensions.push_back(name.c_str());
    }
    if (!validation) {
        instance_ = create_bare_instance(nullptr, {}, extensions);
        return;
    }
    if (!layer_available(kValidationLayer)) {
        throw DeviceError(std::string("--validate: the layer ") + kValidationLayer +
                          " is not installed (Debian package vulkan-validationlayers)");
    }
    // Synchronization validation finds missing or wrong barriers (hazards), which the
    // default validation does not check.
    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkDebugUtilsMessengerCreateInfoEXT messenger = messenger_info(validation_log_.get());
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT, &messenger};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    instance_ = create_bare_instance(&features, {kValidationLayer}, extensions);
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    PENUMBRA_VK_CHECK(create(instance_, &messenger, nullptr, &messenger_));
    validation_enabled_ = true;
}

void Context::pick_physical_device(const std::string& selector) {
    const auto devices = enumerate_physical_devices(instance_);
    if (devices.empty()) throw DeviceError("no Vulkan device found");
    std::vector<DeviceInfo> infos;
    for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe_device(devices[i], i));
    const uint32_t chosen = select_device(infos, selector);
    physical_device_ = devices[chosen];
    info_ = infos[chosen];
    vkGetPhysicalDeviceProperties(physical_device_, &properties_);
    queue_family_ = *graphics_queue_family(physical_device_);
}

// A window needs a graphics queue that can also present, and VK_KHR_swapchain.
void Context::pick_present_queue_family() {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(physical_device_, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(physical_device_, nullptr, &count, extensions.data());
    const bool has_swapchain = std::any_of(extensions.begin(), extensions.end(), [](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, VK_KHR_SWAPCHAIN_EXTENSION_NAME) == 0;
    });
    if (!has_swapchain)
        throw DeviceError("device " + info_.name + " does not support " VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &count, families.data());
    for (uint32_t family = 0; family < count; ++family) {
        if ((families[family].queueFlags & VK_QUEUE_GRAPHICS_BIT) &&
            (!presentation_->can_present || presentation_->can_present(instance_, physical_device_, family))) {
            queue_family_ = family;
            return;
        }
    }
    throw DeviceError("device " + info_.name + " has no graphics queue that can present to the window");
}

void Context::create_device() {
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(physical_device_, &supported);
    VkPhysicalDeviceVulkan11Features supported11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceFeatures2 supported2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &supported11};
    vkGetPhysicalDeviceFeatures2(physical_device_, &supported2);
    if (!supported11.multiview) throw DeviceError("device " + info_.name + " does not support multiview");
    depth_clamp_ = supported.depthClamp == VK_TRUE;
    depth_bias_clamp_ = supported.depthBiasClamp == VK_TRUE;
    VkPhysicalDeviceMultiviewProperties multiview{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &multiview};
    vkGetPhysicalDeviceProperties2(physical_device_, &properties);
    max_multiview_views_ = multiview.maxMultiviewViewCount;

    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.dynamicRendering = VK_TRUE;
    features13.synchronization2 = VK_TRUE;
    VkPhysicalDeviceVulkan11Features features11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &features13};
    features11.multiview = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features11};
    features.features.depthClamp = depth_clamp_ ? VK_TRUE : VK_FALSE;
    features.features.depthBiasClamp = depth_bias_clamp_ ? VK_TRUE : VK_FALSE;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue_info;
    const char* swapchain_extension = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    if (presentation_) {
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = &swapchain_extension;
    }
    PENUMBRA_VK_CHECK(vkCreateDevice(physical_device_, &info, nullptr, &device_));
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = queue_family_;
    PENUMBRA_VK_CHECK(vkCreateCommandPool(device_, &pool_info, nullptr, &command_pool_));
}

uint32_t Context::find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags wanted) const {
    VkPhysicalDeviceMemoryProperties memory{};
    vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory);
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        if ((type_bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    }
    throw VulkanError("no memory type with the requested properties", VK_ERROR_OUT_OF_DEVICE_MEMORY);
}

void Context::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const {
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = command_pool_;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(vkAllocateCommandBuffers(device_, &allocate, &cmd));
    struct FreeOnExit {
        VkDevice device;
        VkCommandPool pool;
        VkCommandBuffer cmd;
        ~FreeOnExit() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
    } free_on_exit{device_, command_pool_, cmd};

    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    PENUMBRA_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    PENUMBRA_VK_CHECK(vkEndCommandBuffer(cmd));

    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence_handle = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(vkCreateFence(device_, &fence_info, nullptr, &fence_handle));
    UniqueFence fence(device_, fence_handle);
    VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmd_info.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmd_info;
    PENUMBRA_VK_CHECK(vkQueueSubmit2(queue_, 1, &submit, fence));
    // A fence wait can legitimately time out on a slow CPU device; keep waiting.
    VkResult wait = VK_TIMEOUT;
    while (wait == VK_TIMEOUT) {
        wait = vkWaitForFences(device_, 1, &fence_handle, VK_TRUE, 10'000'000'000ull);
    }
    PENUMBRA_VK_CHECK(wait);
}

}  // namespace penumbra::gpu
