// format_settings_file() is the inverse of the config-file reader: every value written
// reads back bit-exact, so `penumbra render --config` reproduces what `view` saved.
#include <gtest/gtest.h>

#include <cstddef>

#include "penumbra/errors.hpp"
#include "penumbra/scene/settings_files.hpp"

namespace penumbra {
namespace {

RenderSettings unusual_settings() {
    RenderSettings s;
    s.width = 333;
    s.height = 217;
    s.shadow.cascades.count = 3;
    s.shadow.cascades.resolution = 1024;
    s.shadow.cascades.scheme = SplitScheme::Manual;
    s.shadow.cascades.manual_splits = {3.1f, 17.77777f};
    s.shadow.cascades.split_lambda = 0.123456789f;
    s.shadow.cascades.max_distance = 87.654321f;
    s.shadow.cascades.fit = FitMode::Tight;
    s.shadow.bias = {1.5f, 3.3333333f, 0.0123f, 0.7f};
    s.shadow.blend_width = 1.0f / 3.0f;
    s.shadow.strategy = ShadowStrategy::Multiview;
    s.shadow.cull_casters = false;
    s.shadow.caster_culling = CasterCulling::FrontFaces;
    FilterSettings& f = s.shadow.filter;
    f.mode = ShadowFilter::Evsm;
    f.receiver_plane_bias = false;
    f.pcf_radius = 3;
    f.poisson_taps = 32;
    f.poisson_radius = 4.2f;
    f.pcss_blocker_taps = 32;
    f.pcss_quality = PcssQuality::High;
    f.pcss_early_out = true;
    f.pcss_max_penumbra = 17.5f;
    f.light_bleeding_reduction = 0.31f;
    f.blur_radius = 5;
    f.moments_poisson = true;
    f.evsm_positive_exponent = 33.3f;
    f.evsm_negative_exponent = 7.7f;
    f.evsm_components = 2;
    f.msm_moment_bias = 1.234e-5f;
    f.msm_optimized_quantization = true;
    return s;
}

TEST(SettingsWriter, EveryValueRoundTripsExactly) {
    const RenderSettings written = unusual_settings();
    Camera camera;
    camera.eye = {0.1f, 2.0f / 3.0f, -7.123456f};
    camera.target = {1e-3f, 0.0f, 5.5f};
    camera.up = {0.0f, 1.0f, 0.0f};
    camera.fov_y_degrees = 47.3f;
    camera.near_plane = 0.07f;
    camera.far_plane = 321.0f;
    Light sun;
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, 0.2f));
    sun.angular_diameter_degrees = 2.25f;

    const SettingsOverrides read = parse_settings_text(format_settings_file(written, camera, &sun), "saved.toml");
    RenderSettings settings;
    apply_overrides(read, settings);
    Scene scene;
    apply_overrides(read, scene);

    // Exact equality of every value, floats included.
    EXPECT_EQ(settings.width, written.width);
    EXPECT_EQ(settings.height, written.height);
    const CascadeSettings& c = settings.shadow.cascades;
    EXPECT_EQ(c.count, 3);
    EXPECT_EQ(c.resolution, 1024u);
    EXPECT_EQ(c.scheme, SplitScheme::Manual);
    EXPECT_EQ(c.manual_splits, written.shadow.cascades.manual_splits);
    EXPECT_EQ(c.split_lambda, written.shadow.cascades.split_lambda);
    EXPECT_EQ(c.max_distance, written.shadow.cascades.max_distance);
    EXPECT_EQ(c.fit, FitMode::Tight);
    EXPECT_EQ(settings.shadow.bias.constant, written.shadow.bias.constant);
    EXPECT_EQ(settings.shadow.bias.slope, written.shadow.bias.slope);
    EXPECT_EQ(settings.shadow.bias.clamp, written.shadow.bias.clamp);
    EXPECT_EQ(settings.shadow.bias.normal_offset, written.shadow.bias.normal_offset);
    EXPECT_EQ(settings.shadow.blend_width, written.shadow.blend_width);
    EXPECT_EQ(settings.shadow.strategy, ShadowStrategy::Multiview);
    EXPECT_FALSE(settings.shadow.cull_casters);
    EXPECT_EQ(settings.shadow.caster_culling, CasterCulling::FrontFaces);
    const FilterSettings& a = settings.shadow.filter;
    const FilterSettings& b = written.shadow.filter;
    EXPECT_EQ(a.mode, b.mode);
    EXPECT_EQ(a.receiver_plane_bias, b.receiver_plane_bias);
    EXPECT_EQ(a.pcf_radius, b.pcf_radius);
    EXPECT_EQ(a.poisson_taps, b.poisson_taps);
    EXPECT_EQ(a.poisson_radius, b.poisson_radius);
    EXPECT_EQ(a.pcss_blocker_taps, b.pcss_blocker_taps);
    EXPECT_EQ(a.pcss_quality, b.pcss_quality);
    EXPECT_EQ(a.pcss_early_out, b.pcss_early_out);
    EXPECT_EQ(a.pcss_max_penumbra, b.pcss_max_penumbra);
    EXPECT_EQ(a.light_bleeding_reduction, b.light_bleeding_reduction);
    EXPECT_EQ(a.blur_radius, b.blur_radius);
    EXPECT_EQ(a.moments_poisson, b.moments_poisson);
    EXPECT_EQ(a.evsm_positive_exponent, b.evsm_positive_exponent);
    EXPECT_EQ(a.evsm_negative_exponent, b.evsm_negative_exponent);
    EXPECT_EQ(a.evsm_components, b.evsm_components);
    EXPECT_EQ(a.msm_moment_bias, b.msm_moment_bias);
    EXPECT_EQ(a.msm_optimized_quantization, b.msm_optimized_quantization);

    EXPECT_EQ(scene.camera.eye, camera.eye);
    EXPECT_EQ(scene.camera.target, camera.target);
    EXPECT_EQ(scene.camera.fov_y_degrees, camera.fov_y_degrees);
    EXPECT_EQ(scene.camera.near_plane, camera.near_plane);
    EXPECT_EQ(scene.camera.far_plane, camera.far_plane);
    ASSERT_NE(scene.sun(), nullptr);
    EXPECT_EQ(scene.sun()->direction, sun.direction);
    EXPECT_EQ(scene.sun()->angular_diameter_degrees, 2.25f);
}

TEST(SettingsWriter, DefaultsAreValidAndNoSunMeansNoSunTable) {
    const std::string text = format_settings_file(RenderSettings{}, Camera{}, nullptr);
    EXPECT_EQ(text.find("[sun]"), std::string::npos);
    EXPECT_EQ(text.find("splits ="), std::string::npos);  // no manual splits to write
    RenderSettings settings;
    apply_overrides(parse_settings_text(text, "saved.toml"), settings);
    EXPECT_NO_THROW(validate_render_settings(settings, "saved.toml"));
}

// caster_culling takes the names of caster_culling_names(); any other value is one line
// naming the file, the key and the valid names.
TEST(SettingsText, CasterCullingNames) {
    for (const auto& [name, culling] : caster_culling_names()) {
        RenderSettings settings;
        apply_overrides(parse_settings_text("[shadow]\ncaster_culling = \"" + name + "\"\n", "c.toml"), settings);
        EXPECT_EQ(settings.shadow.caster_culling, culling) << name;
    }
    try {
        parse_settings_text("[shadow]\ncaster_culling = \"sideways\"\n", "bad.toml");
        FAIL() << "an unknown caster culling must be rejected";
    } catch (const InputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("bad.toml: shadow.caster_culling"), std::string::npos) << message;
        EXPECT_NE(message.find("front"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(SettingsText, ErrorsNameTheOrigin) {
    EXPECT_THROW(parse_settings_text("[shadow]\ncascades = \n", "script.txt:3"), InputError);
    try {
        parse_settings_text("[nope]\nx = 1\n", "script.txt:3");
        FAIL();
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("script.txt:3: nope: unknown table"), std::string::npos)
            << error.what();
    }
}

// Every name of every choice table (penumbra/settings.hpp) is written and read back as its
// value: the reader, the writer and the tables cannot drift apart.
template <typename Enum, std::size_t N, typename Field>
void expect_every_choice_round_trips(const ChoiceName<Enum> (&choices)[N], Field field) {
    for (const ChoiceName<Enum>& choice : choices) {
        SCOPED_TRACE(choice.name);
        RenderSettings written;
        written.shadow.cascades.scheme = SplitScheme::Manual;  // manual splits need splits
        written.shadow.cascades.manual_splits = {10.0f, 30.0f, 60.0f};
        field(written) = choice.value;
        const SettingsOverrides read =
            parse_settings_text(format_settings_file(written, Camera{}, nullptr), "saved.toml");
        RenderSettings settings;
        apply_overrides(read, settings);
        EXPECT_EQ(field(settings), choice.value);
    }
}

TEST(SettingsWriter, EveryChoiceOfEveryTableRoundTrips) {
    expect_every_choice_round_trips(kSplitSchemeChoices,
                                    [](RenderSettings& s) -> SplitScheme& { return s.shadow.cascades.scheme; });
    expect_every_choice_round_trips(kFitModeChoices,
                                    [](RenderSettings& s) -> FitMode& { return s.shadow.cascades.fit; });
    expect_every_choice_round_trips(kShadowStrategyChoices,
                                    [](RenderSettings& s) -> ShadowStrategy& { return s.shadow.strategy; });
    expect_every_choice_round_trips(kShadowFilterChoices,
                                    [](RenderSettings& s) -> ShadowFilter& { return s.shadow.filter.mode; });
    expect_every_choice_round_trips(kPcssQualityChoices,
                                    [](RenderSettings& s) -> PcssQuality& { return s.shadow.filter.pcss_quality; });
    expect_every_choice_round_trips(kCasterCullingChoices,
                                    [](RenderSettings& s) -> CasterCulling& { return s.shadow.caster_culling; });
    expect_every_choice_round_trips(kLocalShadowSizingChoices,
                                    [](RenderSettings& s) -> LocalShadowSizing& { return s.local_shadows.sizing; });
}

}  // namespace
}  // namespace penumbra
