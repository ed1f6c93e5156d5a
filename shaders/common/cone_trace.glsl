// common/cone_trace.glsl: one cone marched front to back through a mipped 3D lightmap.
//
// Provides: CgCone, cg_cone_trace(), cg_cone_lod(), cg_cone_origin(), cg_cone_reach(),
//           cg_cone_gather_diffuse(), cg_tangent_frame().
// Requires: common/volume.glsl.
//
// VCT paper 3.2 (after Crassin et al. 2011): the cone's footprint at distance t has the
// diameter d = 2 t tan(half angle); the sample is read from the mip level whose voxels
// are d wide (hybrid eq. 8: Lv = log2(d / voxel size)) and composited front to back,
//     c += (1 - a) * alpha_s * c_s,   a += (1 - a) * alpha_s,
// where the volume stores premultiplied colour (alpha_s * c_s), so it is added as read.
// The march stops when a reaches CG_CONE_OPAQUE, past t_max, or once the footprint has
// left the volume (VCT paper 3.2.1). The hybrid tracer reuses cg_cone_lod() and the
// compositing step through cg_cone_composite().
#ifndef CG_COMMON_CONE_TRACE_GLSL
#define CG_COMMON_CONE_TRACE_GLSL

#include "common/volume.glsl"

#define CG_CONE_OPAQUE 0.999

struct CgCone {
    vec3 origin;        // world; already moved off the surface by the caller
    vec3 direction;     // unit
    float tan_half;     // tan of the half apex angle (> 0)
    float t_start;      // world distance of the first sample
    float t_max;        // world distance past which the march stops
    float step_factor;  // sample spacing as a fraction of the footprint diameter (> 0)
    float lod_bias;     // added to the level of eq. 8 (see cg_cone_trace)
};

// Footprint diameter at distance t, never below one voxel: log2 of a zero (or sub-voxel)
// diameter would be -inf (or sample a finer level than exists), so the guard is here.
float
cg_cone_diameter(CgCone c, CgVolume v, float t)
{
    return max(2.0 * c.tan_half * t, v.voxel_size);
}

// Hybrid eq. 8, guarded by cg_cone_diameter: Lv = log2(diameter / voxel size) >= 0.
float
cg_cone_lod(CgVolume v, float diameter)
{
    return log2(diameter / v.voxel_size);
}

// One compositing step with a premultiplied sample, as the VCT paper and the issue state
// it: c += (1 - a) * alpha_s * c_s; a += (1 - a) * alpha_s. No Beer-Lambert correction of
// alpha_s for the step length: the voxels hold surfaces (alpha is coverage, not a density),
// and with trilinear filtering the correction lets cones slip through walls that the coarse
// levels have spread over a whole cell (docs/vct.md: the furnace falls 2.5% short with it).
void
cg_cone_composite(inout vec4 acc, vec4 s)
{
    float alpha = clamp(s.a, 0.0, 1.0);
    acc.rgb += (1.0 - acc.a) * s.rgb;
    acc.a += (1.0 - acc.a) * alpha;
}

#ifdef CG_CONE_ANISOTROPIC
// Six directional chains of levels 1.. (mip3d with anisotropic = true): level k of cg_aniso_px
// is level k + 1 as seen by a cone travelling along +x, and so on (Crassin et al. 2011).
#define CG_CONE_ANISO_BINDING 3
layout(binding = CG_CONE_ANISO_BINDING + 0) uniform sampler3D cg_aniso_px;
layout(binding = CG_CONE_ANISO_BINDING + 1) uniform sampler3D cg_aniso_nx;
layout(binding = CG_CONE_ANISO_BINDING + 2) uniform sampler3D cg_aniso_py;
layout(binding = CG_CONE_ANISO_BINDING + 3) uniform sampler3D cg_aniso_ny;
layout(binding = CG_CONE_ANISO_BINDING + 4) uniform sampler3D cg_aniso_pz;
layout(binding = CG_CONE_ANISO_BINDING + 5) uniform sampler3D cg_aniso_nz;
#endif

// One filtered sample of the volume at level `lod` for a cone travelling along unit `d`.
// Anisotropic: the three directional chains facing d, weighted by d's squared components
// (they sum to 1); below level 1 blended with the isotropic level 0.
vec4
cg_cone_sample(sampler3D volume, vec3 uvw, float lod, vec3 d)
{
#ifdef CG_CONE_ANISOTROPIC
    vec4 s = vec4(0.0);
    if (lod > 0.0) {
        float k = max(lod - 1.0, 0.0);
        vec3 w = d * d;
        s = w.x * (d.x >= 0.0 ? textureLod(cg_aniso_px, uvw, k) : textureLod(cg_aniso_nx, uvw, k)) +
            w.y * (d.y >= 0.0 ? textureLod(cg_aniso_py, uvw, k) : textureLod(cg_aniso_ny, uvw, k)) +
            w.z * (d.z >= 0.0 ? textureLod(cg_aniso_pz, uvw, k) : textureLod(cg_aniso_nz, uvw, k));
    }
    if (lod < 1.0)
        s = mix(textureLod(volume, uvw, 0.0), s, lod);
    return s;
#else
    return textureLod(volume, uvw, lod);
#endif
}

// Returns the gathered radiance (rgb, already scaled to radiance) and the cone's opacity (a).
vec4
cg_cone_trace(sampler3D volume, CgVolume v, CgCone c)
{
    vec4 acc = vec4(0.0);
    float extent = cg_volume_extent(v);
    float top = v.levels - 1.0;
    float t = c.t_start;
    // The loop bound is a safety net against a zero step; steps grow with t, so real
    // marches end far earlier (about log(t_max / t_start) / log(1 + 2 step tan) steps).
    for (int i = 0; i < 4096 && t < c.t_max && acc.a < CG_CONE_OPAQUE; i++) {
        float diameter = cg_cone_diameter(c, v, t);
        vec3 p = c.origin + c.direction * t;
        vec3 uvw = cg_volume_uvw(v, p);
        float reach = 0.5 * diameter / extent;
        if (any(lessThan(uvw, vec3(-reach))) || any(greaterThan(uvw, vec3(1.0 + reach))))
            break;  // the whole footprint is outside the volume: nothing more to gather
        // Eq. 8 picks the level whose voxel is as wide as the footprint; trilinear filtering
        // then spreads the sample over two such voxels, so a bias of -1 keeps the sample's
        // support within the footprint (and off the surface the cone starts from); the
        // gather's default, -2, measured closer to the path tracer (docs/vct.md).
        float lod = clamp(cg_cone_lod(v, diameter) + c.lod_bias, 0.0, top);
        vec4 s = cg_cone_sample(volume, uvw, lod, c.direction);
        cg_cone_composite(acc, s);
        t += c.step_factor * diameter;
    }
    acc.rgb *= v.radiance_scale;
    return acc;
}

// Where the cones of a surface point start and how far they go (VCT paper 3.2.1): start_offset
// voxels along the normal, off the surface's own voxels (VCT self-illumination), for at most
// max_distance, or the volume's diagonal when that is 0.
vec3
cg_cone_origin(CgVolume v, vec3 position, vec3 n, float start_offset)
{
    return position + n * (start_offset * v.voxel_size);
}

float
cg_cone_reach(CgVolume v, float max_distance)
{
    return max_distance > 0.0 ? max_distance : cg_volume_extent(v) * sqrt(3.0);
}

#define CG_CONE_SET_MAX 16

// The diffuse gather of one surface point (VCT paper 3.2.1; hybrid eq. 3-4): cones[k] = (tangent-
// space direction, weight W_k), frame = the point's tangent frame. Returns sum_k W_k L_k (rgb)
// and the ambient visibility sum_k W_k (1 - a_k) (a). cone_gather and hybrid_gather (without a
// 2D lightmap) both call this, so that they agree bit for bit.
vec4
cg_cone_gather_diffuse(sampler3D volume, CgVolume v, vec3 origin, mat3 frame, vec4 cones[CG_CONE_SET_MAX],
                       float tan_half[CG_CONE_SET_MAX], int count, float t_max, float step, float lod_bias)
{
    vec4 diffuse = vec4(0.0);
    for (int k = 0; k < count; k++) {
        CgCone cone = CgCone(origin, normalize(frame * cones[k].xyz), tan_half[k], v.voxel_size, t_max,
                             step, lod_bias);
        vec4 r = cg_cone_trace(volume, v, cone);
        diffuse.rgb += cones[k].w * r.rgb;
        diffuse.a += cones[k].w * (1.0 - r.a);
    }
    return diffuse;
}

// Orthonormal tangent frame for a unit normal, NaN-free for every normal including the
// axes (Duff et al. 2017); the same construction as cg_cone_frame() in core/src/cone.c.
mat3
cg_tangent_frame(vec3 n)
{
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float b = n.x * n.y * a;
    vec3 t = vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    vec3 bt = vec3(b, s + n.y * n.y * a, -n.y);
    return mat3(t, bt, n);
}

#endif
