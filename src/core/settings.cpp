// The public settings' validation and recreation rule, read from their declarations
// (kSettingDeclarations). Every message names the origin, the setting as the user writes
// it, the offending value and the allowed range, on one line.
#include "penumbra/settings.hpp"

#include <sstream>

#include "core/settings_difference.hpp"
#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

[[noreturn]] void reject(const std::string& origin, const char* key, const std::string& problem) {
    throw InputError(origin + ": " + key + ": " + problem);
}

// Manual splits (the one check across settings): count - 1 values, strictly increasing
// inside (0, max_distance).
void validate_manual_splits(const CascadeSettings& cascades, const std::string& origin) {
    const char* key = "splits";
    const size_t expected = static_cast<size_t>(cascades.count - 1);
    if (cascades.manual_splits.size() != expected) {
        std::ostringstream problem;
        problem << cascades.manual_splits.size() << " values given, " << cascades.count << " cascades need exactly "
                << expected;
        reject(origin, key, problem.str());
    }
    float previous = 0.0f;
    for (const float split : cascades.manual_splits) {
        if (!(split > previous) || !(split < cascades.max_distance)) {
            std::ostringstream problem;
            problem << split << " must be greater than the previous split (" << previous
                    << ") and less than max_distance (" << cascades.max_distance
                    << "); splits are strictly increasing view distances";
            reject(origin, key, problem.str());
        }
        previous = split;
    }
}

}  // namespace

void validate_settings(const Settings& settings, const std::string& origin) {
    for (const SettingDeclaration& setting : kSettingDeclarations) {
        const std::string problem = setting_value_problem(setting, setting.get(settings));
        if (!problem.empty()) reject(origin, setting.name, problem);
    }
    if (settings.shadow.cascades.scheme == SplitScheme::Manual)
        validate_manual_splits(settings.shadow.cascades, origin);
    // The moments filters prefilter a whole map (convert, blur); a virtual shadow map's
    // pages are scattered over its pool, and filtering across page edges would need each
    // page's neighbours (docs/filters.md).
    if (settings.shadow.technique == ShadowTechnique::Virtual && is_moment_filter(settings.shadow.filter.mode)) {
        reject(origin, "filter",
               std::string(choice_name(kShadowFilterChoices, settings.shadow.filter.mode)) +
                   " is not available with shadow_technique virtual (use hard, pcf, poisson or pcss)");
    }
}

void validate_shadow_settings(const ShadowSettings& settings, const std::string& origin) {
    validate_settings(Settings{settings, LocalShadowSettings{}}, origin);
}

void validate_local_shadow_settings(const LocalShadowSettings& settings, const std::string& origin) {
    validate_settings(Settings{ShadowSettings{}, settings}, origin);
}

const std::map<std::string, SplitScheme>& split_scheme_names() { return choice_map(kSplitSchemeChoices); }
const std::map<std::string, FitMode>& fit_mode_names() { return choice_map(kFitModeChoices); }
const std::map<std::string, ShadowStrategy>& shadow_strategy_names() { return choice_map(kShadowStrategyChoices); }
const std::map<std::string, ShadowTechnique>& shadow_technique_names() { return choice_map(kShadowTechniqueChoices); }
const std::map<std::string, ShadowFilter>& shadow_filter_names() { return choice_map(kShadowFilterChoices); }
const std::map<std::string, PcssQuality>& pcss_quality_names() { return choice_map(kPcssQualityChoices); }
const std::map<std::string, LocalShadowSizing>& local_shadow_sizing_names() {
    return choice_map(kLocalShadowSizingChoices);
}
const std::map<std::string, CasterCulling>& caster_culling_names() { return choice_map(kCasterCullingChoices); }

bool is_moment_filter(ShadowFilter filter) {
    return filter == ShadowFilter::Vsm || filter == ShadowFilter::Evsm || filter == ShadowFilter::Msm;
}

SettingEffect settings_change_effect(const Settings& current, const Settings& next) {
    return core::compare_settings(current, next).effect;
}

core::SettingsDifference core::compare_settings(const Settings& current, const Settings& next) {
    SettingsDifference difference;
    for (const SettingDeclaration& setting : kSettingDeclarations) {
        if (setting.get(current) == setting.get(next)) continue;
        difference.any = true;
        if (setting.effect > difference.effect) difference.effect = setting.effect;
    }
    return difference;
}

}  // namespace penumbra
