/* glTF 2.0's BSDF in scalar C: see cg/bsdf.h for the model, the conventions and the sources. */
#include "cg/bsdf.h"

#include <math.h>

#define BSDF_PI 3.14159265358979323846f
#define BSDF_ALBEDO_GRID 64

static float
clamp01(float x)
{
    return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x);
}

static float
dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void
normalize3(float a[3])
{
    float len = sqrtf(dot3(a, a));
    if (len > 0.0f)
        for (int k = 0; k < 3; k++)
            a[k] /= len;
}

/* The channel mean: how a lobe's weight is judged when lobes are chosen (the GLSL side does the same). */
static float
mean3(const float a[3])
{
    return (a[0] + a[1] + a[2]) * (1.0f / 3.0f);
}

static float
pow5(float x)
{
    float x2 = x * x;
    return x2 * x2 * x;
}

void
cg_bsdf_from_material(const cg_material *m, const float base_color[4], float metallic, float roughness,
                      float transmission, cg_bsdf *out)
{
    float metal = clamp01(metallic), trans = clamp01(transmission);
    float rough = clamp01(roughness);
    float ior = m->ior > 0.0f ? m->ior : 1.5f;
    /* KHR_materials_ior: F0 of a dielectric from its ior; KHR_materials_specular scales it by
     * specularColor (clamped to 1) and specular, and sets F90 = specular. */
    float r = (ior - 1.0f) / (ior + 1.0f);
    float f0_ior = r * r;
    for (int k = 0; k < 3; k++) {
        float base = base_color[k];
        float f0_dielectric = fminf(f0_ior * m->specular_color[k], 1.0f) * m->specular;
        /* glTF Appendix B.3.5: mix(dielectric_brdf, metal_brdf, metallic); the metal's F0 is the base colour. */
        out->f0[k] = f0_dielectric + (base - f0_dielectric) * metal;
        out->diffuse[k] = (1.0f - metal) * (1.0f - trans) * base;
        out->transmission[k] = (1.0f - metal) * trans * base;
        float sigma = 0.0f;
        if (isfinite(m->attenuation_distance) && m->attenuation_distance > 0.0f)
            sigma = -logf(fmaxf(m->attenuation_color[k], 1e-6f)) / m->attenuation_distance;
        out->sigma[k] = sigma;
    }
    out->f90 = m->specular + (1.0f - m->specular) * metal;
    out->roughness = rough;
    out->alpha = rough * rough;
    out->ior = ior;
    out->thickness = m->thickness > 0.0f ? m->thickness : 0.0f;
}

bool
cg_bsdf_is_smooth(const cg_bsdf *b)
{
    return b->alpha < CG_BSDF_ALPHA_MIN;
}

float
cg_bsdf_ggx_d(float alpha, float n_dot_h)
{
    float a2 = alpha * alpha;
    float t = n_dot_h * n_dot_h * (a2 - 1.0f) + 1.0f;
    return a2 / (BSDF_PI * t * t);
}

float
cg_bsdf_smith_v(float alpha, float n_dot_l, float n_dot_v)
{
    float a2 = alpha * alpha;
    float nl = fabsf(n_dot_l), nv = fabsf(n_dot_v);
    float gv = nl * sqrtf(nv * nv * (1.0f - a2) + a2);
    float gl = nv * sqrtf(nl * nl * (1.0f - a2) + a2);
    float s = gv + gl;
    return s > 0.0f ? 0.5f / s : 0.0f;
}

float
cg_bsdf_smith_g1(float alpha, float n_dot_v)
{
    float a2 = alpha * alpha;
    float nv = fabsf(n_dot_v);
    float s = nv + sqrtf(a2 + (1.0f - a2) * nv * nv);
    return s > 0.0f ? 2.0f * nv / s : 0.0f;
}

void
cg_bsdf_fresnel(const float f0[3], float f90, float v_dot_h, float out[3])
{
    float w = pow5(1.0f - clamp01(fabsf(v_dot_h)));
    for (int k = 0; k < 3; k++)
        out[k] = f0[k] + (f90 - f0[k]) * w;
}

static bool
bsdf_is_solid(const cg_bsdf *b)
{
    return b->thickness > 0.0f;
}

void
cg_bsdf_fresnel_dielectric(const cg_bsdf *b, float v_dot_h, float eta, float out[3])
{
    float c = fabsf(v_dot_h);
    if (bsdf_is_solid(b) && eta < 1.0f) {
        /* Leaving the denser medium: Snell's sin_t = sin_i / eta; Schlick's approximation holds on the
         * larger (outside) angle, so F0 is the same from both sides. */
        float sin2_t = (1.0f - c * c) / (eta * eta);
        if (sin2_t >= 1.0f) {
            out[0] = out[1] = out[2] = 1.0f;
            return;
        }
        c = sqrtf(1.0f - sin2_t);
    }
    cg_bsdf_fresnel(b->f0, b->f90, c, out);
}

/* An orthonormal frame (t, s, n) around unit n: Duff et al., "Building an Orthonormal Basis,
 * Revisited" (JCGT 6(1), 2017), listing 3. */
static void
frame_of(const float n[3], float t[3], float s[3])
{
    float sign = copysignf(1.0f, n[2]);
    float a = -1.0f / (sign + n[2]);
    float b = n[0] * n[1] * a;
    t[0] = 1.0f + sign * n[0] * n[0] * a;
    t[1] = sign * b;
    t[2] = -sign * n[0];
    s[0] = b;
    s[1] = sign + n[1] * n[1] * a;
    s[2] = -n[1];
}

/* The lobe-choice weights (what cg_bsdf_sample and cg_bsdf_pdf agree on): the diffuse lobe by
 * rho (1 - F(n.v)), the microfacet lobes by F(n.v) (glossy) plus tau (1 - F(n.v)) (transmission). */
static float
diffuse_probability(const cg_bsdf *b, float n_dot_v, int lobes, bool *any)
{
    float fn[3], fd[3], ft[3];
    cg_bsdf_fresnel(b->f0, b->f90, n_dot_v, fn);
    for (int k = 0; k < 3; k++) {
        fd[k] = b->diffuse[k] * (1.0f - fn[k]);
        ft[k] = b->transmission[k] * (1.0f - fn[k]);
    }
    float wd = (lobes & CG_BSDF_DIFFUSE) ? mean3(fd) : 0.0f;
    float ws = ((lobes & CG_BSDF_GLOSSY) ? mean3(fn) : 0.0f) + ((lobes & CG_BSDF_TRANSMISSION) ? mean3(ft) : 0.0f);
    *any = wd + ws > 0.0f;
    return *any ? wd / (wd + ws) : 0.0f;
}

/* Given a microfacet normal's Fresnel, the probability of reflecting rather than transmitting. */
static float
reflect_probability(const cg_bsdf *b, const float f[3], int lobes)
{
    float ft[3];
    for (int k = 0; k < 3; k++)
        ft[k] = b->transmission[k] * (1.0f - f[k]);
    float wr = (lobes & CG_BSDF_GLOSSY) ? mean3(f) : 0.0f;
    float wt = (lobes & CG_BSDF_TRANSMISSION) ? mean3(ft) : 0.0f;
    return wr + wt > 0.0f ? wr / (wr + wt) : 0.0f;
}

static bool
has_transmission(const cg_bsdf *b)
{
    return b->transmission[0] > 0.0f || b->transmission[1] > 0.0f || b->transmission[2] > 0.0f;
}

/* The half vector of a solid's refraction, Walter 2007 eq. 16 with eta_i = 1, eta_o = eta, turned to
 * n's side; false where v and l are not on the opposite sides of it that refraction needs. */
static bool
refraction_half(const float n[3], const float v[3], const float l[3], float eta, float h[3])
{
    for (int k = 0; k < 3; k++)
        h[k] = -(v[k] + eta * l[k]);
    normalize3(h);
    if (dot3(h, n) < 0.0f)
        for (int k = 0; k < 3; k++)
            h[k] = -h[k];
    return dot3(v, h) > 0.0f && dot3(l, h) < 0.0f;
}

/* The other side's direction of a thin sheet: l mirrored through the surface's plane. */
static void
mirror_plane(const float n[3], const float l[3], float out[3])
{
    float d = 2.0f * dot3(n, l);
    for (int k = 0; k < 3; k++)
        out[k] = l[k] - d * n[k];
}

void
cg_bsdf_eval(const cg_bsdf *b, const float n[3], const float v[3], const float l[3], float eta, int lobes,
             float out[3])
{
    out[0] = out[1] = out[2] = 0.0f;
    float nv = dot3(n, v), nl = dot3(n, l);
    if (nv <= 0.0f || nl == 0.0f)
        return;
    bool smooth = cg_bsdf_is_smooth(b);
    if (nl > 0.0f) {
        if (!(lobes & (CG_BSDF_DIFFUSE | CG_BSDF_GLOSSY)))
            return;
        float h[3] = { v[0] + l[0], v[1] + l[1], v[2] + l[2] };
        normalize3(h);
        float f[3];
        cg_bsdf_fresnel_dielectric(b, dot3(v, h), eta, f);
        float spec = 0.0f;
        if ((lobes & CG_BSDF_GLOSSY) && !smooth)
            spec = cg_bsdf_ggx_d(b->alpha, dot3(n, h)) * cg_bsdf_smith_v(b->alpha, nl, nv) * nl;
        float diff = (lobes & CG_BSDF_DIFFUSE) ? nl / BSDF_PI : 0.0f;
        for (int k = 0; k < 3; k++)
            out[k] = b->diffuse[k] * diff * (1.0f - f[k]) + f[k] * spec;
        return;
    }
    if (!(lobes & CG_BSDF_TRANSMISSION) || smooth || !has_transmission(b))
        return;
    float anl = -nl;
    float h[3], f[3], t;
    if (!bsdf_is_solid(b)) {
        float lm[3];
        mirror_plane(n, l, lm);
        for (int k = 0; k < 3; k++)
            h[k] = v[k] + lm[k];
        normalize3(h);
        cg_bsdf_fresnel(b->f0, b->f90, dot3(v, h), f);
        t = cg_bsdf_ggx_d(b->alpha, dot3(n, h)) * cg_bsdf_smith_v(b->alpha, anl, nv) * anl;
    } else {
        if (!refraction_half(n, v, l, eta, h))
            return;
        float vh = dot3(v, h), lh = dot3(l, h);
        cg_bsdf_fresnel_dielectric(b, vh, eta, f);
        float denom = vh + eta * lh;
        /* Walter 2007 eq. 21: |i.h||o.h| / (|i.n||o.n|) eta_o^2 G D / (eta_i i.h + eta_o o.h)^2, with
         * G = 4 V |n.l||n.v|; times |n.l|. */
        t = 4.0f * vh * fabsf(lh) * eta * eta * cg_bsdf_smith_v(b->alpha, anl, nv) *
            cg_bsdf_ggx_d(b->alpha, dot3(n, h)) * anl / (denom * denom);
    }
    for (int k = 0; k < 3; k++)
        out[k] = b->transmission[k] * (1.0f - f[k]) * t;
}

float
cg_bsdf_pdf(const cg_bsdf *b, const float n[3], const float v[3], const float l[3], float eta, int lobes)
{
    float nv = dot3(n, v), nl = dot3(n, l);
    if (nv <= 0.0f || nl == 0.0f)
        return 0.0f;
    bool any;
    float pd = diffuse_probability(b, nv, lobes, &any);
    if (!any)
        return 0.0f;
    bool smooth = cg_bsdf_is_smooth(b);
    float g1 = cg_bsdf_smith_g1(b->alpha, nv);
    if (nl > 0.0f) {
        float pdf = pd * nl / BSDF_PI;
        if (!smooth && pd < 1.0f) {
            float h[3] = { v[0] + l[0], v[1] + l[1], v[2] + l[2] };
            normalize3(h);
            float f[3];
            cg_bsdf_fresnel_dielectric(b, dot3(v, h), eta, f);
            float pr = reflect_probability(b, f, lobes);
            /* Heitz 2018 eq. 3 and the reflection's Jacobian 1/(4 v.h): G1(v) D(h) / (4 n.v). */
            pdf += (1.0f - pd) * pr * g1 * cg_bsdf_ggx_d(b->alpha, dot3(n, h)) / (4.0f * nv);
        }
        return pdf;
    }
    if (smooth || pd >= 1.0f || !has_transmission(b))
        return 0.0f;
    float h[3], f[3];
    if (!bsdf_is_solid(b)) {
        float lm[3];
        mirror_plane(n, l, lm);
        for (int k = 0; k < 3; k++)
            h[k] = v[k] + lm[k];
        normalize3(h);
        cg_bsdf_fresnel(b->f0, b->f90, dot3(v, h), f);
        float pr = reflect_probability(b, f, lobes);
        return (1.0f - pd) * (1.0f - pr) * g1 * cg_bsdf_ggx_d(b->alpha, dot3(n, h)) / (4.0f * nv);
    }
    if (!refraction_half(n, v, l, eta, h))
        return 0.0f;
    float vh = dot3(v, h), lh = dot3(l, h);
    cg_bsdf_fresnel_dielectric(b, vh, eta, f);
    float pr = reflect_probability(b, f, lobes);
    float denom = vh + eta * lh;
    /* The visible normals' pdf times the refraction's Jacobian eta^2 |o.h| / (i.h + eta o.h)^2 (Walter 2007 eq. 17). */
    float dv = g1 * vh * cg_bsdf_ggx_d(b->alpha, dot3(n, h)) / nv;
    return (1.0f - pd) * (1.0f - pr) * dv * eta * eta * fabsf(lh) / (denom * denom);
}

void
cg_bsdf_sample_vndf(float alpha, const float v_local[3], float u1, float u2, float h_local[3])
{
    /* Heitz 2018, listing 1: stretch the view, sample the projected disc, unstretch. */
    float vh[3] = { alpha * v_local[0], alpha * v_local[1], v_local[2] };
    normalize3(vh);
    float lensq = vh[0] * vh[0] + vh[1] * vh[1];
    float t1v[3] = { 1.0f, 0.0f, 0.0f };
    if (lensq > 0.0f) {
        float inv = 1.0f / sqrtf(lensq);
        t1v[0] = -vh[1] * inv;
        t1v[1] = vh[0] * inv;
        t1v[2] = 0.0f;
    }
    float t2v[3] = { vh[1] * t1v[2] - vh[2] * t1v[1], vh[2] * t1v[0] - vh[0] * t1v[2],
                     vh[0] * t1v[1] - vh[1] * t1v[0] };
    float r = sqrtf(u1);
    float phi = 2.0f * BSDF_PI * u2;
    float t1 = r * cosf(phi), t2 = r * sinf(phi);
    float s = 0.5f * (1.0f + vh[2]);
    t2 = (1.0f - s) * sqrtf(fmaxf(0.0f, 1.0f - t1 * t1)) + s * t2;
    float tz = sqrtf(fmaxf(0.0f, 1.0f - t1 * t1 - t2 * t2));
    float nh[3];
    for (int k = 0; k < 3; k++)
        nh[k] = t1 * t1v[k] + t2 * t2v[k] + tz * vh[k];
    h_local[0] = alpha * nh[0];
    h_local[1] = alpha * nh[1];
    h_local[2] = fmaxf(0.0f, nh[2]);
    normalize3(h_local);
}

bool
cg_bsdf_sample(const cg_bsdf *b, const float n[3], const float v[3], float eta, int lobes, const float u[3],
               cg_bsdf_sample_result *out)
{
    float nv = dot3(n, v);
    if (nv <= 0.0f)
        return false;
    bool any;
    float pd = diffuse_probability(b, nv, lobes, &any);
    if (!any)
        return false;
    float t[3], s[3];
    frame_of(n, t, s);
    out->delta = false;
    out->refracted = false;
    if (u[0] < pd) {
        /* Cosine-weighted hemisphere (Malley's method). */
        float r = sqrtf(u[1]), phi = 2.0f * BSDF_PI * u[2];
        float x = r * cosf(phi), y = r * sinf(phi), z = sqrtf(fmaxf(0.0f, 1.0f - u[1]));
        for (int k = 0; k < 3; k++)
            out->l[k] = x * t[k] + y * s[k] + z * n[k];
        out->lobe = CG_BSDF_DIFFUSE;
    } else {
        float uc = pd > 0.0f ? (u[0] - pd) / (1.0f - pd) : u[0];
        bool smooth = cg_bsdf_is_smooth(b);
        float h[3];
        if (smooth) {
            h[0] = n[0], h[1] = n[1], h[2] = n[2];
        } else {
            float vl[3] = { dot3(v, t), dot3(v, s), nv }, hl[3];
            cg_bsdf_sample_vndf(b->alpha, vl, u[1], u[2], hl);
            for (int k = 0; k < 3; k++)
                h[k] = hl[0] * t[k] + hl[1] * s[k] + hl[2] * n[k];
        }
        float vh = dot3(v, h);
        if (vh <= 0.0f)
            return false;
        float f[3];
        cg_bsdf_fresnel_dielectric(b, vh, eta, f);
        float pr = reflect_probability(b, f, lobes);
        float r[3];
        for (int k = 0; k < 3; k++)
            r[k] = 2.0f * vh * h[k] - v[k];
        if (uc < pr) {
            for (int k = 0; k < 3; k++)
                out->l[k] = r[k];
            out->lobe = CG_BSDF_GLOSSY;
            if (dot3(n, out->l) <= 0.0f)
                return false;
        } else {
            out->lobe = CG_BSDF_TRANSMISSION;
            if (!bsdf_is_solid(b)) {
                mirror_plane(n, r, out->l);
            } else {
                /* Walter 2007 eq. 40 with eta_i/eta_o = 1/eta: o = (c/eta - sqrt(1 + (c^2 - 1)/eta^2)) h - v/eta. */
                float inv = 1.0f / eta;
                float k2 = 1.0f + inv * inv * (vh * vh - 1.0f);
                if (k2 <= 0.0f)
                    return false; /* total internal reflection: pr was 1, this is float rounding */
                float c = vh * inv - sqrtf(k2);
                for (int k = 0; k < 3; k++)
                    out->l[k] = c * h[k] - inv * v[k];
                normalize3(out->l);
                out->refracted = true;
            }
            if (dot3(n, out->l) >= 0.0f)
                return false;
        }
        if (smooth) {
            /* A delta lobe: its weight is its Fresnel share over the probability of having chosen it. */
            float p = (1.0f - pd) * (out->lobe == CG_BSDF_GLOSSY ? pr : 1.0f - pr);
            for (int k = 0; k < 3; k++)
                out->weight[k] = (out->lobe == CG_BSDF_GLOSSY ? f[k] : b->transmission[k] * (1.0f - f[k])) / p;
            out->pdf = 0.0f;
            out->delta = true;
            return true;
        }
    }
    /* Every lobe allowed could have drawn l: the one-sample estimate divides the sum of their f by the
     * sum of their pdfs (the balance heuristic over lobes). */
    float pdf = cg_bsdf_pdf(b, n, v, out->l, eta, lobes);
    if (!(pdf > 0.0f))
        return false;
    float f[3];
    cg_bsdf_eval(b, n, v, out->l, eta, lobes, f);
    for (int k = 0; k < 3; k++)
        out->weight[k] = f[k] / pdf;
    out->pdf = pdf;
    return true;
}

void
cg_bsdf_specular_albedo_terms(float alpha, float n_dot_v, float *scale, float *bias)
{
    float nv = fminf(fmaxf(n_dot_v, 1e-4f), 1.0f);
    if (alpha < CG_BSDF_ALPHA_MIN) {
        float w = pow5(1.0f - nv);
        *scale = 1.0f - w;
        *bias = w;
        return;
    }
    float v[3] = { sqrtf(1.0f - nv * nv), 0.0f, nv };
    double a = 0.0, c = 0.0;
    float g1 = cg_bsdf_smith_g1(alpha, nv);
    for (int i = 0; i < BSDF_ALBEDO_GRID; i++)
        for (int j = 0; j < BSDF_ALBEDO_GRID; j++) {
            float h[3];
            cg_bsdf_sample_vndf(alpha, v, ((float)i + 0.5f) / BSDF_ALBEDO_GRID, ((float)j + 0.5f) / BSDF_ALBEDO_GRID,
                                h);
            float vh = dot3(v, h);
            float lz = 2.0f * vh * h[2] - v[2];
            if (lz <= 0.0f || vh <= 0.0f)
                continue;
            /* F D V (n.l) over the visible normals' pdf G1 D / (4 n.v): F 4 V (n.l)(n.v) / G1 = F G2 / G1. */
            float g = 4.0f * cg_bsdf_smith_v(alpha, lz, nv) * lz * nv / g1;
            float w = pow5(1.0f - vh);
            a += (double)((1.0f - w) * g);
            c += (double)(w * g);
        }
    double n = (double)BSDF_ALBEDO_GRID * BSDF_ALBEDO_GRID;
    *scale = (float)(a / n);
    *bias = (float)(c / n);
}

void
cg_bsdf_diffuse_albedo_terms(float n_dot_v, float *a, float *b)
{
    float nv = fminf(fmaxf(n_dot_v, 0.0f), 1.0f);
    float v[3] = { sqrtf(1.0f - nv * nv), 0.0f, nv };
    double sa = 0.0, sb = 0.0;
    /* (n.l)/pi dl is du dphi / (2 pi) with u = cos^2 theta: the mean over a grid in (u, phi). */
    for (int i = 0; i < BSDF_ALBEDO_GRID; i++)
        for (int j = 0; j < BSDF_ALBEDO_GRID; j++) {
            float u = ((float)i + 0.5f) / BSDF_ALBEDO_GRID;
            float phi = 2.0f * BSDF_PI * ((float)j + 0.5f) / BSDF_ALBEDO_GRID;
            float st = sqrtf(1.0f - u), ct = sqrtf(u);
            float h[3] = { v[0] + st * cosf(phi), v[1] + st * sinf(phi), v[2] + ct };
            normalize3(h);
            float w = pow5(1.0f - clamp01(dot3(v, h)));
            sa += (double)(1.0f - w);
            sb += (double)w;
        }
    double n = (double)BSDF_ALBEDO_GRID * BSDF_ALBEDO_GRID;
    *a = (float)(sa / n);
    *b = (float)(sb / n);
}

void
cg_bsdf_albedo(const cg_bsdf *b, float n_dot_v, float diffuse[3], float glossy[3], float transmission[3])
{
    float sa, sb, da, db;
    cg_bsdf_specular_albedo_terms(b->alpha, n_dot_v, &sa, &sb);
    cg_bsdf_diffuse_albedo_terms(n_dot_v, &da, &db);
    for (int k = 0; k < 3; k++) {
        diffuse[k] = b->diffuse[k] * (1.0f - b->f0[k] * da - b->f90 * db);
        glossy[k] = b->f0[k] * sa + b->f90 * sb;
        transmission[k] = b->transmission[k] * ((1.0f - b->f0[k]) * sa + (1.0f - b->f90) * sb);
    }
}
