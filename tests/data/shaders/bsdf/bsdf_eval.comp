#version 450 core
// tests/passes/test_bsdf_glsl.c: common/bsdf.glsl's functions and scene.glsl's
// cg_bsdf_from_material on the test's inputs, one case an invocation, written for the C side
// (cg/bsdf.h) to check.
#include "common/scene.glsl"

layout(local_size_x = 64) in;

struct BsdfCase {
    vec4 n;         // xyz unit shading normal
    vec4 v;         // xyz unit, towards the viewer
    vec4 l;         // xyz unit, towards the light
    vec4 params;    // x = material index, y = eta, z = w = 0
    vec4 dots;      // n.h, n.l, n.v, v.h with h = normalize(v + l), as the C side rounded them, so
                    // that the scalar functions see the very same arguments
};

layout(std430, binding = 1) readonly buffer Cases { BsdfCase cases[]; };
// Per case, CG_BSDF_TEST_VEC4 vec4s (test_bsdf_glsl.c reads them in this order).
layout(std430, binding = 2) writeonly buffer Results { vec4 results[]; };
layout(location = 8) uniform uint u_count;   // 0..2 are scene.glsl's

#define CG_BSDF_TEST_VEC4 12

void
main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count)
        return;
    BsdfCase c = cases[i];
    int material = int(c.params.x);
    float eta = c.params.y;
    CgMaterial m = cg_materials[material];
    CgBsdf b = cg_bsdf_from_material(material, m.base_color, m.pbr.x, m.pbr.y, m.volume.y);
    vec3 n = c.n.xyz, v = c.v.xyz, l = c.l.xyz;
    uint o = i * uint(CG_BSDF_TEST_VEC4);
    vec4 d = c.dots;
    results[o + 0u] = vec4(cg_bsdf_ggx_d(b.alpha, d.x), cg_bsdf_smith_v(b.alpha, d.y, d.z), cg_bsdf_smith_g1(b.alpha, d.z),
                           cg_bsdf_is_smooth(b) ? 1.0 : 0.0);
    results[o + 1u] = vec4(cg_bsdf_fresnel(b.f0, b.f90, d.w), 0.0);
    results[o + 2u] = vec4(cg_bsdf_fresnel_dielectric(b, d.w, eta), 0.0);
    results[o + 3u] = vec4(cg_bsdf_eval(b, n, v, l, eta, CG_BSDF_ALL_LOBES), 0.0);
    results[o + 4u] = vec4(cg_bsdf_eval(b, n, v, l, eta, CG_BSDF_DIFFUSE), 0.0);
    results[o + 5u] = vec4(cg_bsdf_eval(b, n, v, l, eta, CG_BSDF_GLOSSY), 0.0);
    results[o + 6u] = vec4(cg_bsdf_eval(b, n, v, l, eta, CG_BSDF_TRANSMISSION), 0.0);
    results[o + 7u] = vec4(b.diffuse, b.f90);
    results[o + 8u] = vec4(b.f0, b.alpha);
    results[o + 9u] = vec4(b.transmission, b.ior);
    results[o + 10u] = vec4(b.sigma, b.thickness);
    results[o + 11u] = vec4(cg_bsdf_diffuse_hemispherical(b), 0.0);
}
