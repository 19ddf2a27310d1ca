#include "example_vulkan.hpp"

#include <png.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace example {
namespace {

std::atomic<uint32_t> validation_messages{0};

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
    std::fprintf(stderr, "validation: %s\n", data->pMessage);
    ++validation_messages;
    return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info() {
    VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = on_message;
    return info;
}

// The first physical device of Vulkan 1.3 with a graphics + compute queue family.
bool pick(VkInstance instance, VkPhysicalDevice& chosen, uint32_t& family) {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance, &count, devices.data());
    for (VkPhysicalDevice device : devices) {
        VkPhysicalDeviceProperties properties{};
        vkGetPhysicalDeviceProperties(device, &properties);
        if (properties.apiVersion < VK_API_VERSION_1_3) continue;
        uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(device, &families, nullptr);
        std::vector<VkQueueFamilyProperties> props(families);
        vkGetPhysicalDeviceQueueFamilyProperties(device, &families, props.data());
        for (uint32_t i = 0; i < families; ++i) {
            if ((props[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
                (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
                chosen = device;
                family = i;
                return true;
            }
        }
    }
    return false;
}

}  // namespace

uint32_t validation_message_count() { return validation_messages; }

void check(VkResult result, const char* call) {
    if (result != VK_SUCCESS) throw std::runtime_error(std::string(call) + " failed: " + std::to_string(result));
}

// A family with compute and without graphics: the queue GPUs run beside graphics work.
uint32_t compute_only_family(VkPhysicalDevice physical_device) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_device, &count, families.data());
    for (uint32_t family = 0; family < count; ++family) {
        const VkQueueFlags flags = families[family].queueFlags;
        if ((flags & VK_QUEUE_COMPUTE_BIT) && !(flags & VK_QUEUE_GRAPHICS_BIT)) return family;
    }
    return VK_QUEUE_FAMILY_IGNORED;
}

Device::Device(bool validation, bool async_compute) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "penumbra example";
    app.apiVersion = VK_API_VERSION_1_3;  // Penumbra needs an instance of Vulkan 1.3
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    const VkValidationFeatureEnableEXT synchronization = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkDebugUtilsMessengerCreateInfoEXT messenger_create = messenger_info();
    VkValidationFeaturesEXT validation_features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT, &messenger_create};
    validation_features.enabledValidationFeatureCount = 1;
    validation_features.pEnabledValidationFeatures = &synchronization;
    if (validation) {
        info.pNext = &validation_features;
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = &layer;
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = &extension;
    }
    EXAMPLE_CHECK(vkCreateInstance(&info, nullptr, &instance));
    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        EXAMPLE_CHECK(create(instance, &messenger_create, nullptr, &messenger));
    }
    if (!pick(instance, physical_device, queue_family)) throw std::runtime_error("no Vulkan 1.3 device");

    // Exactly the features docs/library.md lists as required, and nothing more.
    features13.dynamicRendering = VK_TRUE;
    features13.synchronization2 = VK_TRUE;
    features.pNext = &features13;
    if (async_compute) compute_family = compute_only_family(physical_device);
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_infos[2] = {{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO},
                                              {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO}};
    for (VkDeviceQueueCreateInfo& queue_info : queue_infos) {
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
    }
    queue_infos[0].queueFamilyIndex = queue_family;
    queue_infos[1].queueFamilyIndex = compute_family;
    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
    device_info.queueCreateInfoCount = compute_family != VK_QUEUE_FAMILY_IGNORED ? 2 : 1;
    device_info.pQueueCreateInfos = queue_infos;
    EXAMPLE_CHECK(vkCreateDevice(physical_device, &device_info, nullptr, &device));
    vkGetDeviceQueue(device, queue_family, 0, &queue);
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.queueFamilyIndex = queue_family;
    EXAMPLE_CHECK(vkCreateCommandPool(device, &pool_info, nullptr, &pool));
    if (compute_family != VK_QUEUE_FAMILY_IGNORED) {
        vkGetDeviceQueue(device, compute_family, 0, &compute_queue);
        pool_info.queueFamilyIndex = compute_family;
        EXAMPLE_CHECK(vkCreateCommandPool(device, &pool_info, nullptr, &compute_pool));
    }
}

Device::~Device() {
    vkDeviceWaitIdle(device);
    vkDestroyCommandPool(device, pool, nullptr);
    if (compute_pool) vkDestroyCommandPool(device, compute_pool, nullptr);
    vkDestroyDevice(device, nullptr);
    if (messenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(instance, messenger, nullptr);
    }
    vkDestroyInstance(instance, nullptr);
}

penumbra::DeviceDesc Device::penumbra_desc() const {
    penumbra::DeviceDesc desc;
    desc.instance = instance;
    desc.physical_device = physical_device;
    desc.device = device;
    desc.queue = queue;
    desc.queue_family = queue_family;
    desc.instance_api_version = VK_API_VERSION_1_3;  // what Device() created the instance with
    desc.enabled_features = &features;
    desc.compute_queue_family = compute_family;  // VK_QUEUE_FAMILY_IGNORED without async compute
    desc.compute_queue = compute_queue;
    return desc;
}

uint32_t Device::memory_type(uint32_t bits, VkMemoryPropertyFlags properties) const {
    VkPhysicalDeviceMemoryProperties memory{};
    vkGetPhysicalDeviceMemoryProperties(physical_device, &memory);
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        if ((bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & properties) == properties) return i;
    }
    throw std::runtime_error("no suitable memory type");
}

void Device::submit(const std::function<void(VkCommandBuffer)>& record) const {
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = pool;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    EXAMPLE_CHECK(vkAllocateCommandBuffers(device, &allocate, &cmd));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    EXAMPLE_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    EXAMPLE_CHECK(vkEndCommandBuffer(cmd));
    VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmd_info.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmd_info;
    EXAMPLE_CHECK(vkQueueSubmit2(queue, 1, &submit, VK_NULL_HANDLE));
    EXAMPLE_CHECK(vkQueueWaitIdle(queue));
    vkFreeCommandBuffers(device, pool, 1, &cmd);
}

Buffer::Buffer(const Device& owner, VkDeviceSize size, VkBufferUsageFlags usage, const void* data) : device(&owner) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    EXAMPLE_CHECK(vkCreateBuffer(owner.device, &info, nullptr, &buffer));
    VkMemoryRequirements requirements{};
    vkGetBufferMemoryRequirements(owner.device, buffer, &requirements);
    VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocate.allocationSize = requirements.size;
    // Host-visible and coherent: small buffers written once, or read back.
    allocate.memoryTypeIndex = owner.memory_type(
        requirements.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    EXAMPLE_CHECK(vkAllocateMemory(owner.device, &allocate, nullptr, &memory));
    EXAMPLE_CHECK(vkBindBufferMemory(owner.device, buffer, memory, 0));
    EXAMPLE_CHECK(vkMapMemory(owner.device, memory, 0, VK_WHOLE_SIZE, 0, &mapped));
    if (data) std::memcpy(mapped, data, size);
}

Buffer::~Buffer() {
    vkDestroyBuffer(device->device, buffer, nullptr);
    vkFreeMemory(device->device, memory, nullptr);
}

Image::Image(const Device& owner, VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage,
             VkImageAspectFlags aspect)
    : device(&owner) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    EXAMPLE_CHECK(vkCreateImage(owner.device, &info, nullptr, &image));
    VkMemoryRequirements requirements{};
    vkGetImageMemoryRequirements(owner.device, image, &requirements);
    VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocate.allocationSize = requirements.size;
    allocate.memoryTypeIndex = owner.memory_type(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    EXAMPLE_CHECK(vkAllocateMemory(owner.device, &allocate, nullptr, &memory));
    EXAMPLE_CHECK(vkBindImageMemory(owner.device, image, memory, 0));
    VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view_info.image = image;
    view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view_info.format = format;
    view_info.subresourceRange = {aspect, 0, 1, 0, 1};
    EXAMPLE_CHECK(vkCreateImageView(owner.device, &view_info, nullptr, &view));
}

Image::~Image() {
    vkDestroyImageView(device->device, view, nullptr);
    vkDestroyImage(device->device, image, nullptr);
    vkFreeMemory(device->device, memory, nullptr);
}

void barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
             VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
             VkAccessFlags2 dst_access) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = src_stage;
    barrier.srcAccessMask = src_access;
    barrier.dstStageMask = dst_stage;
    barrier.dstAccessMask = dst_access;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {aspect, 0, 1, 0, 1};
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

void host_read_barrier(VkCommandBuffer cmd) {
    VkMemoryBarrier2 host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    host.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    host.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &host;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

VkShaderModule shader_module(const Device& device, const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = bytes;
    info.pCode = code;
    VkShaderModule module = VK_NULL_HANDLE;
    EXAMPLE_CHECK(vkCreateShaderModule(device.device, &info, nullptr, &module));
    return module;
}

void write_png16(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint16_t>& pixels) {
    FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) throw std::runtime_error("cannot write " + path);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        std::fclose(file);
        throw std::runtime_error("libpng failed writing " + path);
    }
    png_init_io(png, file);
    png_set_IHDR(png, info, width, height, 16, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    png_set_swap(png);  // PNG stores 16-bit samples big-endian
    for (uint32_t y = 0; y < height; ++y) {
        png_write_row(png, reinterpret_cast<png_const_bytep>(pixels.data() + size_t{y} * width));
    }
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
}

}  // namespace example
