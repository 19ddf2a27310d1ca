#include "penumbra/gpu/debug_names.hpp"

#include "penumbra/gpu/check.hpp"

namespace penumbra::gpu {

ObjectNames::ObjectNames(const Device& device, const std::string& purpose)
    : device_(device), previous_(device.object_purpose()) {
    device_.set_object_purpose("penumbra " + purpose);
}

ObjectNames::~ObjectNames() { device_.set_object_purpose(previous_); }

void name_object(const Device& device, VkObjectType type, uint64_t handle, const char* kind) {
    if (!device.debug_names() || handle == 0) return;
    const std::string name = device.object_purpose() + ": " + kind;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name.c_str();
    PENUMBRA_VK_CHECK(device->vkSetDebugUtilsObjectNameEXT(device, &info));
}

CommandLabel::CommandLabel(const Device& device, VkCommandBuffer cmd, const std::string& name)
    : device_(device), cmd_(cmd) {
    if (!device_.debug_names()) return;
    const std::string label = "penumbra " + name;
    VkDebugUtilsLabelEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
    info.pLabelName = label.c_str();
    device_->vkCmdBeginDebugUtilsLabelEXT(cmd_, &info);
}

CommandLabel::~CommandLabel() {
    if (device_.debug_names()) device_->vkCmdEndDebugUtilsLabelEXT(cmd_);
}

}  // namespace penumbra::gpu
