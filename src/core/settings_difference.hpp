#pragma once
// What differs between two Settings, found in one pass over the declarations: whether
// anything does (caches hold depths that any setting may change) and the largest
// SettingEffect among what does (settings_change_effect()).
#include "penumbra/settings.hpp"

namespace penumbra::core {

struct SettingsDifference {
    bool any = false;
    SettingEffect effect = SettingEffect::Live;
};

SettingsDifference compare_settings(const Settings& current, const Settings& next);

}  // namespace penumbra::core
