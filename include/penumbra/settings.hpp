#pragma once
// The settings of a ShadowSystem: one struct, Settings, with named fields and documented
// defaults and ranges (docs/library.md, docs/techniques.md, docs/filters.md). The CLI's
// scene files, config files and flags fill the same structs. validate_settings() rejects
// out-of-range values with an InputError naming the setting; requires_recreation() tells
// which changes need a new ShadowSystem (they size or specialise GPU resources).
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace penumbra {

inline constexpr int kMaxCascades = 8;   // cascades of the sun's shadow map
inline constexpr int kMaxPcfRadius = 5;  // FilterSettings::pcf_radius

// Spot and point lights (docs/local-lights.md).
inline constexpr uint32_t kMaxLights = 256;             // lights one ShadowSystem takes (set_lights)
inline constexpr uint32_t kMaxLocalShadowBudget = 32;   // shadowed spot/point lights per frame
inline constexpr uint32_t kMaxLocalShadowLayers = 192;  // 32 point lights x 6 faces (Vulkan guarantees 256 layers)
inline constexpr uint32_t kMinCoverageShadowResolution = 64;  // the smallest map coverage sizing picks

enum class SplitScheme { Uniform, Logarithmic, Practical, Manual };
enum class FitMode { Stable, Tight };
enum class ShadowStrategy { PerCascade, Multiview };
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

struct ShadowSettings {
    CascadeSettings cascades;
    BiasSettings bias;
    FilterSettings filter;
    float blend_width = 0.1f;  // fraction of a cascade's depth range blended into the next
    ShadowStrategy strategy = ShadowStrategy::PerCascade;
    bool cull_casters = true;
    CasterCulling caster_culling = CasterCulling::None;
};

// The names validate_shadow_settings() uses for each setting in its messages; config and
// CLI parsers use the same keys so that a message points at what the user wrote.
namespace shadow_keys {
inline constexpr const char* kCascades = "cascades";             // CascadeSettings::count
inline constexpr const char* kResolution = "shadow_resolution";  // 512..8192
inline constexpr const char* kSplitLambda = "split_lambda";      // 0..1
inline constexpr const char* kSplits = "splits";                 // manual_splits
inline constexpr const char* kMaxDistance = "max_distance";      // > 0, finite
inline constexpr const char* kFilterPadding = "filter_padding";  // 0..64 texels
inline constexpr const char* kSlopeBias = "slope_bias";          // 0..20
inline constexpr const char* kConstantBias = "constant_bias";    // 0..1e5
inline constexpr const char* kBiasClamp = "bias_clamp";          // 0..0.1
inline constexpr const char* kNormalOffset = "normal_offset";    // 0..10 texels
inline constexpr const char* kBlendWidth = "blend_width";        // 0..0.5
inline constexpr const char* kFilter = "filter";
inline constexpr const char* kReceiverPlaneBias = "receiver_plane_bias";
inline constexpr const char* kPcfRadius = "pcf_radius";                         // 0..5
inline constexpr const char* kPoissonTaps = "poisson_taps";                     // 16 or 32
inline constexpr const char* kPoissonRadius = "poisson_radius";                 // 0.5..32 texels
inline constexpr const char* kPcssBlockerTaps = "pcss_blocker_taps";            // 16 or 32
inline constexpr const char* kPcssQuality = "pcss_quality";                     // low|medium|high
inline constexpr const char* kPcssEarlyOut = "pcss_early_out";                  // bool
inline constexpr const char* kPcssMaxPenumbra = "pcss_max_penumbra";            // 1..128 texels
inline constexpr const char* kLightBleeding = "light_bleeding_reduction";       // 0..0.95
inline constexpr const char* kBlurRadius = "blur_radius";                       // 0..8 texels
inline constexpr const char* kMomentsPoisson = "moments_poisson";               // bool
inline constexpr const char* kEvsmPositiveExponent = "evsm_positive_exponent";  // 0.1..100
inline constexpr const char* kEvsmNegativeExponent = "evsm_negative_exponent";  // 0.1..100
inline constexpr const char* kEvsmComponents = "evsm_components";               // 2 or 4
inline constexpr const char* kMsmMomentBias = "msm_moment_bias";                // 0..0.01
inline constexpr const char* kMsmQuantization = "msm_optimized_quantization";   // bool
}  // namespace shadow_keys

// How a light without its own `shadow_resolution` gets its map's size
// (`--local-shadow-sizing`, `[shadow] local_shadow_sizing`).
enum class LocalShadowSizing {
    Coverage,  // each frame, from the light's screen coverage, up to `resolution`
    Fixed,     // always `resolution`
};

struct LocalShadowSettings {
    uint32_t budget = 8;         // shadowed local lights (0..kMaxLocalShadowBudget); the rest render unshadowed
    uint32_t resolution = 1024;  // texels per side of a light's map (16..8192; the largest with coverage sizing)
    LocalShadowSizing sizing = LocalShadowSizing::Coverage;
};

// Everything a ShadowSystem is configured with.
struct Settings {
    ShadowSettings shadow;              // the sun's cascades, biases and the filter (every light's)
    LocalShadowSettings local_shadows;  // spot and point light shadow maps
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
                                                                        {"multiview", ShadowStrategy::Multiview}};
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

// The tables above as name -> value maps.
const std::map<std::string, SplitScheme>& split_scheme_names();
const std::map<std::string, FitMode>& fit_mode_names();
const std::map<std::string, ShadowStrategy>& shadow_strategy_names();
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

// True when going from `current` to `next` changes what a ShadowSystem creates once: the
// cascade count or resolution, the filter and its tap counts (pipelines, moments maps and
// the specialization of the caller's shaders), the shadow strategy, or the local shadow
// budget, resolution and sizing. Every other setting may change between frames
// (ShadowSystem::update_settings).
bool requires_recreation(const Settings& current, const Settings& next);

}  // namespace penumbra
