// composite: direct + albedo x indirect x occlusion + reflection + refraction + emissive as linear
// HDR radiance, and an exposed, tonemapped, sRGB-encoded 8-bit image.
#version 450 core

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D direct;
layout(binding = 1) uniform sampler2D indirect;
layout(binding = 2) uniform sampler2D albedo;
layout(binding = 3) uniform sampler2D emissive;
layout(binding = 4) uniform sampler2D reflection;
layout(binding = 5) uniform sampler2D refraction;

layout(binding = 0, rgba32f) uniform writeonly image2D hdr;
layout(binding = 1, rgba8) uniform writeonly image2D ldr;

layout(location = 0) uniform int has_indirect;
layout(location = 1) uniform int has_emissive;
layout(location = 2) uniform float exposure_scale;   // 2^EV
layout(location = 3) uniform int tonemap;            // 0 none, 1 reinhard, 2 aces
layout(location = 4) uniform int has_reflection;
layout(location = 5) uniform int has_refraction;

#define TONEMAP_NONE 0
#define TONEMAP_REINHARD 1
#define TONEMAP_ACES 2

vec3
tonemap_color(vec3 c)
{
    if (tonemap == TONEMAP_REINHARD) {
        // Reinhard et al. 2002, eq. 3, on luminance so that hues are kept.
        float l = dot(c, vec3(0.2126, 0.7152, 0.0722));
        return c / (1.0 + l);
    }
    if (tonemap == TONEMAP_ACES) {
        // Narkowicz 2015, "ACES Filmic Tone Mapping Curve" (fit of the ACES RRT+ODT).
        return (c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14);
    }
    return c;
}

float
srgb_encode(float x)
{
    x = clamp(x, 0.0, 1.0);
    return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

void
main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(hdr);
    if (any(greaterThanEqual(pixel, size)))
        return;
    vec3 radiance = texelFetch(direct, pixel, 0).rgb;
    // The indirect input holds the gathered incident radiance integral E_i/pi such that
    // the outgoing Lambertian radiance is albedo x indirect (docs/passes.md); albedo's alpha is the
    // occlusion texture's factor, which darkens indirect light only (1: none).
    if (has_indirect != 0) {
        vec4 a = texelFetch(albedo, pixel, 0);
        radiance += a.rgb * texelFetch(indirect, pixel, 0).rgb * a.a;
    }
    // The specular and refracted cones' radiance, already weighted by the BSDF (cone_gather).
    if (has_reflection != 0)
        radiance += texelFetch(reflection, pixel, 0).rgb;
    if (has_refraction != 0)
        radiance += texelFetch(refraction, pixel, 0).rgb;
    if (has_emissive != 0)
        radiance += texelFetch(emissive, pixel, 0).rgb;
    imageStore(hdr, pixel, vec4(radiance, 1.0));

    // Capped where every operator has long saturated, so that c^2 in the ACES fit cannot
    // overflow to inf / inf = NaN for radiance above 1.8e19 (or a high exposure).
    vec3 mapped = tonemap_color(min(max(radiance, vec3(0.0)) * exposure_scale, vec3(1e18)));
    imageStore(ldr, pixel, vec4(srgb_encode(mapped.r), srgb_encode(mapped.g), srgb_encode(mapped.b), 1.0));
}
