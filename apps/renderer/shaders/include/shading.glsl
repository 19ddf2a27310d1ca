// Surface shading: Lambert diffuse plus GGX specular (Walter et al. 2007) with the
// Smith height-correlated visibility term and Schlick's Fresnel, and a filmic tone map.
#ifndef PENUMBRA_SHADING_GLSL
#define PENUMBRA_SHADING_GLSL

const float kPi = 3.14159265358979;

float ggx_distribution(float n_dot_h, float alpha) {
    const float a2 = alpha * alpha;
    const float d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

float smith_ggx_correlated(float n_dot_v, float n_dot_l, float alpha) {
    const float a2 = alpha * alpha;
    const float v = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    const float l = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    return 0.5 / max(v + l, 1e-5);
}

vec3 fresnel_schlick(vec3 f0, float v_dot_h) { return f0 + (1.0 - f0) * pow(1.0 - v_dot_h, 5.0); }

// Outgoing radiance from a light of `radiance` arriving from direction `to_light`.
vec3 shade_sun(vec3 albedo, vec3 normal, vec3 to_view, vec3 to_light, vec3 radiance, float roughness, float metallic) {
    const float n_dot_l = max(dot(normal, to_light), 0.0);
    if (n_dot_l <= 0.0) return vec3(0.0);
    const float n_dot_v = max(dot(normal, to_view), 1e-4);
    const vec3 half_vector = normalize(to_view + to_light);
    const float n_dot_h = max(dot(normal, half_vector), 0.0);
    const float v_dot_h = max(dot(to_view, half_vector), 0.0);
    const float alpha = max(roughness * roughness, 0.002);

    const vec3 f0 = mix(vec3(0.04), albedo, metallic);
    const vec3 fresnel = fresnel_schlick(f0, v_dot_h);
    const vec3 specular = fresnel * ggx_distribution(n_dot_h, alpha) * smith_ggx_correlated(n_dot_v, n_dot_l, alpha);
    const vec3 diffuse = (1.0 - fresnel) * (1.0 - metallic) * albedo / kPi;
    return (diffuse + specular) * radiance * n_dot_l;
}

// Narkowicz's fit of the ACES filmic curve; the sRGB encoding happens in the attachment.
vec3 tone_map(vec3 color) {
    const vec3 x = color * 0.8;
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

#endif
