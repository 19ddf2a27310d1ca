// The settings sections of the viewer panel: one control per field of ShadowSettings.
#include <imgui.h>

#include <algorithm>
#include <array>
#include <string>

#include "panel.hpp"
#include "penumbra/scene/render_settings.hpp"
#include "penumbra/settings.hpp"

namespace penumbra::view {
namespace {

template <typename Enum, size_t N>
void combo(const char* label, Enum& value, const std::array<const char*, N>& names) {
    int index = static_cast<int>(value);
    if (ImGui::Combo(label, &index, names.data(), static_cast<int>(N))) value = static_cast<Enum>(index);
}

// A setting's choice from its table (penumbra/settings.hpp), matched by value, not by the
// enum's numbering, so the list cannot drift from the values.
template <typename Enum, size_t N>
void combo(const char* label, Enum& value, const ChoiceName<Enum> (&choices)[N]) {
    std::array<const char*, N> names{};
    int index = 0;
    for (size_t i = 0; i < N; ++i) {
        names[i] = choices[i].name;
        if (choices[i].value == value) index = static_cast<int>(i);
    }
    if (ImGui::Combo(label, &index, names.data(), static_cast<int>(N))) value = choices[index].value;
}

// A choice between two integer values (tap counts, component counts).
void two_choice(const char* label, int& value, int first, int second) {
    const std::string a = std::to_string(first);
    const std::string b = std::to_string(second);
    const std::array<const char*, 2> names{a.c_str(), b.c_str()};
    int index = value == second ? 1 : 0;
    if (ImGui::Combo(label, &index, names.data(), 2)) value = index == 1 ? second : first;
}

void resolution_combo(uint32_t& resolution) {
    static constexpr std::array<uint32_t, 5> kSizes{512, 1024, 2048, 4096, 8192};
    static constexpr std::array<const char*, 5> kNames{"512", "1024", "2048", "4096", "8192"};
    int index = static_cast<int>(std::find(kSizes.begin(), kSizes.end(), resolution) - kSizes.begin());
    if (index >= static_cast<int>(kSizes.size())) index = 2;
    if (ImGui::Combo("resolution", &index, kNames.data(), static_cast<int>(kNames.size()))) resolution = kSizes[index];
}

// Switching to manual splits starts from the splits of the last frame.
void manual_splits(CascadeSettings& cascades, const renderer::FrameInfo* frame) {
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

void cascade_section(CascadeSettings& cascades, const renderer::FrameInfo* frame) {
    if (!ImGui::CollapsingHeader("Cascades", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::SliderInt("cascades", &cascades.count, 1, 8);
    resolution_combo(cascades.resolution);
    combo("split scheme", cascades.scheme, kSplitSchemeChoices);
    if (cascades.scheme == SplitScheme::Practical)
        ImGui::SliderFloat("split lambda", &cascades.split_lambda, 0.0f, 1.0f);
    if (cascades.scheme == SplitScheme::Manual) manual_splits(cascades, frame);
    ImGui::DragFloat("max distance (m)", &cascades.max_distance, 0.5f, 1.0f, 10000.0f, "%.1f");
    combo("fit", cascades.fit, kFitModeChoices);
}

void bias_section(ShadowSettings& shadow) {
    if (!ImGui::CollapsingHeader("Bias and blending", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::SliderFloat("slope bias", &shadow.bias.slope, 0.0f, 20.0f);
    ImGui::DragFloat("constant bias", &shadow.bias.constant, 1.0f, 0.0f, 100000.0f, "%.1f");
    ImGui::SliderFloat("bias clamp", &shadow.bias.clamp, 0.0f, 0.1f, "%.4f");
    ImGui::SliderFloat("normal offset (texels)", &shadow.bias.normal_offset, 0.0f, 10.0f);
    ImGui::SliderFloat("blend width", &shadow.blend_width, 0.0f, 0.5f);
    combo("strategy", shadow.strategy, kShadowStrategyChoices);
    ImGui::Checkbox("cull casters", &shadow.cull_casters);
    combo("caster face culling", shadow.caster_culling, kCasterCullingChoices);
}

void comparison_filter_controls(FilterSettings& filter) {
    if (filter.mode == ShadowFilter::Pcf) ImGui::SliderInt("PCF radius", &filter.pcf_radius, 0, 5);
    if (filter.mode == ShadowFilter::Poisson) {
        two_choice("Poisson taps", filter.poisson_taps, 16, 32);
        ImGui::SliderFloat("Poisson radius (texels)", &filter.poisson_radius, 0.5f, 32.0f);
    }
    if (filter.mode == ShadowFilter::Pcss) {
        combo("PCSS quality", filter.pcss_quality, kPcssQualityChoices);
        two_choice("blocker taps", filter.pcss_blocker_taps, 16, 32);
        ImGui::Checkbox("PCSS early out", &filter.pcss_early_out);
        ImGui::SliderFloat("max penumbra (texels)", &filter.pcss_max_penumbra, 1.0f, 128.0f);
    }
    if (filter.mode == ShadowFilter::Pcf || filter.mode == ShadowFilter::Poisson || filter.mode == ShadowFilter::Pcss) {
        ImGui::Checkbox("receiver-plane bias", &filter.receiver_plane_bias);
    }
}

void moment_filter_controls(FilterSettings& filter) {
    if (!is_moment_filter(filter.mode)) return;
    ImGui::SliderFloat("light-bleeding reduction", &filter.light_bleeding_reduction, 0.0f, 0.95f);
    ImGui::SliderInt("blur radius (texels)", &filter.blur_radius, 0, 8);
    ImGui::Checkbox("Poisson taps of the moments", &filter.moments_poisson);
    if (filter.moments_poisson) ImGui::SliderFloat("Poisson radius (texels)", &filter.poisson_radius, 0.5f, 32.0f);
    if (filter.mode == ShadowFilter::Evsm) {
        ImGui::SliderFloat("EVSM positive exponent", &filter.evsm_positive_exponent, 0.1f, 100.0f);
        ImGui::SliderFloat("EVSM negative exponent", &filter.evsm_negative_exponent, 0.1f, 100.0f);
        two_choice("EVSM components", filter.evsm_components, 2, 4);
    }
    if (filter.mode == ShadowFilter::Msm) {
        ImGui::SliderFloat("MSM moment bias", &filter.msm_moment_bias, 0.0f, 0.01f, "%.6f");
        ImGui::Checkbox("MSM optimized quantization", &filter.msm_optimized_quantization);
    }
}

void filter_section(FilterSettings& filter, ShadowResolve& resolve) {
    if (!ImGui::CollapsingHeader("Filter", ImGuiTreeNodeFlags_DefaultOpen)) return;
    combo("filter", filter.mode, kShadowFilterChoices);
    combo("resolve", resolve, kShadowResolveChoices);
    comparison_filter_controls(filter);
    moment_filter_controls(filter);
}

}  // namespace

void draw_shadow_settings(RenderSettings& settings, const renderer::FrameInfo* frame) {
    cascade_section(settings.shadow.cascades, frame);
    bias_section(settings.shadow);
    filter_section(settings.shadow.filter, settings.resolve);
    if (ImGui::CollapsingHeader("Debug view", ImGuiTreeNodeFlags_DefaultOpen)) {
        combo("debug view", settings.debug, std::array<const char*, 3>{"none", "cascade colours", "shadow-map layers"});
    }
}

}  // namespace penumbra::view
