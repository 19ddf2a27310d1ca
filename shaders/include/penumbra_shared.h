// Layouts shared by C++ and GLSL: the frame uniform block and the per-draw push
// constants. C++ includes this header inside namespace penumbra::shader and
// checks sizes and offsets with static_asserts (src/renderer/shader_interface.hpp),
// so the two sides cannot drift apart. Every member is a vec4/mat4 (or an array
// of them) so that std140 and C++ layouts coincide without padding rules.
#ifndef PENUMBRA_SHARED_H
#define PENUMBRA_SHARED_H

#ifdef __cplusplus
#define PENUMBRA_UINT uint32_t
#else
#define PENUMBRA_UINT uint
#endif

#define PENUMBRA_MAX_CASCADES 8

// Descriptor sets and bindings.
#define PENUMBRA_SET_FRAME 0
#define PENUMBRA_BINDING_FRAME_UNIFORMS 0
#define PENUMBRA_BINDING_SHADOW_MAP 1          // sampler2DArrayShadow (hardware comparison)
#define PENUMBRA_BINDING_SHADOW_DEPTH 2        // the same map, raw depth (PCSS blocker search)
#define PENUMBRA_BINDING_SHADOW_MOMENTS 3      // filtered moments (vsm/evsm/msm), else the depth map
#define PENUMBRA_BINDING_LOCAL_LIGHTS 4        // LocalLightUniforms (spot and point lights), storage buffer
#define PENUMBRA_BINDING_LOCAL_SHADOW_MAP 5    // sampler2DArrayShadow: every local light's layers
#define PENUMBRA_BINDING_LOCAL_SHADOW_DEPTH 6  // the same map, raw depth (PCSS blocker search)
#define PENUMBRA_BINDING_LOCAL_MOMENTS 7       // local lights' filtered moments, else their depth map
// The local shadow pass: set 0, binding 0 = LocalLightUniforms (storage buffer).
// The moments blur pass and the local moments pass: set 0 holds the image they read.
#define PENUMBRA_BINDING_BLUR_SOURCE 0
#define PENUMBRA_SET_MATERIAL 1
#define PENUMBRA_BINDING_BASE_COLOR_TEXTURE 0

// FrameUniforms.options.x: debug view of the colour image.
#define PENUMBRA_DEBUG_VIEW_NONE 0u
#define PENUMBRA_DEBUG_VIEW_CASCADES 1u

// DrawPushConstants.flags.z: how the material's alpha is used.
#define PENUMBRA_ALPHA_OPAQUE 0u
#define PENUMBRA_ALPHA_MASK 1u

// Shadow filters: specialization constant PENUMBRA_SPEC_FILTER_MODE of the lighting and
// moments fragment shaders (docs/filters.md).
#define PENUMBRA_FILTER_HARD 0u
#define PENUMBRA_FILTER_PCF 1u
#define PENUMBRA_FILTER_POISSON 2u
#define PENUMBRA_FILTER_PCSS 3u
#define PENUMBRA_FILTER_VSM 4u
#define PENUMBRA_FILTER_EVSM 5u
#define PENUMBRA_FILTER_MSM 6u

// Specialization constant ids (one pipeline per filter configuration).
#define PENUMBRA_SPEC_FILTER_MODE 0
#define PENUMBRA_SPEC_SEARCH_TAPS 1      // poisson taps, or PCSS blocker-search taps: 16 or 32
#define PENUMBRA_SPEC_FILTER_TAPS 2      // PCSS filter taps: 16, 25 or 49
#define PENUMBRA_SPEC_RECEIVER_PLANE 3   // bool: receiver-plane depth bias
#define PENUMBRA_SPEC_PCSS_EARLY_OUT 4   // bool
#define PENUMBRA_SPEC_MOMENTS_POISSON 5  // bool: 16 Poisson taps of the moments
#define PENUMBRA_SPEC_EVSM_COMPONENTS 6  // 2 or 4
#define PENUMBRA_SPEC_MSM_QUANTIZED 7    // bool: optimized moment quantization (RGBA16)

// Cascade index written where no cascade applies (no geometry, beyond the shadow distance).
#define PENUMBRA_NO_CASCADE 255u

struct FrameUniforms {
    mat4 view_projection;                                 // camera: world -> clip
    mat4 view;                                            // camera: world -> view (for view depth)
    mat4 cascade_view_projection[PENUMBRA_MAX_CASCADES];  // world -> cascade clip (reverse-Z)
    vec4 camera_position;                                 // xyz
    vec4 sun_direction;  // xyz: unit vector toward the sun; w: 1 when the scene has a sun
    vec4 sun_radiance;   // rgb: colour * intensity; w: 1 when the sun casts shadows
    vec4 ambient;        // rgb: ambient radiance
    // Cascade i's far split (view distance) is element [i / 4][i % 4]; likewise its texel size.
    vec4 cascade_split_far[PENUMBRA_MAX_CASCADES / 4];
    vec4 cascade_texel_world_size[PENUMBRA_MAX_CASCADES / 4];
    // x: cascade count (0 = no shadow), y: normal offset in texels, z: blend width (fraction),
    // w: shadow distance (where the distance fade reaches fully lit).
    vec4 shadow_params;
    // x: camera near plane (start of cascade 0)
    vec4 camera_params;
    // x: debug view (PENUMBRA_DEBUG_VIEW_*)
    uvec4 options;
    // Shadow filtering (shaders/include/shadow.glsl, docs/filters.md). Per cascade:
    // xy: the light's radius in UV per unit of reverse-Z depth (depth range * tan(angular
    // diameter / 2) / light-space width, height); zw: clamp of the receiver-plane depth
    // gradient dz/du, dz/dv.
    vec4 cascade_filter[PENUMBRA_MAX_CASCADES];
    // x: pcf radius (taps), y: poisson radius (texels), z: pcss max penumbra (texels),
    // w: one shadow-map texel in UV
    vec4 filter_params;
    // x: light-bleeding reduction, y: evsm positive exponent, z: evsm negative exponent
    // (both already clamped to the moments format), w: msm moment bias
    vec4 moment_params;
    // x: frame index (per-frame rotation of the sampling patterns)
    uvec4 filter_options;
};

// Spot and point lights (docs/local-lights.md, src/core/local_lights.hpp).
#define PENUMBRA_MAX_LOCAL_LIGHTS 64
#define PENUMBRA_MAX_LOCAL_SHADOW_LAYERS 192
#define PENUMBRA_LIGHT_SPOT 1.0
#define PENUMBRA_LIGHT_POINT 2.0

struct LocalLight {
    vec4 position_range;  // xyz: world position; w: range (metres)
    vec4 direction_type;  // xyz: unit travel direction (spot); w: PENUMBRA_LIGHT_SPOT or _POINT
    vec4 radiance;        // rgb: colour * intensity; w: light radius (metres)
    // x: cos(outer angle), y: cos(inner angle) (spot; -1, -1 for points); z: 1 when the
    // shadow is a cube of six faces (points, spots wider than kMaxPerspectiveSpotAngle)
    vec4 cone;
    // x: first shadow layer (-1: unshadowed), y: near plane, z: 2 tan(fov / 2) of a layer,
    // w: the used fraction of the map per side (light resolution / map resolution)
    vec4 shadow;
};

struct LocalLightUniforms {
    mat4 shadow_view_projection[PENUMBRA_MAX_LOCAL_SHADOW_LAYERS];  // world -> reverse-Z clip per layer
    LocalLight lights[PENUMBRA_MAX_LOCAL_LIGHTS];
    // x: local light count, y: slot of the light written to the visibility target (-1: the sun),
    // z: normal offset in texels, w: one map texel in UV
    vec4 counts;
    // x: pcf radius (taps), y: pcss max penumbra (texels), z: receiver-plane slope limit
    // (kMaxReceiverSlope, metres of depth per metre across)
    vec4 filter_params;
};

struct DrawPushConstants {
    mat4 model;       // model -> world
    vec4 base_color;  // linear RGBA factor
    vec4 material;    // x: alpha cutoff, y: roughness, z: metallic
    // x: cascade index (per-cascade shadow pass; 0 with multiview), y: 1 when the material
    // has a base colour texture, z: alpha mode (PENUMBRA_ALPHA_*)
    uvec4 flags;
};

// The sampling-rate ceiling pass (shaders/tap_ceiling.frag, `penumbra bench --ceiling taps`).
struct TapCeilingPushConstants {
    vec4 target_and_texel;  // xy: 1 / target size in pixels, z: one shadow-map texel in UV units
    uvec4 counts;           // x: texture taps per pixel, y: shadow-map layers
};

// The moments blur pass (shaders/moments_blur.frag).
struct BlurPushConstants {
    // x: layer, y: radius in texels, z: 1 horizontal / 0 vertical, w: texels per side the
    // layer uses from its top-left corner (0: all)
    uvec4 params;
};

// The local lights' moments pass (shaders/local_moments.frag): one layer of the local
// shadow map's reverse-Z depth converted to moments of the normalised linear distance.
struct LocalMomentsPushConstants {
    uvec4 layer;       // x: layer
    vec4 depth_range;  // x: near plane, y: far plane (range), zw: EVSM exponents (positive, negative)
};

#endif
