#include "library_fixture.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "analytic_shadow.hpp"

namespace penumbra::library_tests {

glm::mat4 to_glm(const Mat4& m) { return glm::make_mat4(m.m.data()); }

Mat4 to_mat4(const glm::mat4& m) {
    Mat4 result;
    std::memcpy(result.m.data(), glm::value_ptr(m), sizeof(result.m));
    return result;
}

Mat4 translation(const glm::vec3& offset) {
    Mat4 m;
    m(0, 3) = offset.x;
    m(1, 3) = offset.y;
    m(2, 3) = offset.z;
    return m;
}

void vk_check(VkResult result, const char* call) {
    if (result != VK_SUCCESS) throw std::runtime_error(std::string(call) + " failed: " + std::to_string(result));
}

namespace {

uint32_t memory_type(VkPhysicalDevice physical_device, uint32_t bits, VkMemoryPropertyFlags wanted) {
    VkPhysicalDeviceMemoryProperties properties;
    vkGetPhysicalDeviceMemoryProperties(physical_device, &properties);
    for (uint32_t i = 0; i < properties.memoryTypeCount; ++i) {
        if ((bits & (1u << i)) && (properties.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    }
    throw std::runtime_error("no memory type for the test's resources");
}

VkDeviceMemory allocate(const DeviceDesc& desc, const VkMemoryRequirements& requirements,
                        VkMemoryPropertyFlags properties) {
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = requirements.size;
    info.memoryTypeIndex = memory_type(desc.physical_device, requirements.memoryTypeBits, properties);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    TEST_VK(vkAllocateMemory(desc.device, &info, nullptr, &memory));
    return memory;
}

void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, uint32_t layers, VkImageLayout from,
                   VkImageLayout to, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                   VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
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
    barrier.subresourceRange = {aspect, 0, 1, 0, layers};
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

void add_quad(MeshArrays& mesh, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c, d});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

}  // namespace

void host_read_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access) {
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = src_stage;
    barrier.srcAccessMask = src_access;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    barrier.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

HostBuffer::HostBuffer(const DeviceDesc& desc, VkDeviceSize size, VkBufferUsageFlags usage) : device(desc.device) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    TEST_VK(vkCreateBuffer(device, &info, nullptr, &buffer));
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device, buffer, &requirements);
    memory = allocate(desc, requirements, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    TEST_VK(vkBindBufferMemory(device, buffer, memory, 0));
    TEST_VK(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped));
}

HostBuffer::~HostBuffer() {
    vkDestroyBuffer(device, buffer, nullptr);
    vkFreeMemory(device, memory, nullptr);
}

TestImage::TestImage(const DeviceDesc& desc, VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage,
                     VkImageAspectFlags aspect, std::optional<uint32_t> layers)
    : device(desc.device) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = layers.value_or(1);
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    TEST_VK(vkCreateImage(device, &info, nullptr, &image));
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device, image, &requirements);
    memory = allocate(desc, requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    TEST_VK(vkBindImageMemory(device, image, memory, 0));
    VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view_info.image = image;
    view_info.viewType = layers ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
    view_info.format = format;
    view_info.subresourceRange = {aspect, 0, 1, 0, info.arrayLayers};
    TEST_VK(vkCreateImageView(device, &view_info, nullptr, &view));
}

TestImage::~TestImage() {
    vkDestroyImageView(device, view, nullptr);
    vkDestroyImage(device, image, nullptr);
    vkFreeMemory(device, memory, nullptr);
}

MeshArrays box_mesh() {
    MeshArrays mesh;
    // Each face counter-clockwise seen from outside (its normal by the right-hand rule).
    add_quad(mesh, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1});      // +Z
    add_quad(mesh, {1, -1, -1}, {-1, -1, -1}, {-1, 1, -1}, {1, 1, -1});  // -Z
    add_quad(mesh, {1, -1, 1}, {1, -1, -1}, {1, 1, -1}, {1, 1, 1});      // +X
    add_quad(mesh, {-1, -1, -1}, {-1, -1, 1}, {-1, 1, 1}, {-1, 1, -1});  // -X
    add_quad(mesh, {-1, 1, 1}, {1, 1, 1}, {1, 1, -1}, {-1, 1, -1});      // +Y
    add_quad(mesh, {-1, -1, -1}, {1, -1, -1}, {1, -1, 1}, {-1, -1, 1});  // -Y
    return mesh;
}

MeshArrays ground_mesh() {
    MeshArrays mesh;
    add_quad(mesh, {-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20});
    return mesh;
}

MeshArrays quad_mesh(bool facing_up) {
    MeshArrays mesh;
    if (facing_up) {
        add_quad(mesh, {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});
    } else {
        add_quad(mesh, {-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1});
    }
    return mesh;
}

InstanceId add_scene(ShadowSystem& shadows, const MeshArrays& box, const MeshArrays& ground) {
    const MeshId ground_mesh_id = shadows.add_mesh(ground.data());
    const MeshId box_mesh_id = shadows.add_mesh(box.data());
    shadows.add_instance({ground_mesh_id, Mat4{}});
    const LightDesc sun{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}};
    shadows.set_lights({&sun, 1});
    return shadows.add_instance({box_mesh_id, translation(kBoxCentre)});
}

BoxesAndMover add_ground_and_box_mesh(ShadowSystem& shadows) {
    BoxesAndMover scene;
    const MeshId ground_id = shadows.add_mesh(scene.ground.data());
    scene.box_id = shadows.add_mesh(scene.box.data());
    shadows.add_instance({ground_id, Mat4{}});
    return scene;
}

BoxesAndMover add_box_row_and_mover(ShadowSystem& shadows) {
    BoxesAndMover scene = add_ground_and_box_mesh(shadows);
    for (int i = 0; i < 5; ++i) {
        const glm::vec3 at(-4.0f + 3.0f * static_cast<float>(i), 1.0f + 0.5f * static_cast<float>(i % 2), -2.0f);
        scene.statics.push_back(shadows.add_instance({scene.box_id, translation(at)}));
    }
    scene.mover =
        shadows.add_instance({scene.box_id, translation({0.0f, 2.0f, 2.0f}), kInstanceCastsShadows | kInstanceDynamic});
    return scene;
}

void LibraryTest::SetUp() {
    VulkanContextOptions options;
    options.validation = true;
    options.best_practices = best_practices();
    options.async_compute = async_compute();
    log_ = options.validation_log;
    context_ = std::make_unique<VulkanContext>(options);
    device_ = context_->device_desc();
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.queueFamilyIndex = device_.queue_family;
    TEST_VK(vkCreateCommandPool(device_.device, &pool_info, nullptr, &pool_));
    depth_ = std::make_unique<TestImage>(device_, VK_FORMAT_D32_SFLOAT, kScreen, kScreen,
                                         VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                         VK_IMAGE_ASPECT_DEPTH_BIT);
}

void LibraryTest::TearDown() {
    if (context_) vkDeviceWaitIdle(device_.device);
    depth_.reset();
    if (pool_) vkDestroyCommandPool(device_.device, pool_, nullptr);
    context_.reset();
    for (const std::string& message : log_->messages) ADD_FAILURE() << "validation: " << message;
}

Settings LibraryTest::test_settings() {
    Settings settings;  // the default cascades (4 x 2048 x 2048)
    settings.local_shadows.resolution = 512;
    return settings;
}

ShadowSystemDesc LibraryTest::system_desc(const Settings& settings, uint32_t frames_in_flight) const {
    ShadowSystemDesc desc;
    desc.device = device_;
    desc.settings = settings;
    desc.frames_in_flight = frames_in_flight;
    return desc;
}

void LibraryTest::submit(const std::function<void(VkCommandBuffer)>& record) const {
    const VkCommandBuffer cmd =
        submit_on(device_.queue, pool_, VK_NULL_HANDLE, VK_PIPELINE_STAGE_2_NONE, VK_NULL_HANDLE, record);
    TEST_VK(vkQueueWaitIdle(device_.queue));
    vkFreeCommandBuffers(device_.device, pool_, 1, &cmd);
}

VkCommandBuffer LibraryTest::record_commands(VkCommandPool pool,
                                             const std::function<void(VkCommandBuffer)>& record) const {
    VkCommandBufferAllocateInfo allocate_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate_info.commandPool = pool;
    allocate_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate_info.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    TEST_VK(vkAllocateCommandBuffers(device_.device, &allocate_info, &cmd));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    TEST_VK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    TEST_VK(vkEndCommandBuffer(cmd));
    return cmd;
}

VkCommandBuffer LibraryTest::submit_on(VkQueue queue, VkCommandPool pool, VkSemaphore wait,
                                       VkPipelineStageFlags2 wait_stage, VkSemaphore signal,
                                       const std::function<void(VkCommandBuffer)>& record) const {
    const VkCommandBuffer cmd = record_commands(pool, record);
    VkCommandBufferSubmitInfo command{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    command.commandBuffer = cmd;
    VkSemaphoreSubmitInfo wait_info{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait_info.semaphore = wait;
    wait_info.stageMask = wait_stage;
    VkSemaphoreSubmitInfo signal_info{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signal_info.semaphore = signal;
    signal_info.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkSubmitInfo2 submit_info{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit_info.waitSemaphoreInfoCount = wait ? 1u : 0u;
    submit_info.pWaitSemaphoreInfos = &wait_info;
    submit_info.commandBufferInfoCount = 1;
    submit_info.pCommandBufferInfos = &command;
    submit_info.signalSemaphoreInfoCount = signal ? 1u : 0u;
    submit_info.pSignalSemaphoreInfos = &signal_info;
    TEST_VK(vkQueueSubmit2(queue, 1, &submit_info, VK_NULL_HANDLE));
    return cmd;
}

ViewDesc LibraryTest::top_down_view() { return top_down_view_at(0.0f, 0.0f); }

ViewDesc LibraryTest::top_down_view_at(float x, float z) {
    return look_at_view({x, kCameraHeight, z}, {x, 0.0f, z}, {0.0f, 0.0f, -1.0f}, glm::radians(60.0f), 0.1f, 100.0f,
                        kScreen, kScreen);
}

size_t differing_pixels(const VisibilityImage2D& a, const VisibilityImage2D& b) {
    size_t differ = 0;
    for (size_t i = 0; i < a.values.size(); ++i) differ += a.values[i] != b.values[i] ? 1 : 0;
    return differ;
}

size_t shadowed_pixels(const VisibilityImage2D& image) {
    return static_cast<size_t>(
        std::count_if(image.values.begin(), image.values.end(), [](float v) { return v < 0.5f; }));
}

glm::mat4 view_projection_of(const ViewDesc& view) { return to_glm(reverse_z_projection(view)) * to_glm(view.view); }

glm::vec3 LibraryTest::ground_point(uint32_t x, uint32_t y) {
    // Right is +X and the top of the image is -Z (up vector -Z); 60 degrees each way.
    const float half = kCameraHeight * std::tan(glm::radians(30.0f));
    const float u = 2.0f * (static_cast<float>(x) + 0.5f) / kScreen - 1.0f;
    const float v = 2.0f * (static_cast<float>(y) + 0.5f) / kScreen - 1.0f;
    return {u * half, 0.0f, v * half};
}

void LibraryTest::record_ground_visibility(VkCommandBuffer cmd, ShadowSystem& shadows, const TestImage* normals,
                                           NormalEncoding encoding, const TestImage* face_normals) {
    shadows.record_visibility(cmd, record_ground_depth(cmd, top_down_view(), normals, encoding, face_normals));
}

ScreenInputs LibraryTest::depth_screen(const glm::mat4& view_projection) const {
    ScreenInputs screen;
    screen.depth = depth_->view;
    screen.width = kScreen;
    screen.height = kScreen;
    screen.view_projection = to_mat4(view_projection);
    screen.background_depth = 0.0f;
    return screen;
}

ScreenInputs LibraryTest::record_ground_depth(VkCommandBuffer cmd, const ViewDesc& view, const TestImage* normals,
                                              NormalEncoding encoding, const TestImage* face_normals) {
    const glm::mat4 view_projection = to_glm(reverse_z_projection(view)) * to_glm(view.view);
    const glm::vec4 clip = view_projection * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    // Every pixel at the ground's depth: the plane y = 0 is parallel to the image plane.
    const VkClearDepthStencilValue ground{clip.z / clip.w, 0};
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
    image_barrier(cmd, depth_->image, VK_IMAGE_ASPECT_DEPTH_BIT, 1, VK_IMAGE_LAYOUT_UNDEFINED,
                  VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_NONE,
                  VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    vkCmdClearDepthStencilImage(cmd, depth_->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &ground, 1, &range);
    image_barrier(cmd, depth_->image, VK_IMAGE_ASPECT_DEPTH_BIT, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);
    ScreenInputs screen = depth_screen(view_projection);
    if (normals) {
        screen.normals = normals->view;
        screen.normal_encoding = encoding;
    }
    if (face_normals) screen.face_normals = face_normals->view;
    return screen;
}

ScreenInputs LibraryTest::record_depth_image(VkCommandBuffer cmd, const ViewDesc& view,
                                             const std::vector<float>& depths, const HostBuffer& staging) {
    EXPECT_EQ(depths.size(), size_t{kScreen} * kScreen);
    std::memcpy(staging.mapped, depths.data(), depths.size() * sizeof(float));
    image_barrier(cmd, depth_->image, VK_IMAGE_ASPECT_DEPTH_BIT, 1, VK_IMAGE_LAYOUT_UNDEFINED,
                  VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_NONE,
                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
    region.imageExtent = {kScreen, kScreen, 1};
    vkCmdCopyBufferToImage(cmd, staging.buffer, depth_->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    image_barrier(cmd, depth_->image, VK_IMAGE_ASPECT_DEPTH_BIT, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);
    return depth_screen(to_glm(reverse_z_projection(view)) * to_glm(view.view));
}

void LibraryTest::expect_box_shadow_of_the_sun(const VisibilityImage2D& image) {
    const FootprintCheck check = check_footprint(image, kBoxCentre, kSunDirection, 0.3f);
    EXPECT_GT(check.shadowed, 500u);
    EXPECT_EQ(check.wrong, 0u);
}

VisibilityImage2D LibraryTest::render_visibility(ShadowSystem& shadows, uint32_t slot, const TestImage* normals,
                                                 NormalEncoding encoding, const TestImage* face_normals) {
    shadows.prepare(top_down_view());
    submit([&](VkCommandBuffer cmd) {
        const ScreenInputs screen = record_ground_depth(cmd, top_down_view(), normals, encoding, face_normals);
        shadows.record_page_marking(cmd, screen);
        shadows.record_shadow_maps(cmd);
        shadows.record_visibility(cmd, screen);
    });
    return read_visibility(shadows, slot);
}

VisibilityImage2D LibraryTest::render_visibility_from(ShadowSystem& shadows, const ViewDesc& view, uint32_t slot) {
    shadows.prepare(view);
    submit([&](VkCommandBuffer cmd) {
        const ScreenInputs screen = record_ground_depth(cmd, view, nullptr, NormalEncoding::SignedFloat, nullptr);
        shadows.record_page_marking(cmd, screen);
        shadows.record_shadow_maps(cmd);
        shadows.record_visibility(cmd, screen);
    });
    return read_visibility(shadows, slot);
}

VisibilityImage2D LibraryTest::read_visibility(const ShadowSystem& shadows, uint32_t slot, uint32_t view) {
    const VisibilityImage visibility = shadows.visibility_image(view);
    EXPECT_LT(slot, visibility.slots);
    HostBuffer readback(device_, VkDeviceSize{visibility.width} * visibility.height * 4,
                        VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    submit([&](VkCommandBuffer cmd) {
        // The contract: SHADER_READ_ONLY, its compute writes visible to shader reads, which
        // this barrier chains from; returned to that layout after.
        image_barrier(cmd, visibility.image, VK_IMAGE_ASPECT_COLOR_BIT, visibility.layers,
                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, slot / 4, 1};
        region.imageExtent = {visibility.width, visibility.height, 1};
        vkCmdCopyImageToBuffer(cmd, visibility.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1,
                               &region);
        image_barrier(cmd, visibility.image, VK_IMAGE_ASPECT_COLOR_BIT, visibility.layers,
                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_NONE);
        host_read_barrier(cmd);
    });
    VisibilityImage2D result{visibility.width, visibility.height, {}};
    const auto* rgba = static_cast<const uint8_t*>(readback.mapped);
    result.values.resize(size_t{visibility.width} * visibility.height);
    for (size_t i = 0; i < result.values.size(); ++i) result.values[i] = rgba[4 * i + slot % 4] / 255.0f;
    return result;
}

std::vector<uint8_t> LibraryTest::read_map(const MapImage& map) {
    uint32_t texel_bytes = 4;  // D32_SFLOAT
    if (map.format == VK_FORMAT_R32G32_SFLOAT || map.format == VK_FORMAT_R16G16B16A16_UNORM) texel_bytes = 8;
    if (map.format == VK_FORMAT_R32G32B32A32_SFLOAT) texel_bytes = 16;
    const VkDeviceSize layer_texels = VkDeviceSize{map.resolution} * map.resolution;
    HostBuffer readback(device_, layer_texels * map.layers * texel_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    submit([&](VkCommandBuffer cmd) {
        // The contract: SHADER_READ_ONLY with the writes visible to fragment and compute
        // shader reads; chained from those stages, returned to that layout after.
        const VkPipelineStageFlags2 shader_stages =
            VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
        image_barrier(cmd, map.image, map.aspect, map.layers, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, shader_stages, VK_ACCESS_2_NONE,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {map.aspect, 0, 0, map.layers};
        region.imageExtent = {map.resolution, map.resolution, 1};
        vkCmdCopyImageToBuffer(cmd, map.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1, &region);
        image_barrier(cmd, map.image, map.aspect, map.layers, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                      shader_stages, VK_ACCESS_2_NONE);
        host_read_barrier(cmd);
    });
    std::vector<uint8_t> bytes(layer_texels * map.layers * texel_bytes);
    std::memcpy(bytes.data(), readback.mapped, bytes.size());
    return bytes;
}

std::vector<float> LibraryTest::read_cascade_depths(const ShadowSystem& shadows) {
    const std::vector<uint8_t> bytes = read_map(shadows.shadow_maps().cascades);
    std::vector<float> depths(bytes.size() / sizeof(float));
    std::memcpy(depths.data(), bytes.data(), depths.size() * sizeof(float));
    return depths;
}

FootprintCheck LibraryTest::check_footprint(const VisibilityImage2D& image, const glm::vec3& centre,
                                            const glm::vec3& direction, float edge_band,
                                            std::optional<glm::vec3> light_position) {
    const testing::Box box{centre - glm::vec3(1.0f), centre + glm::vec3(1.0f)};
    const std::vector<glm::vec2> polygon = light_position ? testing::point_light_shadow_polygon(box, *light_position)
                                                          : testing::shadow_polygon(box, glm::normalize(direction));
    FootprintCheck check;
    size_t intersection = 0, union_count = 0;
    for (uint32_t y = 0; y < image.height; ++y) {
        for (uint32_t x = 0; x < image.width; ++x) {
            const glm::vec3 point = ground_point(x, y);
            const glm::vec2 ground(point.x, point.z);
            const bool shadowed = testing::inside_convex_polygon(polygon, ground);
            const float value = image.at(x, y);
            intersection += shadowed && value < 0.5f;
            union_count += shadowed || value < 0.5f;
            if (testing::distance_to_polygon_edge(polygon, ground) < edge_band) continue;
            ++check.judged;
            check.shadowed += shadowed;
            check.wrong += value != (shadowed ? 0.0f : 1.0f);
        }
    }
    check.iou = union_count ? static_cast<double>(intersection) / static_cast<double>(union_count) : 0.0;
    return check;
}

}  // namespace penumbra::library_tests
