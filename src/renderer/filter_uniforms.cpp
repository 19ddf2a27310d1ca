#include "renderer/filter_uniforms.hpp"

#include "core/shadow_filters.hpp"

namespace penumbra::renderer {

void fill_filter_uniforms(shader::FrameUniforms& frame, const Scene& scene, const CascadeSet& cascades,
                          const ShadowSettings& settings, uint32_t frame_index) {
    const Light* sun = scene.sun();
    const float angular_diameter = sun ? sun->angular_diameter_degrees : 0.0f;
    for (size_t c = 0; c < cascades.cascades.size(); ++c) {
        const CascadeFilterParams params = cascade_filter_params(cascades.cascades[c], angular_diameter);
        frame.cascade_filter[c] = glm::vec4(params.light_radius_uv_per_depth, params.max_depth_gradient);
    }
    const FilterSettings& filter = settings.filter;
    frame.filter_params = glm::vec4(static_cast<float>(filter.pcf_radius), filter.poisson_radius,
                                    filter.pcss_max_penumbra, 1.0f / static_cast<float>(settings.cascades.resolution));
    const glm::vec2 exponents = clamped_evsm_exponents(filter);
    frame.moment_params = glm::vec4(filter.light_bleeding_reduction, exponents.x, exponents.y, filter.msm_moment_bias);
    frame.filter_options = glm::uvec4(frame_index, 0u, 0u, 0u);
}

}  // namespace penumbra::renderer
