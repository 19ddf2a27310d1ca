#pragma once
// Tests of the public library API as a caller uses it: only <penumbra/penumbra.hpp> (no
// internal header is on these tests' include path), a VulkanContext with the validation
// layer and synchronization validation (any message fails the test), the caller's own
// command buffers, buffers and images, and the scene of the examples: a 2 m box floating
// at (0, 3, 0) over a 40 x 40 m ground plane.
//
// Screen-space visibility is resolved from a depth image cleared to the ground plane's
// depth under a camera looking straight down, so every pixel's ground point, and so its
// analytic answer, is known without rendering anything of our own.
#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <penumbra/penumbra.hpp>
#include <string>
#include <vector>

namespace penumbra {

// gtest prints a test's parameter with PrintTo, found by argument-dependent lookup: a filter
// by its name rather than as raw bytes in the test log.
inline void PrintTo(ShadowFilter filter, std::ostream* os) { *os << choice_name(kShadowFilterChoices, filter); }

}  // namespace penumbra

namespace penumbra::library_tests {

glm::mat4 to_glm(const Mat4& m);
Mat4 to_mat4(const glm::mat4& m);
Mat4 translation(const glm::vec3& offset);

// Makes writes of `src_stage` (copies by default) visible to the host after the fence.
void host_read_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage = VK_PIPELINE_STAGE_2_COPY_BIT,
                       VkAccessFlags2 src_access = VK_ACCESS_2_TRANSFER_WRITE_BIT);

// Expects `call` to throw exactly `Expected` with a message containing `needle`.
template <typename Expected, typename Call>
void expect_error(Call&& call, const std::string& needle) {
    try {
        call();
        ADD_FAILURE() << "no error; expected one mentioning \"" << needle << "\"";
    } catch (const Expected& error) {
        EXPECT_NE(std::string(error.what()).find(needle), std::string::npos) << error.what();
    } catch (const std::exception& error) {
        ADD_FAILURE() << "an error of another type: " << error.what();
    }
}

// Checks a Vulkan call of the test itself.
void vk_check(VkResult result, const char* call);
#define TEST_VK(call) ::penumbra::library_tests::vk_check((call), #call)

// A host-visible buffer of the test (the caller's buffer in the API's terms).
struct HostBuffer {
    VkDevice device = VK_NULL_HANDLE;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
    HostBuffer(const DeviceDesc& desc, VkDeviceSize size, VkBufferUsageFlags usage);
    ~HostBuffer();
    HostBuffer(const HostBuffer&) = delete;
    HostBuffer& operator=(const HostBuffer&) = delete;
};

// A 2D image with one view of `aspect` (the caller's depth or normal buffer); with
// `layers`, a 2D array image and a 2D array view of every layer.
struct TestImage {
    VkDevice device = VK_NULL_HANDLE;
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    TestImage(const DeviceDesc& desc, VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage,
              VkImageAspectFlags aspect, std::optional<uint32_t> layers = std::nullopt);
    ~TestImage();
    TestImage(const TestImage&) = delete;
    TestImage& operator=(const TestImage&) = delete;
};

// Geometry of the scene as CPU arrays (MeshData spans point into these).
struct MeshArrays {
    std::vector<Vec3> positions;
    std::vector<uint32_t> indices;
    MeshData data() const { return MeshData{positions, indices}; }
};
MeshArrays box_mesh();                 // a 2 m cube centred at the origin, outward (CCW) faces
MeshArrays ground_mesh();              // 40 x 40 m at y = 0, facing +Y
MeshArrays quad_mesh(bool facing_up);  // 2 x 2 m at y = 0, one-sided
inline const glm::vec3 kBoxCentre{0.0f, 3.0f, 0.0f};
inline const glm::vec3 kSunDirection{-0.4f, -1.0f, -0.3f};

// Screen-space visibility of the sun (or another slot) per pixel, 0..1.
struct VisibilityImage2D {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> values;
    float at(uint32_t x, uint32_t y) const { return values[size_t{y} * width + x]; }
};

// The pixels where two visibility images of the same view differ.
size_t differing_pixels(const VisibilityImage2D& a, const VisibilityImage2D& b);
// The pixels in shadow (visibility below 0.5).
size_t shadowed_pixels(const VisibilityImage2D& image);
// A view's reverse-Z view-projection, as its ScreenInputs take it.
glm::mat4 view_projection_of(const ViewDesc& view);

struct FootprintCheck {
    size_t judged = 0;    // pixels away from the analytic shadow's edge
    size_t wrong = 0;     // judged pixels whose visibility is not exactly the analytic answer
    size_t shadowed = 0;  // judged pixels inside the analytic shadow
    double iou = 0.0;     // rendered (< 0.5) against analytic over every pixel
};

class LibraryTest : public ::testing::Test {
protected:
    static constexpr uint32_t kScreen = 160;  // the top-down camera's image, pixels per side
    static constexpr float kCameraHeight = 10.0f;

    void SetUp() override;
    void TearDown() override;  // fails the test on any validation message
    // Whether the validation layer also runs its best-practices checks.
    virtual bool best_practices() const { return false; }
    // Whether the context also makes an async compute queue (DeviceDesc::compute_queue_family),
    // where the device has a compute-only family.
    virtual bool async_compute() const { return false; }

    // The default settings, with 512-texel local maps to stay quick on lavapipe.
    static Settings test_settings();
    ShadowSystemDesc system_desc(const Settings& settings = test_settings(), uint32_t frames_in_flight = 2) const;

    // Records with `record` into a new primary command buffer, submits it and waits.
    void submit(const std::function<void(VkCommandBuffer)>& record) const;
    // Records with `record` into a new primary command buffer of `pool`, for the caller to
    // submit and free.
    VkCommandBuffer record_commands(VkCommandPool pool, const std::function<void(VkCommandBuffer)>& record) const;
    // Records with `record` into a new primary command buffer of `pool` and submits it on
    // `queue`, waiting for `wait` (at `wait_stage`) and signalling `signal` (either may be
    // VK_NULL_HANDLE); returns the buffer, for the caller to free once it has completed.
    VkCommandBuffer submit_on(VkQueue queue, VkCommandPool pool, VkSemaphore wait, VkPipelineStageFlags2 wait_stage,
                              VkSemaphore signal, const std::function<void(VkCommandBuffer)>& record) const;

    // The camera straight down on the ground from kCameraHeight (row 0 towards -Z).
    static ViewDesc top_down_view();
    // The same camera moved sideways, over the ground point (x, 0, z).
    static ViewDesc top_down_view_at(float x, float z);
    // The ground point a pixel of top_down_view() sees.
    static glm::vec3 ground_point(uint32_t x, uint32_t y);

    // One whole frame: prepare, the depth of the ground, record_page_marking (the virtual
    // shadow map's; nothing with cascades), record_shadow_maps, record_visibility (with
    // `normals` when given), then read the visibility image's `slot`.
    VisibilityImage2D render_visibility(ShadowSystem& shadows, uint32_t slot = 0, const TestImage* normals = nullptr,
                                        NormalEncoding encoding = NormalEncoding::SignedFloat,
                                        const TestImage* face_normals = nullptr);
    // The same frame seen by `view`, a top-down view (top_down_view() moved sideways: the
    // ground's depth is the same at every pixel).
    VisibilityImage2D render_visibility_from(ShadowSystem& shadows, const ViewDesc& view, uint32_t slot = 0);
    // Clears depth_ to the ground's depth under the top-down `view` and returns it as the
    // screen inputs, ready for compute reads.
    ScreenInputs record_ground_depth(VkCommandBuffer cmd, const ViewDesc& view, const TestImage* normals,
                                     NormalEncoding encoding, const TestImage* face_normals);
    // depth_ as the screen inputs of a view with `view_projection` (no normals).
    ScreenInputs depth_screen(const glm::mat4& view_projection) const;
    // Copies `depths` (kScreen x kScreen reverse-Z values, row 0 first) from `staging` into
    // depth_ and returns it as the screen inputs of `view`, ready for compute reads.
    ScreenInputs record_depth_image(VkCommandBuffer cmd, const ViewDesc& view, const std::vector<float>& depths,
                                    const HostBuffer& staging);
    // Records the ground depth (cleared) into depth_ and hands it to record_visibility.
    void record_ground_visibility(VkCommandBuffer cmd, ShadowSystem& shadows, const TestImage* normals,
                                  NormalEncoding encoding, const TestImage* face_normals = nullptr);
    // Copies the visibility image's layer holding `slot` (of `view`'s image) and extracts its channel.
    VisibilityImage2D read_visibility(const ShadowSystem& shadows, uint32_t slot, uint32_t view = 0);
    // Every layer of the cascades' depth map after the last recorded frame, as floats.
    std::vector<float> read_cascade_depths(const ShadowSystem& shadows);
    // Every layer of a map (depth, or moments: RG32F, RGBA32F, RGBA16) as its bytes.
    std::vector<uint8_t> read_map(const MapImage& map);

    // The scene's sun shadow of the box in `image`: check_footprint() with a 0.3 m edge
    // band finds more than 500 shadowed pixels and no wrong one.
    static void expect_box_shadow_of_the_sun(const VisibilityImage2D& image);

    // Compares visibility with the box at `centre` casting along `direction` (a sun), or
    // from `light_position` (a point light) when given. Pixels within `edge_band` metres of
    // the analytic shadow's edge are not judged.
    static FootprintCheck check_footprint(const VisibilityImage2D& image, const glm::vec3& centre,
                                          const glm::vec3& direction, float edge_band,
                                          std::optional<glm::vec3> light_position = std::nullopt);

    std::unique_ptr<VulkanContext> context_;
    std::shared_ptr<ValidationLog> log_;
    DeviceDesc device_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::unique_ptr<TestImage> depth_;
};

// The scene of the examples into `shadows`: the ground and the box; returns the box.
InstanceId add_scene(ShadowSystem& shadows, const MeshArrays& box, const MeshArrays& ground);

// Static boxes over the ground and one box that moves every frame: the cache and layered
// strategy tests' scenes (each test places its own).
struct BoxesAndMover {
    MeshArrays box = box_mesh();
    MeshArrays ground = ground_mesh();
    MeshId box_id;
    std::vector<InstanceId> statics;
    InstanceId mover;
};

// Adds the ground (mesh and instance) and the box mesh; the caller places the boxes.
BoxesAndMover add_ground_and_box_mesh(ShadowSystem& shadows);
// The ground, five static boxes in a row across it (z = -2, alternating heights) and a
// dynamic box at (0, 2, 2); no light.
BoxesAndMover add_box_row_and_mover(ShadowSystem& shadows);

}  // namespace penumbra::library_tests
