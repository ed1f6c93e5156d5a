// common/shadow.glsl: shadow-map lookup for one light, as written by the shadow_map pass.
//
// The shadow_map pass writes a depth texture (GL_DEPTH_COMPONENT32F, window depth of
// the light's projection) and the std140 block `matrix` (CG_SHADOW_BLOCK of common/blocks.h,
// 192 bytes), bound here at CG_BINDING_SHADOW. A program that has no shadow map binds the
// pass SDK's fallback (cgp_bind_shadow), whose light index is -1.
// Bias (docs/passes.md): the receiver is moved towards the light by
//   texel * (constant + slope * min(tan(theta), 10))
// where texel is the world size of one shadow-map texel at the receiver and theta the
// angle between the normal and the light: scale-free, so the same defaults work for a
// 1 m box and a 2 km terrain. The other constants below guard unit vectors and angles
// (cosines, a normal's z, a ray direction whose z is -1), never lengths.
#ifndef CG_SHADOW_GLSL
#define CG_SHADOW_GLSL

#include "common/blocks.h"

CG_UNIFORM_BLOCK(CgShadow, cg_shadow_block, CG_BINDING_SHADOW, CG_SHADOW_BLOCK);

// Distance along the light's view axis stored in a texel of window depth d.
float
cg_shadow_linear_depth(float d)
{
    float n = cg_shadow_block.frustum.z, f = cg_shadow_block.frustum.w;
    if (cg_shadow_block.frustum.y > 0.5)
        return n + d * (f - n);
    float z_ndc = 2.0 * d - 1.0;
    return 2.0 * n * f / ((f + n) - z_ndc * (f - n));
}

// Fraction of the light `light_index` reaching world point p with unit normal n:
// 1 lit, 0 shadowed; 1 outside the shadow map's frustum (no information there) and for
// lights the map does not serve.
float
cg_shadow_visibility(sampler2D shadow_map, int light_index, vec3 p, vec3 n)
{
    if (light_index != int(cg_shadow_block.frustum.x))
        return 1.0;
    vec4 clip = cg_shadow_block.view_proj * vec4(p, 1.0);
    if (clip.w <= 0.0)
        return 1.0;
    vec3 ndc = clip.xyz / clip.w;
    if (any(greaterThan(abs(ndc.xy), vec2(1.0))))
        return 1.0;
    float dist = -(cg_shadow_block.view * vec4(p, 1.0)).z;
    bool ortho = cg_shadow_block.frustum.y > 0.5;
    vec3 to_light = ortho ? cg_shadow_block.light.xyz : normalize(cg_shadow_block.light.xyz - p);
    float cos_theta = clamp(abs(dot(n, to_light)), 1e-3, 1.0);
    float tan_theta = min(sqrt(1.0 - cos_theta * cos_theta) / cos_theta, 10.0);
    vec2 texel2 = ortho ? cg_shadow_block.texel.xy : cg_shadow_block.texel.xy * dist;
    float texel = max(texel2.x, texel2.y);
    float receiver = dist - texel * (cg_shadow_block.params.x + cg_shadow_block.params.y * tan_theta);

    // Receiver-plane depth (Isidoro 2006, "Shadow mapping: GPU-based tips and techniques"):
    // each tap compares against the receiver's plane continued to that texel's centre, so
    // that filters over sloped receivers do not self-shadow. The change of depth is capped
    // at 10 times the lateral offset, like the slope bias.
    vec3 pv = (cg_shadow_block.view * vec4(p, 1.0)).xyz;
    vec3 nv = mat3(cg_shadow_block.view) * n;
    float plane = dot(nv, pv);
    float nz = nv.z >= 0.0 ? max(nv.z, 1e-4) : min(nv.z, -1e-4);
    int resolution = int(cg_shadow_block.params.w);
    int radius = int(cg_shadow_block.params.z);
    vec2 st = (ndc.xy * 0.5 + 0.5) * float(resolution);
    ivec2 center = ivec2(floor(st));
    float lit = 0.0;
    for (int y = -radius; y <= radius; y++)
        for (int x = -radius; x <= radius; x++) {
            ivec2 t = clamp(center + ivec2(x, y), ivec2(0), ivec2(resolution - 1));
            vec2 offset_texels = vec2(center + ivec2(x, y)) + 0.5 - st;
            vec2 offset = offset_texels * texel2;   // metres across the light at the receiver
            float delta;
            if (ortho) {
                // Parallel rays: depth changes by n.xy/n.z per metre across the light.
                delta = dot(nv.xy, offset) / nz;
            } else {
                // The ray through the tap's texel centre, q = s (u, v, -1) at depth s, meets
                // the plane n.q = n.p at s = n.p / n.(u, v, -1). A ray nearly parallel to
                // the plane gives a huge delta, which the cap below bounds.
                vec3 ray = vec3(pv.xy / dist + offset_texels * cg_shadow_block.texel.xy, -1.0);
                float along = dot(nv, ray);
                delta = abs(along) > 1e-6 ? plane / along - dist : 0.0;
            }
            float cap = 10.0 * length(offset);
            delta = clamp(delta, -cap, cap);
            float occluder = cg_shadow_linear_depth(texelFetch(shadow_map, t, 0).r);
            lit += receiver + delta <= occluder ? 1.0 : 0.0;
        }
    float taps = float((2 * radius + 1) * (2 * radius + 1));
    return lit / taps;
}

#endif
