// common/gather.glsl: the interface of a cone gather's shader, as the pass SDK binds it
// (cgp_gather_begin, passes/sdk/cone.c): the mipped 3D lightmap, the G-buffer's position and
// normal, the output image `radiance`, and the pixel and surface point of an invocation.
//
// Provides: cg_gather_volume, CG_GATHER_LOBE_VOLUME, cg_gather_radiance, cg_gather_pixel(), cg_gather_surface(); with
//           CG_GATHER_MATERIAL (the G-buffer's material inputs, cgp_gather_declare_material) also
//           CgGatherMaterial, cg_gather_material(), cg_gather_brdf(), cg_gather_specular_tan_half(),
//           cg_gather_diffuse_share(), cg_gather_specular_weight(), cg_gather_transmission_share(),
//           CgGatherLobe, cg_gather_reflection_lobe(), cg_gather_refraction_lobe(), cg_gather_reflection()
//           (which calls cg_gather_trace_lobe(), defined by the including pass after this file).
#ifndef CG_COMMON_GATHER_GLSL
#define CG_COMMON_GATHER_GLSL

#include "common/blocks.h"
#include "common/bsdf.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = CG_UNIT_VOLUME) uniform sampler3D cg_gather_volume;
// The volume a material lobe's cone reads, CG_GATHER_LOBE_VOLUME: with CG_GATHER_GLOSSY voxel_light's
// `glossy`, its light one diffuse bounce further than `volume` (glossy and transmissive scattering on a
// path from the camera do not count against its diffuse bounces, as path_trace and Cycles count them:
// the surface a mirror shows keeps its diffuse bounce; docs/vct.md); else the diffuse cones' volume.
#ifdef CG_GATHER_GLOSSY
layout(binding = CG_UNIT_GLOSSY) uniform sampler3D cg_gather_glossy;
#define CG_GATHER_LOBE_VOLUME cg_gather_glossy
#else
#define CG_GATHER_LOBE_VOLUME cg_gather_volume
#endif
layout(binding = CG_UNIT_POSITION) uniform sampler2D cg_gather_position;
layout(binding = CG_UNIT_NORMAL) uniform sampler2D cg_gather_normal;

// fp32: gathered radiance has the range of the scene's light (no clipping at 65504, no
// denormals under 6e-5), as direct_light's output.
layout(binding = 0, rgba32f) writeonly uniform image2D cg_gather_radiance;

// This invocation's pixel; false past the image's edge, where there is nothing to write. A work
// group is an 8x8 tile, and llvmpipe runs its invocations eight at a time in lockstep (SIMD lanes,
// in the order of gl_LocalInvocationIndex), each loop until its slowest lane is done: so the eight
// are a 4x2 block of the tile rather than one of its rows, whose cones, from nearer points, march
// more alike (cone_gather on Cornell and the open world: 8-10% less CPU time, docs/vct.md, Cost).
// Which invocation takes which pixel changes no pixel's result.
bool
cg_gather_pixel(out ivec2 pixel)
{
    uint i = gl_LocalInvocationIndex;
    uvec2 in_tile = uvec2(((i >> 1u) & 4u) | (i & 3u), ((i >> 3u) & 6u) | ((i >> 2u) & 1u));
    pixel = ivec2(gl_WorkGroupID.xy * uvec2(gl_WorkGroupSize.xy) + in_tile);
    return all(lessThan(pixel, imageSize(cg_gather_radiance)));
}

// The G-buffer's surface at `pixel`, its unit normal n; false on the background (w = 0) and for
// a degenerate normal, which gather nothing (the normal is a unit vector: its 1e-12 has no unit).
bool
cg_gather_surface(ivec2 pixel, out vec3 position, out vec3 n)
{
    vec4 p = texelFetch(cg_gather_position, pixel, 0);
    vec3 normal = texelFetch(cg_gather_normal, pixel, 0).xyz;
    position = p.xyz;
    n = vec3(0.0, 0.0, 1.0);
    if (!(p.w > 0.0 && dot(normal, normal) > 1e-12))
        return false;
    n = normalize(normal);
    return true;
}

// A cone of a material lobe: where it starts, its axis and aperture, the surface it leaves (as in
// cg_cone_step: unit normal, height of the origin above it), and the weight of what it gathers.
struct CgGatherLobe {
    vec3 origin;
    vec3 direction;
    float tan_half;
    vec4 surface;
    vec3 weight;
};

#ifdef CG_GATHER_MATERIAL
// ---- the material terms: the VCT paper's specular and refracted cones (3.2.2), weighted so that a
// white furnace of radiance L returns L x the BSDF's directional albedo (the glTF spec's Appendix B:
// Lambertian diffuse, GGX specular with height-correlated Smith V, Schlick Fresnel; docs/vct.md).
layout(binding = CG_UNIT_ALBEDO) uniform sampler2D cg_gather_albedo;
layout(binding = CG_UNIT_SPECULAR) uniform sampler2D cg_gather_specular;
layout(binding = CG_UNIT_MATERIAL) uniform sampler2D cg_gather_material_map;
layout(binding = CG_UNIT_TRANSMISSION) uniform sampler2D cg_gather_transmission;
layout(binding = CG_UNIT_ATTENUATION) uniform sampler2D cg_gather_attenuation;
// The split-sum table (cgp_brdf_table_fill, passes/sdk/cone.c): r = A, g = B, b = c over
// (n.v, roughness) at texel centres.
layout(binding = CG_UNIT_BRDF_TABLE) uniform sampler2D cg_gather_brdf_table;

// A pixel's material as the G-buffer writes it (docs/passes.md, gbuffer).
struct CgGatherMaterial {
    vec3 rho;           // diffuse weight (1 - m)(1 - T) base colour
    float occlusion;    // the occlusion texture's factor (1: none); indirect light only
    vec3 f0;            // Fresnel at normal incidence
    float f90;          // Fresnel at grazing incidence
    float roughness;    // perceptual; alpha = roughness^2
    float thickness;    // metres; 0: thin-walled
    vec3 tau;           // transmission weight (1 - m) T base colour
    float ior;
    vec3 sigma;         // Beer-Lambert coefficient inside, 1/m
};

CgGatherMaterial
cg_gather_material(ivec2 pixel)
{
    vec4 a = texelFetch(cg_gather_albedo, pixel, 0);
    vec4 s = texelFetch(cg_gather_specular, pixel, 0);
    vec4 m = texelFetch(cg_gather_material_map, pixel, 0);
    vec4 t = texelFetch(cg_gather_transmission, pixel, 0);
    vec3 sigma = texelFetch(cg_gather_attenuation, pixel, 0).rgb;
    return CgGatherMaterial(max(a.rgb, vec3(0.0)), a.a, max(s.rgb, vec3(0.0)), max(s.a, 0.0),
                            clamp(m.x, 0.0, 1.0), max(m.z, 0.0), max(t.rgb, vec3(0.0)), max(t.a, 1.0),
                            max(sigma, vec3(0.0)));
}

// (A, B, c) of the split-sum table at n.v and the perceptual roughness.
vec3
cg_gather_brdf(float nv, float roughness)
{
    // Texel i at i / (size - 1) (cgp_brdf_table_fill): 0 and 1 at the edge texels' centres.
    float size = float(textureSize(cg_gather_brdf_table, 0).x);
    vec2 at = (clamp(vec2(nv, roughness), 0.0, 1.0) * (size - 1.0) + 0.5) / size;
    return textureLod(cg_gather_brdf_table, at, 0.0).rgb;
}

// The specular cone's aperture from the roughness (the VCT paper's "specular diffusion factor",
// 3.2.2): the cone whose solid angle 2 pi (1 - cos theta) is 1 / p, p = D(n) / 4 = 1 / (4 pi alpha^2)
// the density of the GGX reflected lobe at the mirror direction at normal incidence (Walter et al.
// 2007, eq. 14 and 38): 1 - cos theta = 2 alpha^2, theta about 2 alpha for a small alpha. At most 60
// degrees (alpha 0.5), the widest diffuse cone's aperture; at least tan 0.005 (a ray: the march's
// footprint is a voxel wide anyway). Returns tan theta.
float
cg_gather_specular_tan_half(float roughness)
{
    float alpha = roughness * roughness;
    float cos_t = max(1.0 - 2.0 * alpha * alpha, 0.5);
    return max(sqrt(max(1.0 - cos_t * cos_t, 0.0)) / cos_t, 0.005);
}

// What the diffuse lobe keeps of the light: rho/pi (1 - F(v.h)) has the directional albedo
// rho (1 - F0 - (F90 - F0) c(n.v)) (the glTF spec's fresnel_mix integrated over the cosine lobe),
// the factor of the gathered irradiance that composite multiplies by rho.
vec3
cg_gather_diffuse_share(CgGatherMaterial m, vec3 brdf)
{
    return max(vec3(1.0) - m.f0 - (m.f90 - m.f0) * brdf.z, vec3(0.0));
}

// The specular lobe's directional albedo F0 A + F90 B (Karis 2013's split sum): the weight of the
// radiance its cone gathers.
vec3
cg_gather_specular_weight(CgGatherMaterial m, vec3 brdf)
{
    return m.f0 * brdf.x + m.f90 * brdf.y;
}

// What a smooth-to-rough interface lets through: the specular microfacets' directional albedo
// without their Fresnel, less what Fresnel reflects, A (1 - F0) + B (1 - F90) (for a mirror
// 1 - F(n.v)); the transmission lobe's (1 - F) of the spec's fresnel_mix, with the BTDF's own
// shadowing taken as the BRDF's (a departure: the GGX BTDF's albedo is not tabulated).
vec3
cg_gather_transmission_share(CgGatherMaterial m, vec3 brdf)
{
    return max(brdf.x * (vec3(1.0) - m.f0) + brdf.y * (1.0 - m.f90), vec3(0.0));
}

// The specular cone (VCT paper 3.2.2): along the mirror direction of the unit view direction
// `view` (camera to surface) about the normal n (towards the viewer), from `offset` metres off the
// surface, weighted by the lobe's directional albedo.
CgGatherLobe
cg_gather_reflection_lobe(CgGatherMaterial m, vec3 position, vec3 n, vec3 view, float offset)
{
    float nv = max(dot(n, -view), 0.0);
    vec3 brdf = cg_gather_brdf(nv, m.roughness);
    return CgGatherLobe(position + n * offset, reflect(view, n), cg_gather_specular_tan_half(m.roughness),
                        vec4(n, offset), cg_gather_specular_weight(m, brdf));
}

// A material lobe's cone through the including pass's march (defined there, after this file): rgb the
// gathered radiance x lobe.weight, a its coverage; `reach` the pass's march limits, passed through.
vec4 cg_gather_trace_lobe(CgGatherLobe lobe, vec4 reach);

// Where a rough lobe leaves the single cone for the diffuse cone set (perceptual roughness; between
// the two, both, blended). The single cone of a rough lobe is wide (60 degrees from alpha 0.5): on a
// curved surface its first samples cover the surface's own voxels beside the pixel, which the own
// plane left out does not remove (a white metal sphere of roughness 1 in a furnace read 0.61 of the
// path tracer; docs/vct.md, Per material).
#define CG_GATHER_ROUGH_FROM 0.5
#define CG_GATHER_ROUGH_TO 0.75

// The specular lobe's light: the mirror's single cone (cg_gather_reflection_lobe) where the lobe is
// narrow; where it is rough, the pass's diffuse cone set about n (common/cone_trace.glsl), each cone k
// weighted by W_k D(h_k) V(l_k, v) (the set's weights integrate the cosine lobe, so W_k f_k is the
// BRDF's share of that cone, Fresnel aside) over their sum, times the lobe's weight F0 A + F90 B: a
// uniform sky still returns the split sum, and the light comes from the lobe's directions, not its
// axis. `mirror` is the single cone (its origin, surface and weight serve the set's cones too).
vec4
cg_gather_reflection(CgGatherMaterial m, CgGatherLobe mirror, vec3 view, vec4 reach)
{
    float share = smoothstep(CG_GATHER_ROUGH_FROM, CG_GATHER_ROUGH_TO, m.roughness);
    vec4 reflection = vec4(0.0);
    if (share < 1.0)
        reflection = (1.0 - share) * cg_gather_trace_lobe(mirror, reach);
    if (share <= 0.0)
        return reflection;
    vec3 n = mirror.surface.xyz, v = -view;
    mat3 frame = cg_tangent_frame(n);
    float alpha = max(m.roughness * m.roughness, CG_BSDF_ALPHA_MIN), nv = max(dot(n, v), 1e-4);
    float density[CG_CONE_SET_MAX];
    float sum = 0.0;
    for (int k = 0; k < cg_cone_count(); k++) {
        vec3 l = cg_cone_direction(frame, k);
        float nl = max(dot(n, l), 1e-4);
        vec3 h = normalize(l + v);
        density[k] = cg_cone_set_block.cones[k].w * cg_bsdf_ggx_d(alpha, max(dot(n, h), 0.0)) *
                     cg_bsdf_smith_v(alpha, nl, nv);
        sum += density[k];
    }
    for (int k = 0; k < cg_cone_count(); k++) {
        float w = sum > 0.0 ? share * density[k] / sum : 0.0;
        if (w <= 0.0)
            continue;
        CgGatherLobe cone = CgGatherLobe(mirror.origin, cg_cone_direction(frame, k), cg_cone_tan_half(k), mirror.surface,
                                         w * mirror.weight);
        vec4 traced = cg_gather_trace_lobe(cone, reach);
        reflection += vec4(traced.rgb, w * traced.a);
    }
    return reflection;
}

// The refracted cone (VCT paper 3.2.2: "a refracted cone (using Snell's law)"), with both faces of a
// solid:
//   thin-walled (thickness 0): the cone goes on along the view direction from the far side
//     (KHR_materials_transmission's thin sheet), weighted tau x the interface's transmission share;
//   solid: refracted in by Snell's law with the ior (refract(view, n, 1 / ior)), carried
//     `thickness` metres along that direction through the solid (KHR_materials_volume's thickness),
//     refracted out through a face parallel to the entry face (the normal flipped: a slab), weighted
//     tau x the share at the entry x the share at the exit (Fresnel at the outside cosine there, the
//     same table) x exp(-sigma thickness) (Beer-Lambert). Total internal reflection at the exit
//     (never, for parallel faces) lets nothing through.
// Both start `offset` metres past the far face, which the voxels hold as opaque and black (the cone
// must not read it). The aperture is the specular cone's for the roughness (a departure: the GGX
// BTDF's lobe is wider by the ior's ratio on the far side).
CgGatherLobe
cg_gather_refraction_lobe(CgGatherMaterial m, vec3 position, vec3 n, vec3 view, float offset)
{
    float nv = max(dot(n, -view), 0.0);
    vec3 weight = m.tau * cg_gather_transmission_share(m, cg_gather_brdf(nv, m.roughness));
    vec3 exit = position;
    vec3 direction = view;
    if (m.thickness > 0.0) {
        vec3 inside = refract(view, n, 1.0 / m.ior);
        direction = refract(inside, n, m.ior);
        if (dot(direction, direction) <= 0.0 || dot(inside, inside) <= 0.0) {
            weight = vec3(0.0);
            direction = view;
        } else {
            exit = position + inside * m.thickness;
            weight *= cg_gather_transmission_share(m, cg_gather_brdf(max(dot(direction, -n), 0.0), m.roughness)) *
                      exp(-m.sigma * m.thickness);
        }
    }
    return CgGatherLobe(exit - n * offset, direction, cg_gather_specular_tan_half(m.roughness), vec4(-n, offset),
                        weight);
}
#endif

#endif
