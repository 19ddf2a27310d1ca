#include "penumbra/scene/setting_presentation.hpp"

#include <stdexcept>
#include <string>

namespace penumbra {

const SettingPresentation* find_presentation(std::string_view name) {
    for (const SettingPresentation& presentation : kSettingPresentations) {
        if (name == presentation.name) return &presentation;
    }
    return nullptr;
}

const SettingPresentation& presentation_of(const SettingDeclaration& setting) {
    if (const SettingPresentation* presentation = find_presentation(setting.name)) return *presentation;
    // A declaration added without its presentation: a defect the unit tests catch.
    throw std::logic_error(std::string("the setting \"") + setting.name + "\" has no SettingPresentation");
}

}  // namespace penumbra
