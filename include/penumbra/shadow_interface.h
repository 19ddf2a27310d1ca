// The GPU side of a ShadowSystem's descriptor set, shared by C++ and GLSL: binding
// numbers, limits, filter ids and the two uniform blocks. penumbra/shadow.glsl includes it;
// Penumbra's C++ includes it inside a namespace and checks every offset with
// static_assert (src/passes/shader_interface.hpp), so the two cannot drift apart. The
// blocks use only vec4-aligned groups of named scalars, vec2 pairs, vec4s and mat4s, for
// which std140/std430 and C++ lay out alike.
#ifndef PENUMBRA_SHADOW_INTERFACE_H
#define PENUMBRA_SHADOW_INTERFACE_H

#ifdef __cplusplus
#define PENUMBRA_UINT uint32_t
#define PENUMBRA_INT int32_t
#else
#define PENUMBRA_UINT uint
#define PENUMBRA_INT int
#endif

#define PENUMBRA_MAX_CASCADES 8
#define PENUMBRA_MAX_LIGHTS 256
#define PENUMBRA_MAX_LOCAL_SHADOW_LAYERS 192
// FilterSettings::pcf_radius's upper bound (the pcf kernel's arrays, penumbra/glsl/pcf.glsl).
#define PENUMBRA_MAX_PCF_RADIUS 5

// Bindings of the ShadowSystem's descriptor set (the set index is the caller's choice).
#define PENUMBRA_BINDING_SHADOW_UNIFORMS 0  // PenumbraShadowUniforms (uniform buffer)
#define PENUMBRA_BINDING_CASCADE_MAP 1      // sampler2DArrayShadow: the cascades, hardware comparison
#define PENUMBRA_BINDING_CASCADE_DEPTH 2    // sampler2DArray: the same map's raw depth (PCSS blocker search)
#define PENUMBRA_BINDING_CASCADE_MOMENTS 3  // sampler2DArray: filtered moments (vsm/evsm/msm), else the depth map
#define PENUMBRA_BINDING_LOCAL_SHADOWS 4    // PenumbraLocalShadows (storage buffer)
#define PENUMBRA_BINDING_LOCAL_MAP 5        // sampler2DArrayShadow: every shadowed spot/point light's layers
#define PENUMBRA_BINDING_LOCAL_DEPTH 6      // sampler2DArray: the same map's raw depth
#define PENUMBRA_BINDING_LOCAL_MOMENTS 7    // sampler2DArray: local lights' filtered moments, else their depth map
// The sun's virtual shadow map (the technique "virtual"; with cascades, placeholders):
#define PENUMBRA_BINDING_VIRTUAL_CLIPMAP_BLOCK 8      // PenumbraVirtualClipmap (uniform buffer)
#define PENUMBRA_BINDING_VIRTUAL_PAGE_TABLE_BUFFER 9  // uint per level and slot (storage buffer)
#define PENUMBRA_BINDING_VIRTUAL_POOL 10              // sampler2DShadow: the physical pages, hardware comparison
#define PENUMBRA_BINDING_VIRTUAL_POOL_DEPTH 11        // sampler2D: the same pages' raw depth

// Filters (Settings::shadow.filter.mode): the ShadowFilter's value is the first
// specialization constant (checked in src/passes/shader_interface.hpp).
#define PENUMBRA_FILTER_HARD 0u
#define PENUMBRA_FILTER_PCF 1u
#define PENUMBRA_FILTER_POISSON 2u
#define PENUMBRA_FILTER_PCSS 3u
#define PENUMBRA_FILTER_VSM 4u
#define PENUMBRA_FILTER_EVSM 5u
#define PENUMBRA_FILTER_MSM 6u
#define PENUMBRA_FILTER_COUNT 7u

// Specialization constant ids, relative to the shaders' PENUMBRA_SPEC_ID_BASE
// (ShadowSystem::shader_specialization()).
#define PENUMBRA_SPEC_FILTER_MODE 0
#define PENUMBRA_SPEC_SEARCH_TAPS 1      // poisson taps, or PCSS blocker-search taps: 16 or 32
#define PENUMBRA_SPEC_FILTER_TAPS 2      // PCSS filter taps: 16, 25 or 49
#define PENUMBRA_SPEC_RECEIVER_PLANE 3   // bool: receiver-plane depth bias
#define PENUMBRA_SPEC_PCSS_EARLY_OUT 4   // bool
#define PENUMBRA_SPEC_MOMENTS_POISSON 5  // bool: 16 Poisson taps of the moments
#define PENUMBRA_SPEC_EVSM_COMPONENTS 6  // 2 or 4
#define PENUMBRA_SPEC_MSM_QUANTIZED 7    // bool: optimized moment quantization (RGBA16)
#define PENUMBRA_SPEC_CONSTANT_COUNT 8

#define PENUMBRA_LIGHT_SPOT 1u
#define PENUMBRA_LIGHT_POINT 2u

// One cascade of the sun's map.
struct PenumbraCascade {
    mat4 view_projection;  // world -> the cascade's clip space (reverse-Z)
    // The light's angular radius in UV per unit of reverse-Z depth: depth range *
    // tan(angular diameter / 2) / light-space (width, height) (PCSS).
    vec2 light_radius_uv_per_depth;
    vec2 max_depth_gradient;  // clamp of the receiver-plane gradient dz/du, dz/dv
    float split_far;          // camera view distance where the cascade ends
    float texel_world_size;   // metres per texel (normal offset)
    // How casters are drawn into the cascade (shaders/caster.vert): the light view's x, y
    // times texels_per_metre is a point's place in a texel grid fixed in the world, less
    // texel_origin (whole numbers) its place in this map, and the light view's z times
    // depth_scale plus depth_offset its reverse-Z depth. The same as view_projection, but
    // a cascade that moves by whole texels puts every caster exactly that many texels
    // further (cached cascades copy what it drew before).
    float depth_scale;
    float depth_offset;
    vec2 texels_per_metre;
    vec2 texel_origin;
    // Where the cascade lies in its layer of the map: the layer texel of the cascade's
    // texel 0, whole numbers. Per-cascade passes place a cascade toroidally (texel_origin
    // modulo the layer's side: a world texel keeps its layer texel while the cascade moves,
    // and the cascade wraps around the layer's edges; sample with REPEAT addressing at
    // uv + layer_origin * texel_uv); multiview leaves it 0.
    vec2 layer_origin;
    float padding_cascade0;
    float padding_cascade1;
};

// PenumbraShadowUniforms::contact_lights: the lights contact shadows trace toward.
#define PENUMBRA_CONTACT_SUN 1u
#define PENUMBRA_CONTACT_LOCAL 2u

struct PenumbraShadowUniforms {
    mat4 camera_view;  // world -> view of the prepared camera (cascade selection by view depth)
    mat4 light_view;   // world -> the sun's light view (a rotation), every cascade's
    PenumbraCascade cascades[PENUMBRA_MAX_CASCADES];
    vec4 to_sun;                     // xyz: unit vector toward the sun; w: 1 when there is a sun
    PENUMBRA_UINT cascade_count;     // 0: the sun casts no shadow (or there is no sun)
    float normal_offset_texels;      // receivers move along their normal by this many texels
    float blend_width;               // fraction of a cascade blended into the next
    float shadow_distance;           // where the last cascade ends
    float camera_near;               // where cascade 0 starts
    float texel_uv;                  // one texel of the cascade map in UV
    float pcf_radius;                // pcf: (2R+1)^2 taps
    float poisson_radius_texels;     // poisson, and the moments' Poisson taps
    float pcss_max_penumbra_texels;  // pcss: largest search and filter radius
    float light_bleeding_reduction;  // vsm/evsm/msm
    float evsm_positive_exponent;    // clamped to the moments' format
    float evsm_negative_exponent;
    float msm_moment_bias;
    PENUMBRA_UINT frame_index;  // rotates the sampling patterns from frame to frame
    // The depth bias the cascade passes gave every caster (vkCmdSetDepthBias): the slope
    // factor and the largest bias in reverse-Z depth (unclamped: FLT_MAX). The
    // receiver-plane bias adds only what it does not cover (penumbra/glsl/filters.glsl).
    float caster_slope_bias;
    float caster_bias_clamp;
    // Screen-space contact shadows (Settings::contact; penumbra/glsl/contact.glsl).
    PENUMBRA_UINT contact_lights;  // PENUMBRA_CONTACT_SUN | PENUMBRA_CONTACT_LOCAL; 0: none
    PENUMBRA_UINT contact_steps;   // depth samples per ray
    float contact_length;          // metres of ray toward the light
    float contact_thickness;       // metres a depth-buffer surface extends behind itself
    float contact_bias;            // metres the ray starts off the surface along its normal
    float contact_max_distance;    // view depth where they end (faded over the last fifth)
    float padding_contact0;
    float padding_contact1;
    // The filter's specialization constants as values (ShadowSystem::shader_specialization()
    // gives the same), for shaders that read them from here instead of being specialised
    // (PENUMBRA_FILTER_FROM_UNIFORMS, penumbra/glsl/filter_constants.glsl).
    PENUMBRA_UINT filter_mode;                 // PENUMBRA_FILTER_*
    PENUMBRA_UINT filter_search_taps;          // PENUMBRA_SPEC_SEARCH_TAPS
    PENUMBRA_UINT filter_taps;                 // PENUMBRA_SPEC_FILTER_TAPS
    PENUMBRA_UINT filter_receiver_plane_bias;  // 0 or 1
    PENUMBRA_UINT filter_pcss_early_out;       // 0 or 1
    PENUMBRA_UINT filter_moments_poisson;      // 0 or 1
    PENUMBRA_UINT filter_evsm_components;      // 2 or 4
    PENUMBRA_UINT filter_msm_quantized;        // 0 or 1
};

// Shadow of one light of the set_lights() list (spot and point lights; others unshadowed).
struct PenumbraLocalShadow {
    vec3 position;             // the light
    float range;               // its shadow ends here (metres)
    PENUMBRA_INT first_layer;  // in the local map; -1: no shadow
    PENUMBRA_UINT cube;        // 1: six cube-face layers (+X, -X, +Y, -Y, +Z, -Z), selected by major axis
    float near_plane;          // of its perspective layers
    float fov_scale;           // 2 tan(fov / 2) of a layer
    float uv_scale;            // the fraction of the map's side its layers use (top-left corner)
    float radius;              // the light's radius (pcss)
    float padding0;
    float padding1;
};  // 48 bytes

#define PENUMBRA_MAX_SHADOWED_LIGHTS 32

struct PenumbraLocalShadows {
    PENUMBRA_UINT light_count;  // entries of `lights` written (the set_lights() list's length)
    float normal_offset_texels;
    float texel_uv;                // one texel of the local map in UV
    float max_receiver_slope;      // receiver-plane gradient clamp (metres of depth per metre across)
    PENUMBRA_UINT shadowed_count;  // lights with a shadow map this frame
    float caster_slope_bias;       // the depth bias of the light layers' casters, as the sun's
    float caster_bias_clamp;
    PENUMBRA_UINT padding0;
    // The set_lights() index of the i-th shadowed light (visibility slot 1 + i) is element
    // [i / 4][i % 4].
    uvec4 shadowed_lights[PENUMBRA_MAX_SHADOWED_LIGHTS / 4];
    mat4 layer_view_projection[PENUMBRA_MAX_LOCAL_SHADOW_LAYERS];  // world -> reverse-Z clip per layer
    PenumbraLocalShadow lights[PENUMBRA_MAX_LIGHTS];
};

// ------------------------------------------------------------ virtual shadow maps
// The sun's virtual shadow map (Settings::shadow.technique = virtual): a clipmap of levels,
// each twice as wide as the one before and centred on the camera, whose 128^2-texel pages
// live in a pool image where a page table says (penumbra/glsl/virtual.glsl samples them).
#define PENUMBRA_MAX_VIRTUAL_LEVELS 24
// A page table entry, one uint per level and slot (level * pages_per_side^2 + slot):
#define PENUMBRA_PAGE_ALLOCATED 0x80000000u  // holds the physical page in the low bits
#define PENUMBRA_PAGE_VALID 0x40000000u      // its texels hold the page's casters (else it is drawn)
#define PENUMBRA_PAGE_RENDER 0x20000000u     // drawn this frame (the casters' culling looks for it)
#define PENUMBRA_PAGE_PHYSICAL_MASK 0x00FFFFFFu
// A physical page's owner when no entry holds it.
#define PENUMBRA_PAGE_NO_OWNER 0xFFFFFFFFu
// One level of the sun's virtual shadow map (docs/techniques.md, "Virtual shadow maps"): a
// window of pages_per_side^2 pages of 128^2 texels, in a page grid fixed in the world, and
// where the window lay the frame before (Penumbra's page allocation frees the pages that
// left it).
struct PenumbraVirtualLevel {
    ivec2 first_page;           // world page of the window's page (0, 0)
    ivec2 previous_first_page;  // the same last frame
    float texels_per_metre;
    float texel_world_size;
    float depth_scale;
    float depth_offset;
};

struct PenumbraVirtualClipmap {
    mat4 light_view;   // world -> light view, every level's
    mat4 camera_view;  // world -> view of the prepared camera (the shadow distance is a view depth)
    // xyz: the prepared camera's position; w: metres of pixel footprint per metre of distance
    vec4 camera_position;
    PENUMBRA_UINT level_count;
    PENUMBRA_UINT pages_per_side;  // of every level's window
    PENUMBRA_UINT pool_pages;      // physical pages
    PENUMBRA_UINT frame;           // increases by one per frame (the pages' ages)
    float lod_scale;               // 2^lod_bias
    float mark_radius_texels;      // what a receiver's filter reads around it, normal offset included
    float shadow_distance;         // pixels at a larger view depth mark nothing
    PENUMBRA_UINT invalidate_all;  // 1: every page's texels are stale (the light or the depth bias changed)
    PENUMBRA_UINT invalidation_count;
    PENUMBRA_UINT padding2;
    PENUMBRA_UINT padding3;
    float light_tan_half_angle;  // tan of the sun's angular radius (PCSS)
    float max_receiver_slope;    // receiver-plane gradient clamp, metres of depth per metre across
    float fade_start;            // view depth where the shadow starts fading to lit at shadow_distance
    float footprint_base;        // metres of pixel footprint at distance 0 (orthographic views; else 0)
    float padding1;
    PenumbraVirtualLevel levels[PENUMBRA_MAX_VIRTUAL_LEVELS];
};

#endif
