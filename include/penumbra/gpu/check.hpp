#pragma once
// Checked Vulkan calls. PENUMBRA_VK_CHECK(expr) throws VulkanError naming the failing
// expression, the file and line, and the VkResult's name. Calls whose non-success
// results are expected (timeouts, VK_INCOMPLETE) are handled at the call site instead.
#include <vulkan/vulkan.h>

#include <string>

#include "penumbra/errors.hpp"

namespace penumbra::gpu {

const char* result_name(VkResult result);
// The name of a core format ("VK_FORMAT_R8G8B8A8_UINT"), or "VkFormat <number>" for any
// other value: for messages.
std::string format_name(VkFormat format);

[[noreturn]] void throw_vk_failure(const char* expression, VkResult result, const char* file, int line);

}  // namespace penumbra::gpu

#define PENUMBRA_VK_CHECK(expression)                                                                \
    do {                                                                                             \
        const VkResult penumbra_vk_result_ = (expression);                                           \
        if (penumbra_vk_result_ != VK_SUCCESS) {                                                     \
            ::penumbra::gpu::throw_vk_failure(#expression, penumbra_vk_result_, __FILE__, __LINE__); \
        }                                                                                            \
    } while (false)
