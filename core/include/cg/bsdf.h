/* cg/bsdf.h: glTF 2.0's metallic-roughness BSDF, defined once in C (the path tracer's), mirrored
 * function by function in GLSL (shaders/common/bsdf.glsl, the same cg_bsdf_* names).
 *
 * Declares: cg_bsdf, cg_bsdf_lobe, CG_BSDF_ALL_LOBES, CG_BSDF_ALPHA_MIN, cg_bsdf_sample_result,
 *           cg_bsdf_from_material, cg_bsdf_is_smooth, cg_bsdf_ggx_d, cg_bsdf_smith_v,
 *           cg_bsdf_smith_g1, cg_bsdf_fresnel, cg_bsdf_fresnel_dielectric, cg_bsdf_eval,
 *           cg_bsdf_pdf, cg_bsdf_sample, cg_bsdf_sample_vndf, cg_bsdf_specular_albedo_terms,
 *           cg_bsdf_diffuse_albedo_terms, cg_bsdf_albedo.
 *
 * The model (glTF 2.0 specification, Appendix B "BRDF Implementation", with KHR_materials_ior,
 * _specular, _transmission and _volume):
 *   f = rho/pi (1 - F)                        diffuse, rho = (1-m)(1-T) baseColor     (B.3.4, B.3.5)
 *     + F D V                                 glossy reflection (GGX, B.3.2, B.3.3)
 *     + tau (1 - F) btdf                      transmission, tau = (1-m) T baseColor
 *   D = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2), alpha = roughness^2           (B.3.2)
 *   V = height-correlated Smith G2 / (4 |n.l| |n.v|)                                 (B.3.2)
 *   F = F0 + (F90 - F0) (1 - |v.h|)^5 (Schlick)                                       (B.3.4)
 *   F0 = mix(min(((ior-1)/(ior+1))^2 specularColor, 1) specular, baseColor, m), F90 = mix(specular, 1, m)
 * btdf: thin-walled (thickness 0): the GGX lobe mirrored through the surface's plane (the
 * direction goes on through the sheet, blurred by the roughness: KHR_materials_transmission);
 * solid: the rough dielectric BTDF of Walter, Marschner, Li and Torrance, "Microfacet Models for
 * Refraction through Rough Surfaces" (EGSR 2007), eq. 21 with the half vector of eq. 16, so that
 * a sample weighs (1 - F) G2/G1 (no eta^2 radiance scaling: a closed solid is entered and left,
 * and the factors cancel). Beer-Lambert inside a solid, exp(-sigma d), is the tracer's (it knows d).
 *
 * Conventions of every function: world-space unit vectors; n the shading normal, v towards the
 * viewer (where the light goes), l towards the light (where it comes from); the caller turns n to
 * v's side (n.v > 0). l on n's side is reflection, on the other side transmission. `eta` is the
 * index of refraction on l's side of a transmission over v's side: ior when v is outside a solid,
 * 1/ior when inside; ignored for thin-walled materials. eval returns f x |n.l| (per channel).
 * Roughness below CG_BSDF_ALPHA_MIN (alpha) is smooth: its glossy and transmission lobes are
 * Dirac deltas that only cg_bsdf_sample returns (eval and pdf give them 0), as pbrt-v4 does.
 */
#ifndef CG_BSDF_H
#define CG_BSDF_H

#include <stdbool.h>

#include "cg/scene.h"

/* Lobes, as flags: a mask of the lobes a caller allows (bounce limits, caustics), and the label of
 * a sample (Cycles' bounce kinds: reflection off glass is glossy, refraction is transmission). */
typedef enum cg_bsdf_lobe {
    CG_BSDF_DIFFUSE = 1,
    CG_BSDF_GLOSSY = 2,
    CG_BSDF_TRANSMISSION = 4
} cg_bsdf_lobe;
#define CG_BSDF_ALL_LOBES (CG_BSDF_DIFFUSE | CG_BSDF_GLOSSY | CG_BSDF_TRANSMISSION)

/* alpha below this is a smooth (delta) surface: 1e-3 as pbrt-v4's TrowbridgeReitzDistribution. */
#define CG_BSDF_ALPHA_MIN 1e-3f

/* A material at one surface point: the same quantities as the G-buffer's (the issue 35 contract). */
typedef struct cg_bsdf {
    float diffuse[3];      /* rho = (1-m)(1-T) baseColor */
    float f0[3];           /* F0, metal and dielectric mixed by metallic */
    float f90;             /* F90 */
    float roughness;       /* glTF perceptual roughness, clamped to [0, 1] */
    float alpha;           /* roughness^2 */
    float transmission[3]; /* tau = (1-m) T baseColor */
    float ior;             /* KHR_materials_ior */
    float thickness;       /* KHR_materials_volume thicknessFactor; 0 = thin-walled */
    float sigma[3];        /* Beer-Lambert coefficient -ln(attenuationColor)/attenuationDistance, 1/m */
} cg_bsdf;

/* What cg_bsdf_sample draws. */
typedef struct cg_bsdf_sample_result {
    float l[3];            /* the direction towards where the light comes from, unit */
    float weight[3];       /* f |n.l| / pdf: the throughput's factor */
    float pdf;             /* solid-angle pdf of sampling l with the lobes allowed (cg_bsdf_pdf);
                            * 0 for a delta sample */
    int lobe;              /* CG_BSDF_DIFFUSE, _GLOSSY or _TRANSMISSION */
    bool delta;            /* a smooth lobe's (Dirac) sample: no light sampling can find it */
    bool refracted;        /* l crossed into the other medium of a solid (not thin-walled) */
} cg_bsdf_sample_result;

/* The BSDF of material m where its base colour (factor x texture, linear RGBA) is base_color and its
 * metallic, roughness and transmission (factors x textures) are given. Alpha (coverage) is not part
 * of it: MASK and BLEND are the caller's (see cg/scene.h). Occlusion is not either: it darkens the
 * raster's indirect light only. */
void cg_bsdf_from_material(const cg_material *m, const float base_color[4], float metallic, float roughness,
                           float transmission, cg_bsdf *out);

/* True where the glossy and transmission lobes are deltas (alpha < CG_BSDF_ALPHA_MIN). */
bool cg_bsdf_is_smooth(const cg_bsdf *b);

/* The GGX (Trowbridge-Reitz) normal distribution D(h), glTF Appendix B.3.2. */
float cg_bsdf_ggx_d(float alpha, float n_dot_h);

/* The height-correlated Smith visibility V = G2 / (4 |n.l| |n.v|), glTF Appendix B.3.2 (Heitz 2014,
 * "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", eq. 99). */
float cg_bsdf_smith_v(float alpha, float n_dot_l, float n_dot_v);

/* Smith's masking G1 of GGX, 2 |n.v| / (|n.v| + sqrt(alpha^2 + (1 - alpha^2) (n.v)^2)) (Heitz 2014, eq. 72). */
float cg_bsdf_smith_g1(float alpha, float n_dot_v);

/* Schlick's Fresnel F0 + (F90 - F0) (1 - |v.h|)^5, per channel (glTF Appendix B.3.4). */
void cg_bsdf_fresnel(const float f0[3], float f90, float v_dot_h, float out[3]);

/* The Fresnel weight of reflection for the material, at the microfacet normal h, where light crosses
 * from v's side into a medium of relative index eta: Schlick on |v.h| entering a denser medium, on the
 * transmitted angle's cosine leaving it (so that the F0 of a glass is the same from both sides), 1
 * (total internal reflection) where Snell has no solution. Thin-walled (thickness 0): Schlick on |v.h|. */
void cg_bsdf_fresnel_dielectric(const cg_bsdf *b, float v_dot_h, float eta, float out[3]);

/* f(v, l) |n.l| of the lobes in `lobes` (a mask of cg_bsdf_lobe); delta lobes give 0. */
void cg_bsdf_eval(const cg_bsdf *b, const float n[3], const float v[3], const float l[3], float eta, int lobes,
                  float out[3]);

/* The solid-angle pdf with which cg_bsdf_sample, allowed `lobes`, draws l (delta lobes excluded). */
float cg_bsdf_pdf(const cg_bsdf *b, const float n[3], const float v[3], const float l[3], float eta, int lobes);

/* Draws l from u (three uniform numbers in [0, 1)): a lobe by its estimated weight, then cosine-
 * weighted hemisphere for the diffuse lobe, or a GGX visible normal (Heitz 2018, "Sampling the GGX
 * Distribution of Visible Normals", JCGT 7(4), listing 1) that reflects, or refracts (Walter 2007,
 * eq. 40), the second by the Fresnel weight. False when nothing was drawn (no lobe allowed has weight,
 * or the direction fell below the surface): the path ends. */
bool cg_bsdf_sample(const cg_bsdf *b, const float n[3], const float v[3], float eta, int lobes, const float u[3],
                    cg_bsdf_sample_result *out);

/* A visible normal of GGX for the view direction v_local in the frame where n = +z (Heitz 2018,
 * listing 1, isotropic alpha), from two uniform numbers. Its pdf is G1(v) max(0, v.h) D(h) / (n.v). */
void cg_bsdf_sample_vndf(float alpha, const float v_local[3], float u1, float u2, float h_local[3]);

/* The directional albedo of the glossy lobe, split by Schlick's two terms as the split-sum tables
 * are (Karis, "Real Shading in Unreal Engine 4", 2013): the integral over the hemisphere of
 * F D V (n.l) is f0 x scale + f90 x bias. Numerical (a 64 x 64 stratified set of visible normals);
 * smooth: scale = 1 - (1 - n.v)^5, bias = (1 - n.v)^5. */
void cg_bsdf_specular_albedo_terms(float alpha, float n_dot_v, float *scale, float *bias);

/* The same for the diffuse lobe's (1 - F): the integral of (1 - F(v.h)) (n.l)/pi, with h = (v+l)/|v+l|,
 * is 1 - f0 x a - f90 x b. Numerical (a 64 x 64 midpoint rule in cos^2 theta and phi); it does not
 * depend on roughness. */
void cg_bsdf_diffuse_albedo_terms(float n_dot_v, float *a, float *b);

/* The directional albedo (the integral of f |n.l| over the sphere) of each lobe for viewing angle
 * n_dot_v: diffuse, glossy and transmission, each RGB. Thin-walled transmission is tau x the glossy
 * integral with (1 - F) for F; a solid's refracted albedo is approximated the same way (what a white
 * furnace through a slab sees: every refracted ray leaves again). */
void cg_bsdf_albedo(const cg_bsdf *b, float n_dot_v, float diffuse[3], float glossy[3], float transmission[3]);

#endif
