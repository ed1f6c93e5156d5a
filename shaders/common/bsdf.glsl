// common/bsdf.glsl: glTF 2.0's metallic-roughness BSDF in GLSL, the mirror of core/include/cg/bsdf.h
// (the path tracer's C), function by function under the same cg_bsdf_* names and with the same
// formulas, conventions and sources (read the model there): glTF 2.0 Appendix B (Lambertian
// diffuse x (1 - F), GGX D, height-correlated Smith V, Schlick F on v.h), KHR_materials_ior,
// _specular, _transmission (thin-walled: the GGX lobe mirrored through the surface) and _volume
// (a solid: the rough dielectric BTDF of Walter et al. 2007, eq. 21).
// tests/passes/test_bsdf_glsl.c evaluates both sides on the same inputs.
//
// Conventions: unit world vectors; n the shading normal turned to v's side (n.v > 0), v towards
// the viewer, l towards the light; l on n's side is reflection, the other side transmission; eta
// the index on l's side over v's (ior from outside a solid). cg_bsdf_eval returns f |n.l|.
//
// Provides: CgBsdf, CG_BSDF_DIFFUSE, CG_BSDF_GLOSSY, CG_BSDF_TRANSMISSION, CG_BSDF_ALL_LOBES,
//           CG_BSDF_ALPHA_MIN, cg_bsdf_is_smooth, cg_bsdf_ggx_d, cg_bsdf_smith_v, cg_bsdf_smith_g1,
//           cg_bsdf_fresnel, cg_bsdf_fresnel_dielectric, cg_bsdf_eval, cg_bsdf_is_lambertian,
//           cg_bsdf_from_gbuffer, cg_bsdf_diffuse_hemispherical, CG_BSDF_DIFFUSE_HEMISPHERICAL_A, _B. (cg_bsdf_from_material is in common/scene.glsl, which has the
//           material buffer.)
#ifndef CG_BSDF_GLSL
#define CG_BSDF_GLSL

#define CG_BSDF_PI 3.14159265358979323846

// Lobe flags (cg_bsdf_lobe).
#define CG_BSDF_DIFFUSE 1
#define CG_BSDF_GLOSSY 2
#define CG_BSDF_TRANSMISSION 4
#define CG_BSDF_ALL_LOBES 7

// alpha below this is a smooth (delta) surface: eval gives its glossy and transmission lobes 0.
#define CG_BSDF_ALPHA_MIN 1e-3

// The diffuse lobe's (1 - F) averaged over both hemispheres, cosine-weighted (uniform light in, the
// outgoing radiance's mean over the viewing directions): 1 - F0 A - F90 B, with A and B the means of
// cg_bsdf_diffuse_albedo_terms' a and b over n.v, cosine-weighted. test_bsdf_glsl integrates them from
// the C function. For ior 1.5 (F0 0.04, F90 1) 0.956; per viewing angle the C terms give 0.937 (n.v
// 0.05) to 0.960 (n.v 1).
#define CG_BSDF_DIFFUSE_HEMISPHERICAL_A 0.996325
#define CG_BSDF_DIFFUSE_HEMISPHERICAL_B 0.003675

// A material at one surface point (struct cg_bsdf): the G-buffer's quantities.
struct CgBsdf {
    vec3 diffuse;       // rho = (1-m)(1-T) baseColor
    vec3 f0;            // F0, metal and dielectric mixed by metallic
    float f90;          // F90
    float roughness;    // glTF perceptual roughness in [0, 1]
    float alpha;        // roughness^2
    vec3 transmission;  // tau = (1-m) T baseColor
    float ior;
    float thickness;    // 0: thin-walled
    vec3 sigma;         // Beer-Lambert coefficient, 1/m
};

bool
cg_bsdf_is_smooth(CgBsdf b)
{
    return b.alpha < CG_BSDF_ALPHA_MIN;
}

// No glossy and no transmission lobe (F0 = F90 = 0, tau = 0): the built-in scenes' Lambertian,
// whose shading keeps the old Lambertian arithmetic (bit for bit the kept images).
bool
cg_bsdf_is_lambertian(CgBsdf b)
{
    return b.f90 == 0.0 && all(equal(b.f0, vec3(0.0))) && all(equal(b.transmission, vec3(0.0)));
}

// GGX D(h), glTF Appendix B.3.2.
float
cg_bsdf_ggx_d(float alpha, float n_dot_h)
{
    float a2 = alpha * alpha;
    float t = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    return a2 / (CG_BSDF_PI * t * t);
}

// Height-correlated Smith V = G2 / (4 |n.l| |n.v|), glTF Appendix B.3.2.
float
cg_bsdf_smith_v(float alpha, float n_dot_l, float n_dot_v)
{
    float a2 = alpha * alpha;
    float nl = abs(n_dot_l), nv = abs(n_dot_v);
    float gv = nl * sqrt(nv * nv * (1.0 - a2) + a2);
    float gl = nv * sqrt(nl * nl * (1.0 - a2) + a2);
    float s = gv + gl;
    return s > 0.0 ? 0.5 / s : 0.0;
}

// Smith's G1 of GGX (Heitz 2014, eq. 72).
float
cg_bsdf_smith_g1(float alpha, float n_dot_v)
{
    float a2 = alpha * alpha;
    float nv = abs(n_dot_v);
    float s = nv + sqrt(a2 + (1.0 - a2) * nv * nv);
    return s > 0.0 ? 2.0 * nv / s : 0.0;
}

// Schlick, glTF Appendix B.3.4: F0 + (F90 - F0) (1 - |v.h|)^5.
vec3
cg_bsdf_fresnel(vec3 f0, float f90, float v_dot_h)
{
    float x = 1.0 - clamp(abs(v_dot_h), 0.0, 1.0);
    float x2 = x * x;
    float w = x2 * x2 * x;
    return f0 + (vec3(f90) - f0) * w;
}

// Schlick on |v.h| entering, on the transmitted cosine leaving a solid (eta < 1); 1 past the
// critical angle; thin-walled: on |v.h|.
vec3
cg_bsdf_fresnel_dielectric(CgBsdf b, float v_dot_h, float eta)
{
    float c = abs(v_dot_h);
    if (b.thickness > 0.0 && eta < 1.0) {
        float sin2_t = (1.0 - c * c) / (eta * eta);
        if (sin2_t >= 1.0)
            return vec3(1.0);
        c = sqrt(1.0 - sin2_t);
    }
    return cg_bsdf_fresnel(b.f0, b.f90, c);
}

// f(v, l) |n.l| of the lobes in `lobes`; delta lobes give 0.
vec3
cg_bsdf_eval(CgBsdf b, vec3 n, vec3 v, vec3 l, float eta, int lobes)
{
    float nv = dot(n, v), nl = dot(n, l);
    if (nv <= 0.0 || nl == 0.0)
        return vec3(0.0);
    bool smooth_surface = cg_bsdf_is_smooth(b);
    if (nl > 0.0) {
        if ((lobes & (CG_BSDF_DIFFUSE | CG_BSDF_GLOSSY)) == 0)
            return vec3(0.0);
        vec3 h = normalize(v + l);
        vec3 f = cg_bsdf_fresnel_dielectric(b, dot(v, h), eta);
        float spec = 0.0;
        if ((lobes & CG_BSDF_GLOSSY) != 0 && !smooth_surface)
            spec = cg_bsdf_ggx_d(b.alpha, dot(n, h)) * cg_bsdf_smith_v(b.alpha, nl, nv) * nl;
        float diff = (lobes & CG_BSDF_DIFFUSE) != 0 ? nl / CG_BSDF_PI : 0.0;
        return b.diffuse * diff * (1.0 - f) + f * spec;
    }
    if ((lobes & CG_BSDF_TRANSMISSION) == 0 || smooth_surface || all(lessThanEqual(b.transmission, vec3(0.0))))
        return vec3(0.0);
    float anl = -nl;
    vec3 f;
    float t;
    if (b.thickness <= 0.0) {
        // Thin-walled: the light goes on through the sheet; l mirrored through the plane.
        vec3 lm = l - 2.0 * dot(n, l) * n;
        vec3 h = normalize(v + lm);
        f = cg_bsdf_fresnel(b.f0, b.f90, dot(v, h));
        t = cg_bsdf_ggx_d(b.alpha, dot(n, h)) * cg_bsdf_smith_v(b.alpha, anl, nv) * anl;
    } else {
        // Walter 2007 eq. 16's half vector, turned to n's side.
        vec3 h = normalize(-(v + eta * l));
        if (dot(h, n) < 0.0)
            h = -h;
        float vh = dot(v, h), lh = dot(l, h);
        if (!(vh > 0.0 && lh < 0.0))
            return vec3(0.0);
        f = cg_bsdf_fresnel_dielectric(b, vh, eta);
        float denom = vh + eta * lh;
        // Walter 2007 eq. 21 with G = 4 V |n.l| |n.v|, times |n.l|.
        t = 4.0 * vh * abs(lh) * eta * eta * cg_bsdf_smith_v(b.alpha, anl, nv) * cg_bsdf_ggx_d(b.alpha, dot(n, h)) *
            anl / (denom * denom);
    }
    return b.transmission * (1.0 - f) * t;
}

// What the diffuse lobe returns of uniform incident light, averaged over the outgoing directions
// (cosine-weighted): rho (1 - F0 A - F90 B). The view-independent albedo a voxel, which radiates the
// same radiance every way, stores: the diffuse exitance is then exact in a furnace, where rho alone
// would leave out what the specular lobe took (4.4% at ior 1.5). rho for a Lambertian material.
vec3
cg_bsdf_diffuse_hemispherical(CgBsdf b)
{
    return b.diffuse * (1.0 - b.f0 * CG_BSDF_DIFFUSE_HEMISPHERICAL_A - b.f90 * CG_BSDF_DIFFUSE_HEMISPHERICAL_B);
}

// The BSDF of a G-buffer pixel (the gbuffer pass's outputs albedo, specular, transmission, material
// and attenuation, docs/passes.md): the quantities cg_bsdf_from_material computed there.
CgBsdf
cg_bsdf_from_gbuffer(vec4 albedo, vec4 specular, vec4 transmission, vec4 material, vec4 attenuation)
{
    CgBsdf b;
    b.diffuse = albedo.rgb;
    b.f0 = specular.rgb;
    b.f90 = specular.a;
    b.roughness = clamp(material.x, 0.0, 1.0);
    b.alpha = b.roughness * b.roughness;
    b.transmission = transmission.rgb;
    b.ior = transmission.a;
    b.thickness = material.z;
    b.sigma = attenuation.rgb;
    return b;
}

#endif
