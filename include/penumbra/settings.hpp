#pragma once
// The settings of a ShadowSystem: one struct, Settings, with named fields and documented
// defaults (docs/library.md, docs/techniques.md, docs/filters.md), and below it one
// declaration per field (kSettingDeclarations: name, range or choices, the filters it
// applies to, what a change rebuilds). validate_settings() and settings_change_effect() read
// the declarations, and so do the tools' config files, flags, --help, viewer and reports
// (with their own labels and help: penumbra/scene/setting_presentation.hpp).
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

#include "penumbra/setting_declaration.hpp"

namespace penumbra {

inline constexpr int kMaxCascades = 8;    // cascades of the sun's shadow map
inline constexpr int kMaxPcfRadius = 5;   // FilterSettings::pcf_radius
inline constexpr uint32_t kMaxViews = 8;  // views one ShadowSystem::prepare() takes

// Spot and point lights (docs/local-lights.md).
inline constexpr uint32_t kMaxLights = 256;             // lights one ShadowSystem takes (set_lights)
inline constexpr uint32_t kMaxLocalShadowBudget = 32;   // shadowed spot/point lights per frame
inline constexpr uint32_t kMaxLocalShadowLayers = 192;  // 32 point lights x 6 faces (Vulkan guarantees 256 layers)
inline constexpr uint32_t kMinCoverageShadowResolution = 64;  // the smallest map coverage sizing picks

enum class SplitScheme { Uniform, Logarithmic, Practical, Manual };
enum class FitMode { Stable, Tight };
enum class ShadowStrategy { PerCascade, Multiview, Layered };
// How the sun's shadow is made (docs/techniques.md): cascaded shadow maps, or a virtual
// shadow map (a clipmap of paged levels whose texels follow the pixels' footprints).
enum class ShadowTechnique { Cascades, Virtual };
// Shadow filters (docs/filters.md): comparison filters over the depth map, and moment
// filters over a prefilterable moments map converted from the depth pass.
enum class ShadowFilter { Hard, Pcf, Poisson, Pcss, Vsm, Evsm, Msm };
enum class PcssQuality { Low, Medium, High };  // 16, 25 or 49 filter taps
// Which faces of casters the shadow passes skip, seen from the light. None draws every
// face (thin and open geometry casts from both sides). FrontFaces draws the faces turned
// away from the light: a closed mesh's shadow is then its back faces' depth, far from the
// lit surface, which hides acne there ("render back faces into the shadow map"); open
// meshes then cast only from their back. BackFaces draws only the faces toward the light.
// Instances flagged double-sided are never culled.
enum class CasterCulling { None, BackFaces, FrontFaces };

struct CascadeSettings {
    int count = 4;                                // 1..kMaxCascades
    SplitScheme scheme = SplitScheme::Practical;  // PSSM (Zhang et al. 2006)
    // 0 = uniform, 1 = logarithmic. Why 0.75: with the defaults (near 0.1 m, 150 m, 4
    // cascades) the logarithmic splits are 0.6 / 3.9 / 24 m, spending a whole cascade on
    // the first 0.6 m, and the uniform ones 38 / 75 / 113 m, leaving the ground at the
    // viewer's feet with 38 m of map. 0.75 gives 9.9 / 22 / 46 m: mostly logarithmic
    // (resolution follows perspective aliasing) without collapsing the first cascade.
    float split_lambda = 0.75f;
    std::vector<float> manual_splits;  // count-1 view distances, strictly increasing
    float max_distance = 150.0f;       // cascades cover [near, min(far, max_distance)]
    FitMode fit = FitMode::Stable;
    uint32_t resolution = 2048;  // texels per side, 512..8192
    // Extra texels around a tight fit so that filter kernels never sample outside.
    float filter_padding_texels = 8.0f;
};

struct BiasSettings {
    float constant = 0.0f;  // depth-bias constant factor (units of the depth format's r)
    float slope = 2.0f;     // slope-scaled depth bias factor
    float clamp = 0.005f;   // maximum absolute depth bias (reverse-Z depth units)
    // World offset along the normal, in cascade texels. Why 0.5: docs/QUALITY.md measured
    // 0 / 0.5 / 1 / 2 / 4 against ray-traced shadows; 0.5 is acne-free with the slope bias
    // and leaks least (false lit 4.8% vs 6.7% at 1 on builtin:default, 30% vs 34% on trees).
    float normal_offset = 0.5f;
};

struct FilterSettings {
    ShadowFilter mode = ShadowFilter::Hard;
    // Receiver-plane depth bias for pcf, poisson and pcss (Isidoro 2006).
    bool receiver_plane_bias = true;
    int pcf_radius = 1;                              // 0..5: a (2R+1) x (2R+1) grid of taps
    int poisson_taps = 16;                           // 16 or 32
    float poisson_radius = 2.5f;                     // texels, 0.5..32 (also the moments' Poisson radius)
    int pcss_blocker_taps = 16;                      // 16 or 32
    PcssQuality pcss_quality = PcssQuality::Medium;  // filter taps: 16 / 25 / 49
    bool pcss_early_out = false;                     // fully shadowed when every blocker tap occludes
    float pcss_max_penumbra = 32.0f;                 // texels, 1..128 (the search radius is clamped too)
    float light_bleeding_reduction = 0.2f;           // vsm, evsm, msm: 0..0.95
    int blur_radius = 2;                             // moments blur, texels 0..8 (0 = no blur)
    bool moments_poisson = false;                    // 16 Poisson taps of the moments (poisson_radius)
    float evsm_positive_exponent = 40.0f;            // 0.1..100, clamped to the format (42 for 32-bit float)
    float evsm_negative_exponent = 5.0f;             // 0.1..100, likewise
    int evsm_components = 4;                         // 2 (positive warp only) or 4
    float msm_moment_bias = 3.0e-5f;                 // 0..0.01
    bool msm_optimized_quantization = false;         // RGBA16 moments (Peters & Klein 2015, sec. 4.3)

    // Every field: a field added later is compared without anyone remembering to.
    bool operator==(const FilterSettings&) const = default;
};

// The sun's virtual shadow map (ShadowTechnique::Virtual; docs/techniques.md, "Virtual
// shadow maps"). Level l spans first_level_extent * 2^l metres in `resolution` texels, cut
// into pages of 128^2 texels; a pool of pool_mib MiB holds the pages the frame's pixels
// need (64 KiB each), the rest of every level is never allocated.
struct VirtualShadowSettings {
    uint32_t resolution = 16384;      // virtual texels per side of every level, 1024..16384
    int levels = 16;                  // clipmap levels, 1..24
    float first_level_extent = 4.0f;  // metres across the finest level, 0.01..100000
    // A pixel samples the finest level whose texel is no larger than its footprint times
    // 2^lod_bias: negative is sharper and takes more pages.
    float lod_bias = 0.0f;
    uint32_t pool_mib = 256;  // the physical pages' memory, 16..1024 MiB (pool_mib * 16 pages)
    // Caster draws into pages one frame holds (8 bytes each), 1..2^24: with the cache, a
    // frame that needs more draws the rest in later frames, as many pages a frame as the
    // buffer holds the draws of (FrameInfo's dropped_page_draws and pages_deferred; their
    // pixels read a coarser level meanwhile). It must hold at least one page's draws.
    uint32_t page_draws = 1u << 22;
};

struct ShadowSettings {
    ShadowTechnique technique = ShadowTechnique::Cascades;
    VirtualShadowSettings virtual_maps;
    CascadeSettings cascades;
    BiasSettings bias;
    FilterSettings filter;
    float blend_width = 0.1f;  // fraction of a cascade's depth range blended into the next
    ShadowStrategy strategy = ShadowStrategy::PerCascade;
    bool cull_casters = true;
    CasterCulling caster_culling = CasterCulling::None;
    // Keep each cascade's static casters' depths from frame to frame and draw again only the
    // texels the cascade's move exposes and those of static casters that changed; dynamic
    // instances (kInstanceDynamic) are drawn over them every frame (per-cascade and layered
    // strategies; multiview ignores it). Spot and point lights keep a layer while its light,
    // near plane and size stay and no caster within its reach moved or is dynamic.
    bool cache_static_casters = false;
};

// How a light without its own `shadow_resolution` gets its map's size
// (the setting local_shadow_sizing).
enum class LocalShadowSizing {
    Coverage,  // each frame, from the light's screen coverage, up to `resolution`
    Fixed,     // always `resolution`
};

struct LocalShadowSettings {
    uint32_t budget = 8;         // shadowed local lights (0..kMaxLocalShadowBudget); the rest render unshadowed
    uint32_t resolution = 1024;  // texels per side of a light's map (16..8192; the largest with coverage sizing)
    LocalShadowSizing sizing = LocalShadowSizing::Coverage;
};

// Screen-space contact shadows (docs/techniques.md, "Contact shadows"): from each pixel of
// the caller's depth, a short ray toward the light marched through that depth buffer, for
// the shadows smaller than a shadow map's texels and biases (a plank on the ground, the
// crease where a box meets the floor). The visibility is the shadow map's times nothing
// more than the trace's: min(map, contact). A change is a uniform update (no new system).
struct ContactShadowSettings {
    bool enabled = false;      // trace at all (the lights below choose which)
    bool sun = true;           // toward the sun
    bool local_lights = true;  // toward shadowed spot and point lights
    // Metres of ray from the surface toward the light (a local light's ray stops at it).
    // Half a metre reaches the gap that a coarse cascade's texels and normal offset open
    // beside a caster's base under a high sun (docs/QUALITY.md, "Contact shadows").
    float length = 0.5f;
    // Depth-buffer samples along the ray, 4..64: 12 keep the steps (4 cm at the default
    // length) within the thickness, so no occluder of the thickness is stepped over.
    int steps = 12;
    // Metres a surface in the depth buffer is taken to extend behind itself: a sample
    // farther behind it than this passes (behind a thin pole, the ray is not blocked).
    float thickness = 0.05f;
    // Metres the ray starts off the surface along its normal: no surface shadows itself
    // through the depth buffer's own steps.
    float bias = 0.005f;
    float max_distance = 50.0f;  // view depth (metres) beyond which there are none; faded over its last fifth
};

// Everything a ShadowSystem is configured with.
struct Settings {
    ShadowSettings shadow;              // the sun's cascades, biases and the filter (every light's)
    LocalShadowSettings local_shadows;  // spot and point light shadow maps
    ContactShadowSettings contact;      // screen-space contact shadows
};

// The name a user writes for each value of a choice (--filter, [shadow] filter, ...): one
// table per enum, in the order the tools list them, read by the config reader and writer,
// the command line, the viewer's lists and the reports. A new enum value goes here once.
template <typename Enum>
struct ChoiceName {
    const char* name;
    Enum value;
};
inline constexpr ChoiceName<SplitScheme> kSplitSchemeChoices[] = {{"uniform", SplitScheme::Uniform},
                                                                  {"log", SplitScheme::Logarithmic},
                                                                  {"practical", SplitScheme::Practical},
                                                                  {"manual", SplitScheme::Manual}};
inline constexpr ChoiceName<FitMode> kFitModeChoices[] = {{"stable", FitMode::Stable}, {"tight", FitMode::Tight}};
inline constexpr ChoiceName<ShadowStrategy> kShadowStrategyChoices[] = {{"per-cascade", ShadowStrategy::PerCascade},
                                                                        {"multiview", ShadowStrategy::Multiview},
                                                                        {"layered", ShadowStrategy::Layered}};
inline constexpr ChoiceName<ShadowTechnique> kShadowTechniqueChoices[] = {{"cascades", ShadowTechnique::Cascades},
                                                                          {"virtual", ShadowTechnique::Virtual}};
inline constexpr ChoiceName<ShadowFilter> kShadowFilterChoices[] = {
    {"hard", ShadowFilter::Hard}, {"pcf", ShadowFilter::Pcf}, {"poisson", ShadowFilter::Poisson},
    {"pcss", ShadowFilter::Pcss}, {"vsm", ShadowFilter::Vsm}, {"evsm", ShadowFilter::Evsm},
    {"msm", ShadowFilter::Msm}};
inline constexpr ChoiceName<PcssQuality> kPcssQualityChoices[] = {
    {"low", PcssQuality::Low}, {"medium", PcssQuality::Medium}, {"high", PcssQuality::High}};
inline constexpr ChoiceName<CasterCulling> kCasterCullingChoices[] = {
    {"none", CasterCulling::None}, {"back", CasterCulling::BackFaces}, {"front", CasterCulling::FrontFaces}};
inline constexpr ChoiceName<LocalShadowSizing> kLocalShadowSizingChoices[] = {{"coverage", LocalShadowSizing::Coverage},
                                                                              {"fixed", LocalShadowSizing::Fixed}};

// The name of `value` in `choices` ("unknown" for a value the table lacks).
template <typename Enum, std::size_t N>
constexpr const char* choice_name(const ChoiceName<Enum> (&choices)[N], Enum value) {
    for (const ChoiceName<Enum>& choice : choices) {
        if (choice.value == value) return choice.name;
    }
    return "unknown";
}

// A choice table as a name -> value map (in name order, as error messages list them),
// built once per table.
template <typename Enum, std::size_t N>
const std::map<std::string, Enum>& choice_map(const ChoiceName<Enum> (&choices)[N]) {
    static const std::map<std::string, Enum> names = [&] {
        std::map<std::string, Enum> built;
        for (const ChoiceName<Enum>& choice : choices) built.emplace(choice.name, choice.value);
        return built;
    }();
    return names;
}

// Bits of `filters` for SettingDeclaration::filters.
constexpr uint32_t filter_bits(std::initializer_list<ShadowFilter> filters) {
    uint32_t bits = 0;
    for (const ShadowFilter filter : filters) bits |= 1u << static_cast<uint32_t>(filter);
    return bits;
}

namespace setting_conditions {
inline bool practical_splits(const Settings& s) { return s.shadow.cascades.scheme == SplitScheme::Practical; }
inline bool manual_splits(const Settings& s) { return s.shadow.cascades.scheme == SplitScheme::Manual; }
inline bool tight_fit(const Settings& s) { return s.shadow.cascades.fit == FitMode::Tight; }
inline bool virtual_maps(const Settings& s) { return s.shadow.technique == ShadowTechnique::Virtual; }
inline bool contact_shadows(const Settings& s) { return s.contact.enabled; }
// The Poisson radius serves the poisson filter and the moment filters' Poisson taps.
inline bool poisson_disk(const Settings& s) {
    return s.shadow.filter.mode == ShadowFilter::Poisson || s.shadow.filter.moments_poisson;
}
}  // namespace setting_conditions

inline constexpr int64_t kSixteenOrThirtyTwo[] = {16, 32};
inline constexpr int64_t kTwoOrFour[] = {2, 4};
inline constexpr uint32_t kMomentFilters = filter_bits({ShadowFilter::Vsm, ShadowFilter::Evsm, ShadowFilter::Msm});

// Every setting of Settings, in the order config files and reports list them. A field's
// default is its initializer above; `effect` says what a change of it rebuilds inside a
// ShadowSystem (SettingEffect: nothing, pipelines, or maps; the scene is kept for each).
inline constexpr SettingDeclaration kSettingDeclarations[] = {
    // The sun's technique and its virtual shadow map (docs/techniques.md).
    declare_choice<kShadowTechniqueChoices, &Settings::shadow, &ShadowSettings::technique>(
        {.name = "shadow_technique", .effect = SettingEffect::Resource}),
    declare<&Settings::shadow, &ShadowSettings::virtual_maps, &VirtualShadowSettings::resolution>(
        {.name = "virtual_resolution",
         .minimum = 1024,
         .maximum = 16384,
         .effect = SettingEffect::Resource,
         .applies_when = setting_conditions::virtual_maps}),
    declare<&Settings::shadow, &ShadowSettings::virtual_maps, &VirtualShadowSettings::levels>(
        {.name = "virtual_levels",
         .minimum = 1,
         .maximum = 24,
         .effect = SettingEffect::Resource,
         .applies_when = setting_conditions::virtual_maps}),
    declare<&Settings::shadow, &ShadowSettings::virtual_maps, &VirtualShadowSettings::first_level_extent>(
        {.name = "virtual_first_extent",
         .minimum = 0.01,
         .maximum = 1.0e5,
         .applies_when = setting_conditions::virtual_maps}),
    declare<&Settings::shadow, &ShadowSettings::virtual_maps, &VirtualShadowSettings::lod_bias>(
        {.name = "virtual_lod_bias", .minimum = -4, .maximum = 4, .applies_when = setting_conditions::virtual_maps}),
    declare<&Settings::shadow, &ShadowSettings::virtual_maps, &VirtualShadowSettings::pool_mib>(
        {.name = "virtual_pool_mib",
         .minimum = 16,
         .maximum = 1024,
         .effect = SettingEffect::Resource,
         .applies_when = setting_conditions::virtual_maps}),
    declare<&Settings::shadow, &ShadowSettings::virtual_maps, &VirtualShadowSettings::page_draws>(
        {.name = "virtual_page_draws",
         .minimum = 1,
         .maximum = 1 << 24,
         .effect = SettingEffect::Resource,
         .applies_when = setting_conditions::virtual_maps}),
    // The sun's cascades (docs/techniques.md).
    declare<&Settings::shadow, &ShadowSettings::cascades, &CascadeSettings::count>(
        {.name = "cascades", .minimum = 1, .maximum = kMaxCascades, .effect = SettingEffect::Resource}),
    declare<&Settings::shadow, &ShadowSettings::cascades, &CascadeSettings::resolution>(
        {.name = "shadow_resolution", .minimum = 512, .maximum = 8192, .effect = SettingEffect::Resource}),
    declare_choice<kSplitSchemeChoices, &Settings::shadow, &ShadowSettings::cascades, &CascadeSettings::scheme>(
        {.name = "split_scheme"}),
    declare<&Settings::shadow, &ShadowSettings::cascades, &CascadeSettings::split_lambda>(
        {.name = "split_lambda", .minimum = 0, .maximum = 1, .applies_when = setting_conditions::practical_splits}),
    declare<&Settings::shadow, &ShadowSettings::cascades, &CascadeSettings::manual_splits>(
        {.name = "splits", .applies_when = setting_conditions::manual_splits}),
    declare<&Settings::shadow, &ShadowSettings::cascades, &CascadeSettings::max_distance>(
        {.name = "max_distance", .minimum = 0, .minimum_exclusive = true}),
    declare_choice<kFitModeChoices, &Settings::shadow, &ShadowSettings::cascades, &CascadeSettings::fit>(
        {.name = "fit"}),
    declare<&Settings::shadow, &ShadowSettings::cascades, &CascadeSettings::filter_padding_texels>(
        {.name = "filter_padding", .minimum = 0, .maximum = 64, .applies_when = setting_conditions::tight_fit}),
    // Biases, blending and the shadow passes (docs/techniques.md).
    declare<&Settings::shadow, &ShadowSettings::bias, &BiasSettings::constant>(
        {.name = "constant_bias", .minimum = 0, .maximum = 1.0e5}),
    declare<&Settings::shadow, &ShadowSettings::bias, &BiasSettings::slope>(
        {.name = "slope_bias", .minimum = 0, .maximum = 20}),
    declare<&Settings::shadow, &ShadowSettings::bias, &BiasSettings::clamp>(
        {.name = "bias_clamp", .minimum = 0, .maximum = 0.1}),
    declare<&Settings::shadow, &ShadowSettings::bias, &BiasSettings::normal_offset>(
        {.name = "normal_offset", .minimum = 0, .maximum = 10}),
    declare<&Settings::shadow, &ShadowSettings::blend_width>({.name = "blend_width", .minimum = 0, .maximum = 0.5}),
    declare_choice<kShadowStrategyChoices, &Settings::shadow, &ShadowSettings::strategy>(
        {.name = "strategy", .effect = SettingEffect::Resource}),
    declare<&Settings::shadow, &ShadowSettings::cull_casters>({.name = "cull_casters"}),
    declare_choice<kCasterCullingChoices, &Settings::shadow, &ShadowSettings::caster_culling>(
        {.name = "caster_culling"}),
    declare<&Settings::shadow, &ShadowSettings::cache_static_casters>(
        {.name = "shadow_cache", .effect = SettingEffect::Resource}),
    // The filter and its parameters, for every light (docs/filters.md).
    declare_choice<kShadowFilterChoices, &Settings::shadow, &ShadowSettings::filter, &FilterSettings::mode>(
        {.name = "filter", .effect = SettingEffect::Resource}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::receiver_plane_bias>(
        {.name = "receiver_plane_bias",
         .effect = SettingEffect::Pipeline,
         .filters = filter_bits({ShadowFilter::Pcf, ShadowFilter::Poisson, ShadowFilter::Pcss})}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::pcf_radius>(
        {.name = "pcf_radius", .minimum = 0, .maximum = kMaxPcfRadius, .filters = filter_bits({ShadowFilter::Pcf})}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::poisson_taps>(
        {.name = "poisson_taps",
         .allowed = kSixteenOrThirtyTwo,
         .effect = SettingEffect::Pipeline,
         .filters = filter_bits({ShadowFilter::Poisson})}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::poisson_radius>(
        {.name = "poisson_radius", .minimum = 0.5, .maximum = 32, .applies_when = setting_conditions::poisson_disk}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::pcss_blocker_taps>(
        {.name = "pcss_blocker_taps",
         .allowed = kSixteenOrThirtyTwo,
         .effect = SettingEffect::Pipeline,
         .filters = filter_bits({ShadowFilter::Pcss})}),
    declare_choice<kPcssQualityChoices, &Settings::shadow, &ShadowSettings::filter, &FilterSettings::pcss_quality>(
        {.name = "pcss_quality", .effect = SettingEffect::Pipeline, .filters = filter_bits({ShadowFilter::Pcss})}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::pcss_early_out>(
        {.name = "pcss_early_out", .effect = SettingEffect::Pipeline, .filters = filter_bits({ShadowFilter::Pcss})}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::pcss_max_penumbra>(
        {.name = "pcss_max_penumbra", .minimum = 1, .maximum = 128, .filters = filter_bits({ShadowFilter::Pcss})}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::light_bleeding_reduction>(
        {.name = "light_bleeding_reduction", .minimum = 0, .maximum = 0.95, .filters = kMomentFilters}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::blur_radius>(
        {.name = "blur_radius",
         .minimum = 0,
         .maximum = 8,
         .effect = SettingEffect::Resource,
         .filters = kMomentFilters}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::moments_poisson>(
        {.name = "moments_poisson", .effect = SettingEffect::Pipeline, .filters = kMomentFilters}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::evsm_positive_exponent>(
        {.name = "evsm_positive_exponent",
         .minimum = 0.1,
         .maximum = 100,
         .filters = filter_bits({ShadowFilter::Evsm})}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::evsm_negative_exponent>(
        {.name = "evsm_negative_exponent",
         .minimum = 0.1,
         .maximum = 100,
         .filters = filter_bits({ShadowFilter::Evsm})}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::evsm_components>(
        {.name = "evsm_components",
         .allowed = kTwoOrFour,
         .effect = SettingEffect::Resource,
         .filters = filter_bits({ShadowFilter::Evsm})}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::msm_moment_bias>(
        {.name = "msm_moment_bias", .minimum = 0, .maximum = 0.01, .filters = filter_bits({ShadowFilter::Msm})}),
    declare<&Settings::shadow, &ShadowSettings::filter, &FilterSettings::msm_optimized_quantization>(
        {.name = "msm_optimized_quantization",
         .effect = SettingEffect::Resource,
         .filters = filter_bits({ShadowFilter::Msm})}),
    // Spot and point light shadow maps (docs/local-lights.md).
    declare<&Settings::local_shadows, &LocalShadowSettings::budget>({.name = "local_shadow_budget",
                                                                     .minimum = 0,
                                                                     .maximum = kMaxLocalShadowBudget,
                                                                     .effect = SettingEffect::Resource}),
    declare<&Settings::local_shadows, &LocalShadowSettings::resolution>(
        {.name = "local_shadow_resolution", .minimum = 16, .maximum = 8192, .effect = SettingEffect::Resource}),
    declare_choice<kLocalShadowSizingChoices, &Settings::local_shadows, &LocalShadowSettings::sizing>(
        {.name = "local_shadow_sizing", .effect = SettingEffect::Resource}),
    // Screen-space contact shadows (docs/techniques.md): uniforms only.
    declare<&Settings::contact, &ContactShadowSettings::enabled>({.name = "contact_shadows"}),
    declare<&Settings::contact, &ContactShadowSettings::sun>(
        {.name = "contact_sun", .applies_when = setting_conditions::contact_shadows}),
    declare<&Settings::contact, &ContactShadowSettings::local_lights>(
        {.name = "contact_local_lights", .applies_when = setting_conditions::contact_shadows}),
    declare<&Settings::contact, &ContactShadowSettings::length>({.name = "contact_length",
                                                                 .minimum = 0.001,
                                                                 .maximum = 100,
                                                                 .applies_when = setting_conditions::contact_shadows}),
    declare<&Settings::contact, &ContactShadowSettings::steps>(
        {.name = "contact_steps", .minimum = 4, .maximum = 64, .applies_when = setting_conditions::contact_shadows}),
    declare<&Settings::contact, &ContactShadowSettings::thickness>(
        {.name = "contact_thickness",
         .minimum = 0.0001,
         .maximum = 100,
         .applies_when = setting_conditions::contact_shadows}),
    declare<&Settings::contact, &ContactShadowSettings::bias>(
        {.name = "contact_bias", .minimum = 0, .maximum = 10, .applies_when = setting_conditions::contact_shadows}),
    declare<&Settings::contact, &ContactShadowSettings::max_distance>(
        {.name = "contact_distance",
         .minimum = 0,
         .maximum = 1.0e6,
         .minimum_exclusive = true,
         .applies_when = setting_conditions::contact_shadows}),
};

// The tables above as name -> value maps.
const std::map<std::string, SplitScheme>& split_scheme_names();
const std::map<std::string, FitMode>& fit_mode_names();
const std::map<std::string, ShadowStrategy>& shadow_strategy_names();
const std::map<std::string, ShadowTechnique>& shadow_technique_names();
const std::map<std::string, ShadowFilter>& shadow_filter_names();
const std::map<std::string, PcssQuality>& pcss_quality_names();
const std::map<std::string, LocalShadowSizing>& local_shadow_sizing_names();
const std::map<std::string, CasterCulling>& caster_culling_names();

// vsm, evsm and msm sample a moments map instead of comparing against the depth map.
bool is_moment_filter(ShadowFilter filter);

// Throws InputError("<origin>: <setting>: <problem>") for any out-of-range or NaN value.
// Manual splits (checked only for SplitScheme::Manual) must be count - 1 finite values,
// strictly increasing, inside (0, max_distance).
void validate_shadow_settings(const ShadowSettings& settings, const std::string& origin);
void validate_local_shadow_settings(const LocalShadowSettings& settings, const std::string& origin);
void validate_settings(const Settings& settings, const std::string& origin);

// The largest effect (SettingDeclaration::effect) among the settings that differ between
// `current` and `next`; Live when none differ. ShadowSystem::update_settings() takes every
// change and keeps the scene: Live ones are uniforms, Pipeline ones rebuild Penumbra's
// pipelines, Resource ones its maps.
SettingEffect settings_change_effect(const Settings& current, const Settings& next);

}  // namespace penumbra
