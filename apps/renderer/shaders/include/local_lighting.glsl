// Spot and point lights' lighting in the tools' renderer (docs/local-lights.md): the
// physically based falloff and the smooth spot cone. Their shadows come from Penumbra
// (penumbra_light_shadow() in penumbra/shadow.glsl).
#ifndef RENDERER_LOCAL_LIGHTING_GLSL
#define RENDERER_LOCAL_LIGHTING_GLSL

// Inverse-square falloff with a smooth window at the range (Karis 2013, "Real Shading in
// Unreal Engine 4"): saturate(1 - (d / range)^4)^2 / d^2.
float distance_falloff(float distance, float range) {
    const float ratio = distance / range;
    const float window = clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0);
    return window * window / max(distance * distance, 1e-4);
}

// Smooth cone: 0 outside the outer angle, 1 inside the inner one, smoothstep between.
float spot_cone(LocalLight light, vec3 to_light) {
    if (light.type != RENDERER_LIGHT_SPOT) return 1.0;
    const float cos_angle = dot(-to_light, light.direction);
    return smoothstep(light.cos_outer, max(light.cos_inner, light.cos_outer + 1e-4), cos_angle);
}

#endif
