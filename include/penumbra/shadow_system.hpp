#pragma once
// ShadowSystem: shadow maps for the sun (cascades), spot and point lights, on the
// caller's Vulkan device and recorded into the caller's command buffers. The guide with
// the whole contract is docs/library.md; in short, per frame:
//
//   const penumbra::FrameInfo& frame = shadows.prepare(view);   // CPU: fit, cull, budget
//   shadows.record_shadow_maps(cmd);                            // the shadow passes
//   // then either sample in your own forward shaders (#include "penumbra/shadow.glsl",
//   // bind frame.descriptor_set at your set index), or resolve screen-space visibility:
//   shadows.record_visibility(cmd, screen);                     // compute, from your depth
//
// Penumbra records commands and never submits, waits (but in ~ShadowSystem) or presents. It inserts barriers
// for its own images only; the state of the caller's images on entry and exit is part of
// each call's contract below. A ShadowSystem is not thread-safe: call it from one thread
// at a time (separate ShadowSystems may be used from separate threads).
//
// Errors are exceptions (penumbra/errors.hpp): InputError for invalid values, UsageError
// for calls out of order or unknown handles, DeviceError for a device that lacks
// something, VulkanError for a failed Vulkan call. After any of them the ShadowSystem is
// still usable and unchanged by the failed call.
#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "penumbra/device.hpp"
#include "penumbra/lights.hpp"
#include "penumbra/math.hpp"
#include "penumbra/settings.hpp"

namespace penumbra {

// ---------------------------------------------------------------------------- meshes

// Handles are small values; 0 is never a valid handle.
struct MeshId {
    uint32_t value = 0;
    friend bool operator==(MeshId, MeshId) = default;
};
struct InstanceId {
    uint32_t value = 0;
    friend bool operator==(InstanceId, InstanceId) = default;
};

// One vertex attribute in a caller's buffer: `format` at `offset` bytes, every `stride`.
struct VertexStream {
    VkBuffer buffer = VK_NULL_HANDLE;  // created with VK_BUFFER_USAGE_VERTEX_BUFFER_BIT
    VkDeviceSize offset = 0;           // of vertex 0
    uint32_t stride = 0;               // bytes between vertices
    VkFormat format = VK_FORMAT_UNDEFINED;
};

// Alpha-tested casters (glTF alphaMode MASK, foliage): a texel casts where
// alpha_scale * texture alpha >= cutoff. The texture is sampled with the caller's sampler
// at the mesh's UVs, and must be in VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL whenever
// record_shadow_maps() runs.
struct AlphaMaskDesc {
    VkImageView view = VK_NULL_HANDLE;  // a 2D colour view; its alpha channel is read
    VkSampler sampler = VK_NULL_HANDLE;
    float cutoff = 0.5f;       // (0, 1]
    float alpha_scale = 1.0f;  // e.g. the material's base colour alpha factor, [0, 1]
};

// A run of consecutive triangles of a mesh with its own model-space bounds. The virtual
// shadow map culls clusters, not instances, against the pages it draws: a tree or a ground
// tile drawn into a fine level's page then sends only the triangles near that page through
// the rasteriser. build_mesh_clusters() makes them; MeshData meshes get them by themselves.
struct MeshCluster {
    uint32_t first_index = 0;  // into the mesh's indices (from MeshDesc::index_offset), a multiple of 3
    uint32_t index_count = 0;  // a positive multiple of 3
    Bounds bounds;             // must contain the vertices its indices reach
};

// Orders the triangles of `indices` (a triangle list; each triangle keeps its corners and
// winding) so that runs of up to 128 are compact in space, along a Morton curve through their
// centroids, and returns those runs for MeshDesc::clusters. Throws InputError when the list
// is not triangles or an index is not below positions.size(). The shadows are the same with
// or without clusters; only the virtual shadow map's rasterisation gets cheaper.
std::vector<MeshCluster> build_mesh_clusters(std::span<const Vec3> positions, std::span<uint32_t> indices);

// A triangle list in the caller's buffers: nothing is copied. The buffers must stay valid
// until the mesh is removed and the frames that used it are complete.
//   positions: R32G32B32_SFLOAT, R32G32B32A32_SFLOAT, R16G16B16A16_SFLOAT or _SNORM / _UNORM
//              (quantized meshes: put the dequantization into the instance transform)
//   uvs (masked casters only): R32G32_SFLOAT, R16G16_SFLOAT, R16G16_UNORM, R16G16_SNORM
struct MeshDesc {
    VertexStream positions;
    VkBuffer index_buffer = VK_NULL_HANDLE;  // created with VK_BUFFER_USAGE_INDEX_BUFFER_BIT
    VkDeviceSize index_offset = 0;           // bytes
    VkIndexType index_type = VK_INDEX_TYPE_UINT32;
    uint32_t index_count = 0;   // a multiple of 3
    int32_t vertex_offset = 0;  // added to every index (vkCmdDrawIndexed's vertexOffset)
    // Model-space bounds of the vertices the indices reach: Penumbra cannot read GPU
    // buffers and culls with these. Must contain the mesh (a smaller box drops shadows),
    // within kMaxWorldMagnitude.
    Bounds bounds;
    std::optional<VertexStream> uvs;  // required with alpha_mask
    std::optional<AlphaMaskDesc> alpha_mask;
    // Empty, or runs that cover [0, index_count) in order, each with its bounds (copied).
    // Without them the virtual shadow map draws the whole mesh into every page an instance
    // of it reaches.
    std::span<const MeshCluster> clusters;
};

// A triangle list on the CPU that Penumbra uploads into buffers of its own (copied during
// the next record_shadow_maps()). Bounds and clusters are computed from the positions (the
// triangles are reordered as build_mesh_clusters() does).
struct MeshData {
    std::span<const Vec3> positions;    // finite, within kMaxWorldMagnitude
    std::span<const uint32_t> indices;  // a multiple of 3, each < positions.size()
    std::span<const Vec2> uvs;          // empty, or one per position (required with alpha_mask)
    std::optional<AlphaMaskDesc> alpha_mask;
};

// --------------------------------------------------------------------------- instances

enum InstanceFlags : uint32_t {
    kInstanceCastsShadows = 1u << 0,  // drawn into shadow maps; without it the instance only receives
    // Never face-culled in the shadow passes, whatever Settings::shadow.caster_culling says.
    kInstanceDoubleSided = 1u << 1,
    // Alpha-tested with its mesh's AlphaMaskDesc (ignored for meshes without one); without
    // this flag such a mesh casts as opaque.
    kInstanceAlphaMasked = 1u << 2,
    // Moves or changes often: drawn into the sun's cascades every frame over the cached
    // static casters (Settings::shadow.cache_static_casters). Instances are static unless
    // flagged: moving, adding, removing or changing a static instance re-renders the
    // cached texels its old and new bounds cover.
    kInstanceDynamic = 1u << 3,
};
// Every flag above; other bits are an InputError.
inline constexpr uint32_t kInstanceAllFlags =
    kInstanceCastsShadows | kInstanceDoubleSided | kInstanceAlphaMasked | kInstanceDynamic;

struct InstanceDesc {
    MeshId mesh;
    // model -> world; any invertible affine transform (mirroring is fine): bottom row exactly
    // (0, 0, 0, 1), and the mesh's bounds placed within kMaxWorldMagnitude. InputError
    // ("world: ...") otherwise.
    Mat4 world;
    uint32_t flags = kInstanceCastsShadows | kInstanceAlphaMasked;  // InstanceFlags only
};

// -------------------------------------------------------------------------- the frame

// The camera the shadows are fitted to and that the shaders' cascade selection uses.
// Penumbra's conventions: right-handed world, view space looks down -Z.
struct ViewDesc {
    Mat4 view;                   // world -> view (looking down -Z)
    float fov_y_radians = 1.0f;  // vertical field of view, (0, pi) (without `projection`)
    float near_plane = 0.1f;     // > 0
    float far_plane = 200.0f;    // > near_plane, finite: the cascades reach min(far, max_distance)
    uint32_t width = 1280;       // the rendered image in pixels: aspect ratio, and the local
    uint32_t height = 720;       // shadow maps' coverage sizing
    // Rotates the per-pixel sampling pattern of the Poisson and PCSS filters, so that a
    // renderer that accumulates frames (TAA) averages the pattern away. nullopt: the frame
    // number, a new rotation every frame; a fixed value keeps the pattern still (the tools'
    // `compare` fixes it while it measures temporal stability).
    std::optional<uint32_t> sampling_frame;
    // The camera's projection, view -> Vulkan clip space (depth 0..1), as the caller renders
    // with it: any perspective (symmetric, off-centre, jittered for TAA, finite or infinite
    // far, reverse or forward Z) or orthographic projection. The cascades fit its frustum
    // (up to min(far, max_distance)); a jitter of up to 2 pixels leaves stable cascades
    // where they are. nullopt: the symmetric perspective of fov_y_radians, near_plane and
    // far_plane (reverse_z_projection()); with a projection those three are not read.
    std::optional<Mat4> projection;
};

// What ShadowSystem::update_settings() changed.
struct SettingsChange {
    SettingEffect effect = SettingEffect::Live;  // the largest effect among the changed settings
    // shader_specialization() gives other values from now on: rebuild the pipelines of your
    // shaders that include penumbra/shadow.glsl before recording with them after the next
    // prepare(). Never true for Live settings.
    bool shader_specialization_changed = false;
};

// A look-at ViewDesc (eye, target, up; up may not be parallel to target - eye).
ViewDesc look_at_view(Vec3 eye, Vec3 target, Vec3 up, float fov_y_radians, float near_plane, float far_plane,
                      uint32_t width, uint32_t height);

// The projection of a ViewDesc: ViewDesc::projection when given, else Penumbra's own:
// Vulkan clip space, Y flipped (image row 0 at the top), reverse-Z (depth 1 at the near
// plane, 0 at the far plane).
Mat4 reverse_z_projection(const ViewDesc& view);

// A rectangle of a cascade's texels, counted from the cascade's texel (0, 0) (not the
// layer's: see CascadeInfo::layer_origin_x).
struct TexelRegion {
    uint32_t x = 0;
    uint32_t y = 0;
    uint32_t width = 0;
    uint32_t height = 0;
};

struct CascadeInfo {
    Mat4 view_projection;           // world -> this cascade's clip space (reverse-Z)
    float split_near = 0.0f;        // camera view distance where the cascade starts
    float split_far = 0.0f;         // ... and ends
    float texel_world_size = 0.0f;  // metres per shadow-map texel
    Vec3 light_extent;              // light-space width, height and depth range (metres)
    uint32_t draws = 0;             // casters drawn into it this frame (after culling)
    uint64_t triangles = 0;
    // With cached static casters (Settings::shadow.cache_static_casters): whether the cache
    // was reused (false: every static caster was drawn), the texels whose static casters
    // were drawn this frame, and the texels copied between the map and its cache.
    bool cache_reused = false;
    uint64_t texels_rendered = 0;
    uint64_t texels_copied = 0;
    // The layer texel of the cascade's texel (0, 0): with per-cascade and layered passes
    // the cascade wraps around its layer from there (toroidal: a world texel keeps its
    // layer texel while the cascade moves; penumbra/glsl/sun.glsl samples accordingly),
    // with multiview (0, 0): the layer is the cascade. The cascade's texel (x, y) is the
    // layer's ((x + layer_origin_x) mod resolution, (y + layer_origin_y) mod resolution).
    uint32_t layer_origin_x = 0;
    uint32_t layer_origin_y = 0;
    // Where this frame drew: the static casters (the whole cascade unless the cache was
    // reused; rectangles may overlap) and, with a cache, the dynamic instances' reach.
    std::vector<TexelRegion> redrawn;
    std::vector<TexelRegion> dynamic_regions;
};

struct LocalShadowInfo {
    uint32_t light = 0;        // index into the set_lights() list
    uint32_t slot = 0;         // 1 + its position in FrameInfo::local_shadows: its visibility slot
    uint32_t first_layer = 0;  // in the local shadow map
    uint32_t layers = 0;       // 1 for a spot, 6 for a cube (points, spots wider than 60 degrees)
    uint32_t resolution = 0;   // texels per side of each of its layers this frame
    float near_plane = 0.0f;   // metres (the nearest caster)
    uint32_t draws = 0;        // casters drawn over all its layers this frame
    uint64_t triangles = 0;
    // With cached static casters (Settings::shadow.cache_static_casters): its layers that
    // still held this light's shadow and were not rendered (all of them for a light whose
    // position, range, near plane and size are unchanged, with no dynamic caster and no
    // static change within reach).
    uint32_t layers_kept = 0;
};

// The sun's virtual shadow map this frame (Settings::shadow.technique = virtual;
// docs/techniques.md, "Virtual shadow maps").
struct VirtualShadowInfo {
    uint32_t levels = 0;                  // clipmap levels (0: the sun casts no shadow)
    std::vector<float> texel_world_size;  // metres per texel of each level, finest first
    uint32_t pool_pages = 0;              // physical pages of 128 x 128 texels (64 KiB each)
    uint64_t pool_bytes = 0;
    uint32_t invalidations = 0;    // page rectangles made stale this frame (changed static casters, dynamic ones)
    bool invalidated_all = false;  // every page stale: light, depth range or settings changed, or no cache
    // The GPU's counts of frame `counted_frame`, the last one known complete (this one less
    // frames_in_flight): 0 until there is one. No readback waits for them.
    uint64_t counted_frame = 0;
    uint32_t pages_requested = 0;      // pages the pixels' filters read (their level's and the next coarser's)
    uint32_t pages_rendered = 0;       // drawn that frame: new pages and stale ones
    uint32_t pages_cached = 0;         // requested and still valid: not drawn
    uint32_t pages_unserved = 0;       // requested, but the pool was full: a coarser level served their pixels
    uint32_t pages_resident = 0;       // physical pages holding a page after that frame's allocation
    uint32_t pages_evicted = 0;        // unrequested pages given to others, least recently requested first
    uint32_t page_draws = 0;           // caster instances into pages the frame asked for (drawn or dropped)
    uint64_t page_draw_triangles = 0;  // the triangles of those draws (each drawn once per page)
    // Page draws beyond Settings::shadow.virtual_maps.page_draws: their pages are drawn again
    // in the next frames, and their pixels read a coarser level until then.
    uint32_t dropped_page_draws = 0;
    // Requested pages left stale for a later frame, since the frames before dropped page
    // draws: a frame then draws only as many pages as the buffer holds all the draws of
    // (their pixels read a coarser level meanwhile).
    uint32_t pages_deferred = 0;
};

// One view's sun shadow in a frame (see ShadowSystem::prepare() with several views).
struct ViewShadowInfo {
    std::vector<CascadeInfo> cascades;             // empty with the virtual shadow map
    std::optional<VirtualShadowInfo> virtual_map;  // with Settings::shadow.technique = virtual
    float shadow_distance = 0.0f;                  // where the last cascade ends (fading to lit before it)
    // The set the caller binds for penumbra/shadow.glsl (at the set index of its choosing)
    // when it shades this view, valid for the command buffers that record this frame.
    VkDescriptorSet descriptor_set = VK_NULL_HANDLE;
};

struct FrameInfo {
    uint64_t frame = 0;  // counts prepare() calls, from 1
    // The sun (the first directional light), when there is one. Its cascades are fitted
    // even when it casts no shadow (then nothing is drawn into them: draws 0).
    std::optional<uint32_t> sun;
    Vec3 sun_direction{0.0f, -1.0f, 0.0f};  // the direction its light travels, normalised
    // The first view's sun shadow (the same as views[0]'s fields):
    std::vector<CascadeInfo> cascades;             // empty with the virtual shadow map
    std::optional<VirtualShadowInfo> virtual_map;  // with Settings::shadow.technique = virtual
    float shadow_distance = 0.0f;                  // where the last cascade ends (fading to lit before it)
    // The set the caller binds for penumbra/shadow.glsl (at the set index of its choosing),
    // valid for the command buffer that records this frame.
    VkDescriptorSet descriptor_set = VK_NULL_HANDLE;
    // Every view's, in the order prepare() took them (one entry with a single view).
    std::vector<ViewShadowInfo> views;
    std::vector<LocalShadowInfo> local_shadows;  // shadowed spot/point lights, in light order, shared by the views
    // Spot/point lights that cast shadows but got none: beyond the budget or the layers.
    std::vector<uint32_t> unshadowed_lights;
    double cpu_fit_ms = 0.0;  // prepare(): cascade splits and fitting, local-light fitting
    // prepare(): applying update_settings() (pipelines and maps rebuilt); 0 without a change
    double cpu_settings_ms = 0.0;
    double cpu_cull_ms = 0.0;  // prepare(): caster culling of every map
};

// ------------------------------------------------------------- deferred (screen) path

enum class NormalEncoding {
    SignedFloat,         // xyz in [-1, 1] (e.g. R16G16B16A16_SFLOAT), world space
    UnsignedNormalized,  // xyz * 0.5 + 0.5 (e.g. R8G8B8A8_UNORM, A2B10G10R10_UNORM), world space
    // Octahedral (Cigolle et al. 2014, "A Survey of Efficient Representations for
    // Independent Unit Vectors"), signed: the normal in .xy and, where face_normals names an
    // image, the face normal in that image's .zw, so one four-channel target (e.g.
    // R16G16B16A16_SFLOAT, 8 bytes a pixel) carries both. n / (|x| + |y| + |z|) gives xy
    // where z >= 0; where z < 0 xy is folded: (1 - |yx|) * sign(xy), sign(0) = +1.
    Octahedral,
};

// The caller's screen inputs of record_visibility(). Both images are sampled by a compute
// shader in the layouts given here; the caller makes its writes to them available to
// VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT reads before the call.
struct ScreenInputs {
    VkImageView depth = VK_NULL_HANDLE;  // a 2D view of the depth aspect (any depth format)
    VkImageLayout depth_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    // World-space normals; VK_NULL_HANDLE: reconstructed from the depth (the geometric normal).
    VkImageView normals = VK_NULL_HANDLE;
    VkImageLayout normals_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    NormalEncoding normal_encoding = NormalEncoding::SignedFloat;  // of normals and face_normals
    // Optional: each pixel's face (geometric) normal in world space, either orientation, as
    // a fragment shader gets it from cross(dFdx(position), dFdy(position)). With it the
    // resolve takes the receiver's plane (face tests, receiver-plane bias) from the surface
    // itself, exactly as penumbra_sun_receiver_fragment() in forward shading; without it,
    // from the neighbouring pixels' depths, which is wrong on objects one or two pixels
    // wide and at silhouettes.
    VkImageView face_normals = VK_NULL_HANDLE;
    VkImageLayout face_normals_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    uint32_t width = 0;  // pixels: the images' extent
    uint32_t height = 0;
    // world -> clip of the projection the depth was rendered with (any convention: reverse
    // or forward Z, jittered, infinite far), and the depth value of pixels with no geometry
    // (0 for reverse-Z, 1 for forward Z): those get visibility 1.
    Mat4 view_projection;
    float background_depth = 0.0f;
};

// What record_visibility() writes: one visibility value per pixel and light, 1 lit,
// 0 shadowed or facing away from the light, in a 2D array image of RGBA8 layers. Slot s
// is layer s / 4, channel s % 4: slot 0 the sun (0 at every pixel with geometry when there
// is no directional light: no sunlight arrives), slot k the local light with
// LocalShadowInfo::slot == k. Left in VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, its writes
// visible to fragment and compute shader reads; valid until the next record_visibility().
struct VisibilityImage {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;  // VK_IMAGE_VIEW_TYPE_2D_ARRAY
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    uint32_t width = 0;  // the pixels written: the ScreenInputs' extent
    uint32_t height = 0;
    uint32_t layers = 0;  // the image's layers (a caller's VisibilityTarget may have more than needed)
    uint32_t slots = 0;   // 1 + FrameInfo::local_shadows.size()
};

// The layers a visibility image needs for `slots` slots (four slots per RGBA8 layer).
constexpr uint32_t visibility_layers(uint32_t slots) { return (slots + 3) / 4; }

// An image of the caller's for record_visibility() to write instead of Penumbra's own, so
// that the caller's descriptors do not change when the screen or the number of shadowed
// lights does: allocate it once at the largest extent and for the most lights the frame
// may have. Its contents are replaced by each record_visibility(); the layout and access
// it is left in are those of VisibilityImage, and its earlier uses must be fragment or
// compute shader reads (or be ordered before compute shaders by the caller's own barrier).
struct VisibilityTarget {
    VkImage image = VK_NULL_HANDLE;              // with VK_IMAGE_USAGE_STORAGE_BIT and _SAMPLED_BIT, one mip level
    VkImageView view = VK_NULL_HANDLE;           // VK_IMAGE_VIEW_TYPE_2D_ARRAY over layers [0, layers)
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;  // the only format the resolve writes
    uint32_t width = 0;  // at least the ScreenInputs' extent; pixels beyond it keep their contents
    uint32_t height = 0;
    uint32_t layers = 0;  // at least visibility_layers(1 + FrameInfo::local_shadows.size())
};

// ---------------------------------------------------------------- the shadow maps

// One of Penumbra's maps, for callers that read them directly (debug views, custom
// filters). After record_shadow_maps() they are in VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL
// with their writes visible to fragment and compute shader reads. A caller that moves one
// into another layout (e.g. to copy it) returns it to that layout, with its reads made
// available, before the next record_shadow_maps().
struct MapImage {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;  // VK_IMAGE_VIEW_TYPE_2D_ARRAY, every layer
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkImageAspectFlags aspect = 0;
    uint32_t resolution = 0;  // texels per side
    uint32_t layers = 0;
};

struct ShadowMaps {
    MapImage cascades;         // D32 reverse-Z depth, one layer per cascade
    MapImage cascade_moments;  // vsm/evsm/msm only (else image == VK_NULL_HANDLE)
    MapImage local;            // D32 reverse-Z depth of every shadowed spot/point light's layers
    MapImage local_moments;    // vsm/evsm/msm with shadowed local lights only
    // The virtual shadow map's physical pages (technique virtual; a placeholder otherwise):
    // D32 reverse-Z, layers of 4 x 4 pages of 128 x 128 texels (penumbra/glsl/virtual_clipmap.glsl).
    MapImage virtual_pool;
};

// -------------------------------------------------------------- timings and memory

struct PassTime {
    // "shadow_cascade_<i>", "shadow_multiview", "shadow_moments", "shadow_local", "visibility";
    // the virtual shadow map's "shadow_virtual_mark", "_allocate", "_cull" and "_raster";
    // a view after the first adds "_view<v>" to its sun's passes and its "visibility"
    std::string name;
    double milliseconds = 0.0;
};

struct GpuTimes {
    uint64_t frame = 0;  // the FrameInfo::frame they belong to
    std::vector<PassTime> passes;
};

struct MemoryStats {
    uint64_t cascade_maps = 0;  // depth, moments and blur scratch of the cascades
    uint64_t local_maps = 0;    // depth, moments and blur scratch of spot/point lights
    uint64_t virtual_pool = 0;  // the virtual shadow map's physical pages (Settings::shadow.virtual_maps.pool_mib)
    uint64_t visibility = 0;    // record_visibility()'s image
    uint64_t buffers = 0;       // uniforms, uploaded meshes, staging, culled draws, the page table
    // VkDeviceMemory blocks that Penumbra's own allocator holds for all of the above (0 with
    // DeviceDesc::allocator, the caller's): each block serves many images or buffers.
    uint32_t memory_blocks = 0;
    uint64_t shadow_maps() const { return cascade_maps + local_maps + virtual_pool; }
    uint64_t total() const { return shadow_maps() + visibility + buffers; }
};

// ---------------------------------------------------------------- the system

struct ShadowSystemDesc {
    DeviceDesc device;
    Settings settings;
    // How many frames the caller records before it waits for the oldest: prepare() for
    // frame F reuses the per-frame resources of frame F - frames_in_flight, whose
    // submission must have completed (1..8).
    uint32_t frames_in_flight = 2;
    // Timestamp queries around every pass, for gpu_times(). False records none: gpu_times()
    // is always nullopt, and prepare() cannot tell a frame still in flight (see prepare()).
    bool timestamps = true;
    // One set of shadow maps per frame in flight instead of one: each view's cascades (or
    // virtual shadow map) and the spot/point lights' maps, each set with its own cache. Frame
    // F draws set F % frames_in_flight, which no frame still in flight samples, so frame F's
    // shadow passes do not depend on frame F - 1's sampling: they may be submitted before it,
    // or on another queue with no semaphore from it (see docs/library.md "Maps per frame in
    // flight"). Costs frames_in_flight times the maps' memory; a set's cache serves it every
    // frames_in_flight frames (static changes are drawn into each set in turn).
    bool maps_per_frame_in_flight = false;
};

// The constants of penumbra/shadow.glsl's specialization, for the caller's pipelines.
// `entries` and `data` view storage that the ShadowSystem owns and never changes: they, and
// the VkSpecializationInfo that info() returns, stay valid until the ShadowSystem is
// destroyed, in every copy and after any copy, move or destruction of this struct (so
// `shadows.shader_specialization(0).info()` may be kept).
struct ShaderSpecialization {
    std::span<const VkSpecializationMapEntry> entries;
    std::span<const uint32_t> data;  // one 4-byte value per entry
    VkSpecializationInfo info() const;
};

class ShadowSystem {
public:
    // Checks the device (DeviceError naming what is missing) and the settings (InputError),
    // then creates the pipelines and the maps the settings ask for.
    explicit ShadowSystem(const ShadowSystemDesc& desc);
    // Waits for DeviceDesc::queue (and compute_queue, when given) to be idle (vkQueueWaitIdle:
    // frames submitted and not waited for complete first; no wait when the caller already
    // waited), then destroys everything Penumbra created. The queues are externally
    // synchronised: no other thread may submit to them while this runs. Frames submitted on
    // other queues are the caller's to wait for.
    ~ShadowSystem();
    ShadowSystem(const ShadowSystem&) = delete;
    ShadowSystem& operator=(const ShadowSystem&) = delete;

    // Geometry. Meshes and instances may be added, changed and removed between frames;
    // the next prepare() sees them.
    MeshId add_mesh(const MeshDesc& mesh);
    MeshId add_mesh(const MeshData& mesh);
    // A mesh still used by an instance cannot be removed (UsageError).
    void remove_mesh(MeshId mesh);
    // InputError naming the argument for a world transform or flags InstanceDesc does not
    // allow (see there); the instance is then unchanged.
    InstanceId add_instance(const InstanceDesc& instance);
    // Setting the matrix an instance already has (or the flags it already has) changes
    // nothing: cached shadow maps stay valid, so uploading every transform every frame is free.
    void set_instance_transform(InstanceId instance, const Mat4& world);
    void set_instance_flags(InstanceId instance, uint32_t flags);
    void remove_instance(InstanceId instance);

    // The lights, replacing the previous list (at most kMaxLights). The first directional
    // light is the sun; other directional lights are ignored. Spot and point lights with
    // cast_shadows get shadow maps in list order, up to the local shadow budget.
    void set_lights(std::span<const LightDesc> lights);

    // Takes any valid settings (validate_settings(): InputError otherwise) from the next
    // prepare() on; the frame already prepared records with the old ones. The meshes,
    // instances and lights stay, and so does the descriptor set layout. Changes rebuild
    // inside the system what they must (SettingEffect, per setting in kSettingDeclarations):
    // live ones are uniforms; Pipeline ones respecialise Penumbra's shaders; Resource ones
    // reallocate the maps, which are drawn again in full. The result says whether the
    // caller's own pipelines (built with shader_specialization()) must be rebuilt.
    SettingsChange update_settings(const Settings& settings);
    // The settings of the next prepare(): the last update_settings() ones.
    const Settings& settings() const;

    // CPU work of a frame: cascade splits and fitting for `view`, the local lights' fits,
    // budget and sizing, caster culling, and the frame's uniforms. Starts a new frame (see
    // ShadowSystemDesc::frames_in_flight). The result is valid until the next prepare().
    // The frame frames_in_flight frames earlier, whose slot this one reuses, must have
    // completed on the GPU: where the queue has timestamps, a frame whose results are not
    // there yet (the caller has more frames in flight, or never submitted it) is a
    // UsageError naming frames_in_flight, thrown before anything changes.
    const FrameInfo& prepare(const ViewDesc& view);
    // Several views in one frame (split screen, a reflection probe's faces, a second camera;
    // VR's two eyes are better one view whose projection holds both frusta): 1..kMaxViews
    // views, each with a sun shadow of its own (cascades or a virtual shadow map fitted to
    // it, with its own cache, uniforms, descriptor set and visibility image), sharing the
    // scene, the settings and the spot/point lights' maps (sized for the view that needs
    // them largest). View v's calls below take `view` = v. A view keeps its caches while
    // the next frames have a view at its index; a frame with fewer views releases the rest.
    // Each view's maps take their own memory (MemoryStats counts them all).
    const FrameInfo& prepare(std::span<const ViewDesc> views);

    // The virtual shadow map (Settings::shadow.technique = virtual) draws only the pages the
    // frame's pixels sample: this records the compute passes that find them in `screen`'s
    // depth (its normals are not read) and allocate them, before record_shadow_maps() in
    // the same frame. The depth is the frame's own (a depth pre-pass, or the G-buffer's
    // depth before the resolve) or, for a forward renderer without a pre-pass, the last
    // frame's (newly visible surfaces then get their pages a frame late, and sample the
    // next coarser level until then). The caller makes the depth's writes available to
    // compute shader reads first, as for record_visibility(). With the cascades it records
    // nothing. With several views, each view's pages are marked from its own depth.
    void record_page_marking(VkCommandBuffer cmd, const ScreenInputs& screen, uint32_t view = 0);

    // Records the frame's shadow passes into `cmd` (a primary command buffer in the
    // recording state, outside any render pass, on a queue of the DeviceDesc's family),
    // after the uploads of meshes added since the last recording. On exit the maps are
    // ready for sampling (see ShadowMaps). Every view's maps are recorded. Requires
    // prepare() first, and with the virtual shadow map record_page_marking() of every view
    // (UsageError).
    void record_shadow_maps(VkCommandBuffer cmd);

    // Records the compute resolve: the visibility of the sun and of every shadowed local
    // light at each pixel of `screen`, with the configured filter, into Penumbra's own
    // image, or into the caller's `target` (InputError naming the field when its format,
    // extent or layers do not fit). Requires record_shadow_maps() earlier in this frame (in
    // this or an earlier submitted command buffer of the same frame). Once per view and frame;
    // `screen` is that view's.
    void record_visibility(VkCommandBuffer cmd, const ScreenInputs& screen, uint32_t view = 0);
    void record_visibility(VkCommandBuffer cmd, const ScreenInputs& screen, const VisibilityTarget& target,
                           uint32_t view = 0);
    // Async compute: the same resolve into the caller's `target`, recorded into
    // `compute_cmd`, a command buffer of DeviceDesc::compute_queue_family (UsageError without
    // one), which the caller submits on DeviceDesc::compute_queue waiting (with a semaphore,
    // at VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT) for the submission that holds this frame's
    // record_shadow_maps(). Penumbra's maps and buffers are shared by both families; the
    // caller's images change hands (docs/library.md, "Async compute", has the barriers):
    // the screen inputs are released by the graphics family and acquired by the compute
    // family before this call, in the layouts ScreenInputs gives; the target's contents are
    // discarded (no acquire needed), and it is left in VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL
    // with its writes visible to compute shader reads of this queue, for the caller to
    // release to the graphics family and acquire there before sampling it. The rest is as
    // record_visibility() (once per frame and view, either call).
    void record_visibility_async(VkCommandBuffer compute_cmd, const ScreenInputs& screen,
                                 const VisibilityTarget& target, uint32_t view = 0);
    // The image the view's last record_visibility() wrote, and where; a UsageError before
    // the first, or for a view the last prepare() did not have.
    VisibilityImage visibility_image(uint32_t view = 0) const;

    // For forward shading with penumbra/shadow.glsl: the layout of FrameInfo::descriptor_set
    // (include it in your pipeline layout at the set index your shaders define as
    // PENUMBRA_SHADOW_SET; its bindings are visible to every stage), and the specialization
    // constants of the configured filter, with IDs from first_constant_id (your shaders'
    // PENUMBRA_SPEC_ID_BASE) to first_constant_id + 7.
    VkDescriptorSetLayout descriptor_set_layout() const;
    ShaderSpecialization shader_specialization(uint32_t first_constant_id = 0) const;

    // The maps of a view of the last prepare() (cascades and virtual pool are the view's, the
    // local lights' are shared); UsageError for a view it did not have.
    ShadowMaps shadow_maps(uint32_t view = 0) const;

    // GPU time of each pass of `frame` (a FrameInfo::frame), once the submission that
    // recorded it has completed, and still after the prepare() that reuses its slot (which
    // keeps them): so any of the last 2 x frames_in_flight frames. nullopt when the queue
    // family has no timestamps, for an older frame, or when the results are not there yet.
    // Never waits.
    std::optional<GpuTimes> gpu_times(uint64_t frame) const;
    MemoryStats memory() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace penumbra
