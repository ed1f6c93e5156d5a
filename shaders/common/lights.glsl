// common/lights.glsl: the scene's punctual lights (SSBO binding 1, filled by cg_gpu_scene)
// and their irradiance, in the units of KHR_lights_punctual as DESIGN.md fixes them:
//   directional: E = intensity x color on a surface facing the light;
//   point:       E = I / d^2 with I = intensity x color, times the range window
//                clamp(1 - (d/range)^4, 0, 1)^2 when range > 0;
//   spot:        as point, times the KHR_lights_punctual smooth cone falloff.
// A Lambertian surface of albedo a returns outgoing radiance a * E * cos(theta) / pi.
#ifndef CG_LIGHTS_GLSL
#define CG_LIGHTS_GLSL

#define CG_PI 3.14159265358979323846

#define CG_LIGHT_DIRECTIONAL 0
#define CG_LIGHT_POINT 1
#define CG_LIGHT_SPOT 2

// Mirrors gpu_light in core/gl/gpu_scene.c (std430, 64 bytes).
struct CgLight {
    vec4 position_type;     // xyz world position, w = type
    vec4 direction_range;   // xyz unit direction the light travels, w = range (0 = infinite)
    vec4 radiance;          // rgb = color x intensity
    vec4 cone;              // x = angle scale, y = angle offset
};

layout(std430, binding = 1) readonly buffer CgLights {
    uvec4 cg_light_header;  // x = light count
    CgLight cg_lights[];
};

uint
cg_light_count()
{
    return cg_light_header.x;
}

// What a light delivers at a point: the unit direction towards the light, the distance
// to it (infinite for directional) and the irradiance on a surface facing the light.
struct CgLightSample {
    vec3 to_light;
    float distance;
    vec3 irradiance;
};

CgLightSample
cg_light_sample(CgLight light, vec3 position)
{
    CgLightSample s;
    int type = int(light.position_type.w);
    if (type == CG_LIGHT_DIRECTIONAL) {
        s.to_light = -light.direction_range.xyz;
        s.distance = 1.0 / 0.0;
        s.irradiance = light.radiance.rgb;
        return s;
    }
    vec3 d = light.position_type.xyz - position;
    float dist2 = dot(d, d);
    // A point at the light itself (or so near that d^2 underflows) receives nothing, as in the
    // path tracer: I / d^2 has no finite value there. No floor in square metres: 1e-12 m^2 dimmed
    // every surface of a micrometre scene (docs/architecture.md, scale-free numerics).
    if (!(dist2 > 0.0)) {
        s.to_light = vec3(0.0);
        s.distance = 0.0;
        s.irradiance = vec3(0.0);
        return s;
    }
    s.distance = sqrt(dist2);
    s.to_light = d / s.distance;
    float attenuation = 1.0 / dist2;
    float range = light.direction_range.w;
    if (range > 0.0) {
        // KHR_lights_punctual's recommended window, squared as in the glTF sample viewer
        // and the path_trace pass: clamp(1 - (d/range)^4, 0, 1)^2.
        float ratio = s.distance / range;
        float window = clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0);
        attenuation *= window * window;
    }
    if (type == CG_LIGHT_SPOT) {
        // KHR_lights_punctual, "Inner and Outer Cone Angles".
        float cd = dot(light.direction_range.xyz, -s.to_light);
        float falloff = clamp(cd * light.cone.x + light.cone.y, 0.0, 1.0);
        attenuation *= falloff * falloff;
    }
    s.irradiance = light.radiance.rgb * attenuation;
    return s;
}

// Outgoing radiance of a Lambertian surface (unit normal n, albedo a) lit by one sample.
vec3
cg_lambert_radiance(vec3 albedo, vec3 n, CgLightSample s)
{
    return albedo * s.irradiance * max(dot(n, s.to_light), 0.0) / CG_PI;
}

#endif
