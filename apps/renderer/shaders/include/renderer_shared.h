// The tools' renderer's GPU interface, shared by its C++ (apps/renderer/shader_interface.hpp
// checks every offset) and its shaders: the frame uniforms, the lights it shades, the
// per-draw push constants, and where Penumbra's descriptor set is bound.
#ifndef PENUMBRA_RENDERER_SHARED_H
#define PENUMBRA_RENDERER_SHARED_H

#ifdef __cplusplus
#define RENDERER_UINT uint32_t
#define RENDERER_INT int32_t
#else
#define RENDERER_UINT uint
#define RENDERER_INT int
#endif

#define RENDERER_SET_FRAME 0
#define RENDERER_BINDING_FRAME_UNIFORMS 0
#define RENDERER_BINDING_LIGHTS 1
// The camera passes draw batches of instances: the model matrix of every draw (by draw
// index), and per instance slot of this frame's batches the draw it is (gl_InstanceIndex).
#define RENDERER_BINDING_DRAW_MODELS 2
#define RENDERER_BINDING_INSTANCE_DRAWS 3
#define RENDERER_SET_MATERIAL 1
#define RENDERER_BINDING_BASE_COLOR_TEXTURE 0
#define RENDERER_BINDING_EMISSIVE_TEXTURE 1
#define RENDERER_BINDING_METALLIC_ROUGHNESS_TEXTURE 2  // G: roughness, B: metallic (glTF)
#define RENDERER_BINDING_OCCLUSION_TEXTURE 3           // R: ambient occlusion (glTF)
// The ShadowSystem's descriptor set (the shaders define PENUMBRA_SHADOW_SET to this).
#define RENDERER_SET_SHADOWS 2
// The deferred resolve's output (ShadowSystem::visibility_image()), read by the lighting
// pass with `--resolve deferred`.
#define RENDERER_SET_SCREEN 3
#define RENDERER_BINDING_SHADOW_VISIBILITY 0
// With contact shadows (Settings::contact), forward or deferred: the depth pre-pass, which
// penumbra_sun_contact() / penumbra_light_contact() trace (same set).
#define RENDERER_BINDING_CONTACT_DEPTH 1
// FrameUniforms::visibility_light for `--aov contact`: the sun's contact term alone.
#define RENDERER_VISIBILITY_CONTACT (-2)

#define RENDERER_DEBUG_VIEW_NONE 0u
#define RENDERER_DEBUG_VIEW_CASCADES 1u
#define RENDERER_DEBUG_VIEW_VIRTUAL_PAGES 2u
#define RENDERER_ALPHA_OPAQUE 0u
#define RENDERER_ALPHA_MASK 1u
// Cascade index written where no cascade applies (no geometry, beyond the shadow distance).
#define RENDERER_NO_CASCADE 255u
#define RENDERER_MAX_LOCAL_LIGHTS 64
#define RENDERER_LIGHT_SPOT 1u
#define RENDERER_LIGHT_POINT 2u

struct FrameUniforms {
    mat4 view_projection;             // camera: world -> clip
    vec4 camera_position;             // xyz
    vec4 to_sun;                      // xyz: unit vector toward the sun; w: 1 when there is a sun
    vec4 sun_radiance;                // rgb: colour * intensity
    vec4 ambient;                     // rgb: ambient radiance
    RENDERER_UINT debug_view;         // RENDERER_DEBUG_VIEW_*
    RENDERER_INT visibility_light;    // the local light written to the visibility target (-1: the sun)
    RENDERER_UINT local_light_count;  // entries of LocalLights::lights
    RENDERER_UINT padding;
    mat4 inverse_view_projection;  // clip -> world (contact shadows trace the pre-pass's depth)
    vec4 screen;                   // xy: the camera targets' pixels; z: the pre-pass's depth where nothing was drawn
};

// A spot or point light as the renderer shades it; its shadow comes from Penumbra.
struct LocalLight {
    vec3 position;
    float range;
    vec3 direction;      // unit travel direction (spot)
    RENDERER_UINT type;  // RENDERER_LIGHT_SPOT or _POINT
    vec3 radiance;       // colour * intensity
    float cos_outer;     // spot cone (-1 for points)
    float cos_inner;
    RENDERER_UINT shadow_index;     // the light's index in the ShadowSystem's set_lights() list
    RENDERER_UINT visibility_slot;  // its slot in the deferred visibility image; 0: no shadow map
    float padding;
};

struct LocalLights {
    LocalLight lights[RENDERER_MAX_LOCAL_LIGHTS];
};

// One batch of a camera pass: instances of one mesh with one material (their model
// matrices come from RENDERER_BINDING_DRAW_MODELS through RENDERER_BINDING_INSTANCE_DRAWS).
struct DrawPushConstants {
    vec4 base_color;  // linear RGBA factor
    vec4 material;    // x: alpha cutoff, y: roughness, z: metallic
    // x: 1 when the material has an emissive texture, y: 1 when it has a base colour
    // texture, z: alpha mode (RENDERER_ALPHA_*), w: 1 when the instance receives shadows
    uvec4 flags;
    vec4 emissive;  // rgb: emitted radiance (linear), added unshadowed; w: occlusion strength
};

#endif
