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
#define PENUMBRA_BINDING_SHADOW_MAP 1
#define PENUMBRA_SET_MATERIAL 1
#define PENUMBRA_BINDING_BASE_COLOR_TEXTURE 0

// FrameUniforms.options.x: debug view of the colour image.
#define PENUMBRA_DEBUG_VIEW_NONE 0u
#define PENUMBRA_DEBUG_VIEW_CASCADES 1u

// DrawPushConstants.flags.z: how the material's alpha is used.
#define PENUMBRA_ALPHA_OPAQUE 0u
#define PENUMBRA_ALPHA_MASK 1u

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
};

struct DrawPushConstants {
    mat4 model;       // model -> world
    vec4 base_color;  // linear RGBA factor
    vec4 material;    // x: alpha cutoff, y: roughness, z: metallic
    // x: cascade index (per-cascade shadow pass; 0 with multiview), y: 1 when the material
    // has a base colour texture, z: alpha mode (PENUMBRA_ALPHA_*)
    uvec4 flags;
};

#endif
