// direct_light: outgoing radiance of every G-buffer pixel lit by every scene light,
// Lambertian (DESIGN.md units), shadowed by the one shadow map when present.
#version 450 core
#include "common/lights.glsl"
#include "common/shadow.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 2) uniform sampler2D gbuffer_position;
layout(binding = 3) uniform sampler2D gbuffer_normal;
layout(binding = 4) uniform sampler2D gbuffer_albedo;
layout(binding = 5) uniform sampler2D shadow_map;

// fp32: radiance from starlight to sunlit snow without clipping (direct_light.c).
layout(binding = 0, rgba32f) uniform writeonly image2D radiance;

void
main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(radiance);
    if (any(greaterThanEqual(pixel, size)))
        return;
    vec4 position = texelFetch(gbuffer_position, pixel, 0);
    vec3 result = vec3(0.0);
    if (position.w > 0.0) {
        vec3 n = normalize(texelFetch(gbuffer_normal, pixel, 0).xyz);
        vec3 albedo = texelFetch(gbuffer_albedo, pixel, 0).rgb;
        for (uint i = 0u; i < cg_light_count(); i++) {
            CgLightSample s = cg_light_sample(cg_lights[i], position.xyz);
            if (dot(n, s.to_light) <= 0.0)
                continue;
            float visibility = cg_shadow_visibility(shadow_map, int(i), position.xyz, n);
            result += visibility * cg_lambert_radiance(albedo, n, s);
        }
    }
    imageStore(radiance, pixel, vec4(result, 1.0));
}
