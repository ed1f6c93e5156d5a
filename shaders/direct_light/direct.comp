// direct_light: outgoing radiance of every G-buffer pixel lit by every scene light through glTF
// 2.0's BSDF (common/bsdf.glsl; the units of docs/architecture.md), shadowed by the one shadow map
// when present, or for one light by a cone_gather's shadow cone (input `visibility`).
// passes/direct_light/direct_light.c says which lobes a punctual light reaches.
#version 450 core
#include "common/bsdf.glsl"
#include "common/lights.glsl"
#include "common/shadow.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 2) uniform sampler2D gbuffer_position;
layout(binding = 3) uniform sampler2D gbuffer_normal;
layout(binding = 4) uniform sampler2D gbuffer_albedo;
layout(binding = 5) uniform sampler2D shadow_map;
layout(binding = 6) uniform sampler2D gbuffer_specular;
layout(binding = 7) uniform sampler2D gbuffer_material;
layout(binding = 8) uniform sampler2D gbuffer_transmission;   // the ior: a solid's Fresnel
layout(binding = 9) uniform sampler2D cone_visibility;        // r: the shadow cone's transmittance

// Whether the inputs specular and material (u_glossy) and transmission are connected.
layout(location = 0) uniform bool u_glossy;
layout(location = 1) uniform bool u_transmission;
layout(location = 2) uniform vec3 u_camera;         // world position
layout(location = 3) uniform vec3 u_camera_back;    // the camera's +z (towards the viewer), world
layout(location = 4) uniform bool u_orthographic;
// The light the shadow cone serves (input `visibility`), -1 without it.
layout(location = 5) uniform int u_visibility_light;

// fp32: radiance from starlight to sunlit snow without clipping (direct_light.c).
layout(binding = 0, rgba32f) uniform writeonly image2D radiance;

// The share of light `i` reaching p: the shadow cone's for its light (clamped: an R16F
// transmittance may round a hair outside [0, 1]), else the shadow map's.
float
light_visibility(int i, vec3 p, vec3 n, float cone)
{
    if (i == u_visibility_light)
        return clamp(cone, 0.0, 1.0);
    return cg_shadow_visibility(shadow_map, i, p, n);
}

void
main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(radiance);
    if (any(greaterThanEqual(pixel, size)))
        return;
    vec4 position = texelFetch(gbuffer_position, pixel, 0);
    float cone = u_visibility_light >= 0 ? texelFetch(cone_visibility, pixel, 0).r : 1.0;
    vec3 result = vec3(0.0);
    if (position.w > 0.0) {
        vec3 n = normalize(texelFetch(gbuffer_normal, pixel, 0).xyz);
        vec4 albedo = texelFetch(gbuffer_albedo, pixel, 0);
        CgBsdf b;
        bool lambertian = true;
        if (u_glossy) {
            vec4 transmission = u_transmission ? texelFetch(gbuffer_transmission, pixel, 0) : vec4(0.0, 0.0, 0.0, 1.5);
            b = cg_bsdf_from_gbuffer(albedo, texelFetch(gbuffer_specular, pixel, 0), transmission,
                                     texelFetch(gbuffer_material, pixel, 0), vec4(0.0));
            lambertian = cg_bsdf_is_lambertian(b);
        }
        vec3 v = u_orthographic ? normalize(u_camera_back) : normalize(u_camera - position.xyz);
        // The G-buffer's normal faces the camera; a normal map can still tilt it past the view
        // ray at grazing angles, where n.v <= 0 gives the microfacet terms nothing to stand on.
        float nv = dot(n, v);
        // Punctual lights reach the reflection lobes only (direct_light.c says why).
        const int lobes = CG_BSDF_DIFFUSE | CG_BSDF_GLOSSY;
        for (uint i = 0u; i < cg_light_count(); i++) {
            CgLightSample s = cg_light_sample(cg_lights[i], position.xyz);
            float nl = dot(n, s.to_light);
            if (lambertian || nv <= 0.0) {
                if (nl <= 0.0)
                    continue;
                float visibility = light_visibility(int(i), position.xyz, n, cone);
                result += visibility * cg_lambert_radiance(albedo.rgb, n, s);
                continue;
            }
            if (nl <= 0.0)
                continue;
            float visibility = light_visibility(int(i), position.xyz, n, cone);
            // eta = ior: the camera is outside (only a solid's Fresnel from inside uses it).
            result += visibility * s.irradiance * cg_bsdf_eval(b, n, v, s.to_light, b.ior, lobes);
        }
    }
    imageStore(radiance, pixel, vec4(result, 1.0));
}
