// The settings sections of the viewer panel: one control per setting, made from its
// declaration (kSettingDeclarations): checkbox, list, slider or drag by its type and range,
// shown only where the setting applies (the filter's own parameters, practical splits...).
#include <imgui.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "panel.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/scene/setting_presentation.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::view {
namespace {

template <typename Enum, size_t N>
void combo(const char* label, Enum& value, const std::array<const char*, N>& names) {
    int index = static_cast<int>(value);
    if (ImGui::Combo(label, &index, names.data(), static_cast<int>(N))) value = static_cast<Enum>(index);
}

// Switching to manual splits starts from the splits of the last frame (the one
// NumberList setting: cascades - 1 distances below max_distance).
void manual_splits_control(Settings& settings, const renderer::FrameInfo* frame) {
    CascadeSettings& cascades = settings.shadow.cascades;
    const size_t wanted = static_cast<size_t>(cascades.count - 1);
    if (cascades.manual_splits.size() != wanted) {
        cascades.manual_splits.clear();
        if (frame && frame->cascades.size() == static_cast<size_t>(cascades.count)) {
            for (size_t i = 0; i < wanted; ++i) cascades.manual_splits.push_back(frame->cascades[i].split_far);
        } else {
            for (size_t i = 0; i < wanted; ++i) {
                cascades.manual_splits.push_back(cascades.max_distance * static_cast<float>(i + 1) / (wanted + 1));
            }
        }
    }
    for (size_t i = 0; i < cascades.manual_splits.size(); ++i) {
        ImGui::PushID(static_cast<int>(i));
        ImGui::DragFloat("split (m)", &cascades.manual_splits[i], 0.1f, 0.01f, cascades.max_distance, "%.2f");
        ImGui::PopID();
    }
}

const char* label_of(const SettingDeclaration& setting) { return presentation_of(setting).label; }

void choice_control(const SettingDeclaration& setting, Settings& settings) {
    const SettingValue current = setting.get(settings);
    int index = 0;
    for (size_t i = 0; i < setting.choices.size(); ++i) {
        if (current == SettingValue(std::string(setting.choices[i]))) index = static_cast<int>(i);
    }
    if (ImGui::Combo(label_of(setting), &index, setting.choices.data(), static_cast<int>(setting.choices.size()))) {
        setting.set(settings, std::string(setting.choices[index]));
    }
}

// Integers limited to a few values (tap counts, components).
void allowed_values_control(const SettingDeclaration& setting, Settings& settings) {
    const int64_t current = std::get<int64_t>(setting.get(settings));
    std::vector<std::string> names;
    std::vector<const char*> items;
    int index = 0;
    for (const int64_t value : setting.allowed) {
        if (value == current) index = static_cast<int>(names.size());
        names.push_back(std::to_string(value));
    }
    for (const std::string& name : names) items.push_back(name.c_str());
    if (ImGui::Combo(label_of(setting), &index, items.data(), static_cast<int>(items.size()))) {
        setting.set(settings, setting.allowed[static_cast<size_t>(index)]);
    }
}

// A map size: a slider over powers of two, labelled with the size itself (which need not
// be a power of two when it came from a file or a flag).
void power_of_two_control(const SettingDeclaration& setting, Settings& settings) {
    const auto current = static_cast<uint64_t>(std::get<int64_t>(setting.get(settings)));
    const int lowest = std::bit_width(static_cast<uint64_t>(setting.minimum)) - 1;
    const int highest = std::bit_width(static_cast<uint64_t>(setting.maximum)) - 1;
    int exponent = std::clamp(static_cast<int>(std::bit_width(current)) - 1, lowest, highest);
    const std::string label = std::to_string(current) + " texels";
    if (ImGui::SliderInt(label_of(setting), &exponent, lowest, highest, label.c_str())) {
        setting.set(settings, int64_t{1} << exponent);
    }
}

void integer_control(const SettingDeclaration& setting, Settings& settings) {
    if (!setting.allowed.empty()) return allowed_values_control(setting, settings);
    if (presentation_of(setting).powers_of_two) return power_of_two_control(setting, settings);
    int value = static_cast<int>(std::get<int64_t>(setting.get(settings)));
    if (ImGui::SliderInt(label_of(setting), &value, static_cast<int>(setting.minimum),
                         static_cast<int>(setting.maximum))) {
        setting.set(settings, int64_t{value});
    }
}

// A slider over a bounded range; a drag for open or very wide ranges (distances, the
// constant bias's 0..1e5), whose step is a thousandth of the range or half a unit.
void number_control(const SettingDeclaration& setting, Settings& settings) {
    auto value = static_cast<float>(std::get<double>(setting.get(settings)));
    const bool bounded = std::isfinite(setting.minimum) && std::isfinite(setting.maximum);
    bool changed = false;
    if (bounded && setting.maximum - setting.minimum <= 1000.0 && !setting.minimum_exclusive) {
        changed = ImGui::SliderFloat(label_of(setting), &value, static_cast<float>(setting.minimum),
                                     static_cast<float>(setting.maximum), "%.4g");
    } else {
        const double lowest = setting.minimum_exclusive ? setting.minimum + 0.01 : setting.minimum;
        const double highest = std::isfinite(setting.maximum) ? setting.maximum : 1.0e4;
        const float speed = bounded ? static_cast<float>((highest - lowest) / 1.0e5) : 0.5f;
        changed = ImGui::DragFloat(label_of(setting), &value, speed, static_cast<float>(lowest),
                                   static_cast<float>(highest), "%.4g");
    }
    if (changed) setting.set(settings, static_cast<double>(value));
}

void setting_control(const SettingDeclaration& setting, Settings& settings, const renderer::FrameInfo* frame) {
    switch (setting.type) {
        case SettingType::Boolean: {
            bool value = std::get<bool>(setting.get(settings));
            if (ImGui::Checkbox(label_of(setting), &value)) setting.set(settings, value);
            break;
        }
        case SettingType::Choice:
            choice_control(setting, settings);
            break;
        case SettingType::Integer:
            integer_control(setting, settings);
            break;
        case SettingType::Number:
            number_control(setting, settings);
            break;
        case SettingType::NumberList:
            manual_splits_control(settings, frame);
            break;
    }
    const char* help = presentation_of(setting).help;
    if (ImGui::IsItemHovered() && *help != '\0') ImGui::SetTooltip("%s", help);
}

}  // namespace

void draw_setting_group(Settings& settings, std::string_view group, const renderer::FrameInfo* frame) {
    for (const SettingDeclaration& setting : kSettingDeclarations) {
        if (group == presentation_of(setting).group && setting_applies(setting, settings))
            setting_control(setting, settings, frame);
    }
}

void draw_shadow_settings(RenderSettings& settings, const renderer::FrameInfo* frame) {
    if (ImGui::CollapsingHeader("Technique", ImGuiTreeNodeFlags_DefaultOpen))
        draw_setting_group(settings, "virtual", frame);
    if (ImGui::CollapsingHeader("Cascades", ImGuiTreeNodeFlags_DefaultOpen))
        draw_setting_group(settings, "cascades", frame);
    if (ImGui::CollapsingHeader("Bias and blending", ImGuiTreeNodeFlags_DefaultOpen)) {
        draw_setting_group(settings, "bias", frame);
    }
    if (ImGui::CollapsingHeader("Filter", ImGuiTreeNodeFlags_DefaultOpen)) {
        setting_control(*find_output_setting("resolve"), settings, frame);
        draw_setting_group(settings, "filter", frame);
    }
    // Turning them on or off makes a new renderer (they need the depth pre-pass); the
    // automatic resolve traces them in the deferred resolve.
    if (ImGui::CollapsingHeader("Contact shadows")) draw_setting_group(settings, "contact", frame);
    if (ImGui::CollapsingHeader("Debug view", ImGuiTreeNodeFlags_DefaultOpen)) {
        combo("debug view", settings.debug,
              std::array<const char*, 4>{"none", "cascade colours", "shadow-map layers", "virtual pages"});
    }
}

}  // namespace penumbra::view
