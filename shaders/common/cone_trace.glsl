// common/cone_trace.glsl: one cone marched front to back through a mipped 3D lightmap.
//
// Provides: CgCone, CgMarch, cg_cone_set_block, cg_cone_march(), cg_cone_count(), cg_cone_direction(),
//           cg_cone_tan_half(), cg_cone_accumulate(), cg_cone_trace(), cg_cone_lod(), cg_cone_origin(),
//           cg_cone_reach(), CgConeSample, cg_cone_composite(), cg_cone_composite_span(), cg_cone_step(),
//           cg_cone_trace_surface(), cg_cone_gather_diffuse(), cg_tangent_frame(); with CG_CONE_SURFACE
//           also cg_cone_sample_surface_from(), _as(), cg_cone_surface_level(), _gap(), _cover(), _sample_at(),
//           _recentre(), _read_position().
//
// VCT paper 3.2 (after Crassin et al. 2011): the cone's footprint at distance t has the
// diameter d = 2 t tan(half angle); the sample is read from the mip level whose voxels
// are about d wide (hybrid eq. 8: Lv = log2(d / voxel size); cg_cone_level: one finer) and
// composited front to back; the paper's rule is c += (1 - a) * alpha_s * c_s,
// a += (1 - a) * alpha_s (cg_cone_composite), the march adds coverage over the path length a
// sample stands for instead (cg_cone_composite_span, exact for walls). The volume stores
// premultiplied colour (alpha_s * c_s). The march stops when a reaches CG_CONE_OPAQUE, past
// t_max, or once the footprint has left the volume (VCT paper 3.2.1). hybrid_gather's 3D steps (its Case 1) are cg_cone_step(),
// the very step of this march, and its gather is cg_cone_accumulate(), as cg_cone_gather_diffuse().
//
// Three volume models, chosen by the defines of the program (passes/sdk/cone.c):
//   none           voxelize's radiance model through mip3d: one isotropic sample per step.
//   CG_CONE_ANISOTROPIC  the same with mip3d's six directional chains (Crassin et al. 2011).
//   CG_CONE_SURFACE      voxel_light's surface voxels (docs/vct.md): one-sided voxels with a mean
//                  normal and plane, per-axis coverage; the lit side by which side of the voxel's
//                  plane the cone's origin lies on, the cone's own plane left out, one level per
//                  surface crossing, read centred on the surface's plane (CgConeState,
//                  cg_cone_surface_recentre). Three reads per occupied sample (four at a crossing's
//                  first), one per empty one.
// Every volume read of a march is counted (CG_READ, common/reads.glsl: the pass's texture reads).
#ifndef CG_COMMON_CONE_TRACE_GLSL
#define CG_COMMON_CONE_TRACE_GLSL

#include "common/blocks.h"
#include "common/volume.glsl"
#include "common/sky.glsl"
#include "common/reads.glsl"

#define CG_CONE_OPAQUE 0.999

// The gather's diffuse cone set and march parameters (cgp_cone_upload, passes/sdk/cone.c).
CG_UNIFORM_BLOCK(CgConeSet, cg_cone_set_block, CG_BINDING_CONES, CG_CONE_SET_BLOCK);

struct CgMarch {
    float step;         // sample spacing as a fraction of the footprint diameter
    float start_offset; // xels the cone origins are moved along the normal
    float max_distance; // world; <= 0: the maps' diagonal
    float lod_bias;     // added to the level of eq. 8
};

CgMarch
cg_cone_march()
{
    vec4 m = cg_cone_set_block.march;
    return CgMarch(m.x, m.y, m.z, m.w);
}

int
cg_cone_count()
{
    return cg_cone_set_block.count.x;
}

// The cones of the set a gather's loops take: k = cg_cone_first, + cg_cone_stride, ... below
// cg_cone_count(). The whole set (0, 1) but for an interleaved block, which takes a quarter of it
// (common/upsample.glsl's cg_upsample_interleave).
int cg_cone_first = 0, cg_cone_stride = 1;

// Cone k of the set for a point with tangent frame `frame`: its world direction and tan of its half angle.
vec3
cg_cone_direction(mat3 frame, int k)
{
    return normalize(frame * cg_cone_set_block.cones[k].xyz);
}

float
cg_cone_tan_half(int k)
{
    return cg_cone_set_block.apertures[k].x;
}

// Adds what cone k gathered, `traced` = (radiance, coverage), to the diffuse sum of a point:
// rgb += W_k L_k, a += W_k (1 - a_k) (hybrid eq. 3-4; the ambient visibility of VCT paper 3.2.3).
void
cg_cone_accumulate(inout vec4 diffuse, int k, vec4 traced)
{
    float w = cg_cone_set_block.cones[k].w;
    diffuse.rgb += w * traced.rgb;
    diffuse.a += w * (1.0 - traced.a);
}

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

// What a march carries from one step to the next (cg_cone_step). With CG_CONE_SURFACE: the level
// a surface crossing is held at, and the span of the previous step (the midpoint weights).
struct CgConeState {
    float held_lod;     // the level may not grow past this while the last sample read coverage
    float prev_span;    // the previous step's span; < 0 before the first step
    float gained;       // coverage added since the current surface crossing began
    vec3 shift;         // where the current crossing reads, off the axis (cg_cone_surface_recentre); 0 between
};

CgConeState
cg_cone_state()
{
    return CgConeState(1e30, -1.0, 0.0, vec3(0.0));
}

#ifdef CG_CONE_ANISOTROPIC
// Six directional chains of levels 1.. (mip3d with anisotropic = true): level k of cg_aniso_px
// is level k + 1 as seen by a cone travelling along +x, and so on (Crassin et al. 2011).
layout(binding = CG_UNIT_ANISO + 0) uniform sampler3D cg_aniso_px;
layout(binding = CG_UNIT_ANISO + 1) uniform sampler3D cg_aniso_nx;
layout(binding = CG_UNIT_ANISO + 2) uniform sampler3D cg_aniso_py;
layout(binding = CG_UNIT_ANISO + 3) uniform sampler3D cg_aniso_ny;
layout(binding = CG_UNIT_ANISO + 4) uniform sampler3D cg_aniso_pz;
layout(binding = CG_UNIT_ANISO + 5) uniform sampler3D cg_aniso_nz;
#endif

#ifdef CG_CONE_SURFACE
// voxel_light's surface voxels besides the radiance at CG_UNIT_VOLUME (passes/voxel_light):
//   radiance (A) = (w L_lit, w)          w = alpha_x + alpha_y + alpha_z
//   sides (B)    = (w beta, w D, 0, alpha_y)
//   normals (C)  = (w N, alpha_z)
// premultiplied by w, so that trilinear and mip averages of rgb over w are w-weighted means:
// L_lit the radiance of the lit side, beta the other side's luminance as a fraction of it, N the
// mean normal of the lit side (|N| <= 1: 1 where every facet faces one way), D its plane's constant,
// N . (x - m) = D voxel for the points x of the plane, m the volume's centre (in level-0 voxels: the
// interpolated N and D of a plane are its own at any point, whatever the sample's position among
// the cells), and alpha_i the coverage a path along axis i meets crossing them, per cell of path.
layout(binding = CG_UNIT_SIDES) uniform sampler3D cg_surface_sides;
layout(binding = CG_UNIT_NORMALS) uniform sampler3D cg_surface_normals;
// The radiance again, read within one mip level (cgp_sampler_volume_one_level): the emptiness test.
layout(binding = CG_UNIT_OCCUPANCY) uniform sampler3D cg_surface_occupancy;

// One sample of the surface voxels at level `lod` (cells `cell` wide) at world p, for a cone from
// `origin` travelling along unit d and leaving `surface` (as in cg_cone_step). Returns premultiplied
// (L sigma, sigma), sigma the coverage per cell of path.
//   Coverage: sigma = sum_i |d_i| alpha_i. A plane with normal n leaves a slab of voxels |n|_1 thick
//     along n; a path along d crosses it over |n|_1 / |n . d| voxels, meeting |d_i| |n_i| / |n|_1 per
//     voxel from axis i: 1 in all where the signs of d_i n_i agree, more (saturated by the
//     compositing) where they do not. A surface seen edge-on covers nothing, one across the path
//     covers the whole cell: no solid cubes.
//   Lit side: e = N . (origin - m) - D voxel is how far the origin lies in front of the mean
//     plane; the cone sees the lit side's radiance on the side of the plane the lit facets face, the
//     other side's (beta L_lit) behind it, blended over half a cell (the plane's uncertainty within
//     one): f = 1/2 + 1/2 clamp(e / (cell / 2), -1, 1), L = L_lit (f + (1 - f) beta). The sign of
//     N . d would ask which way the axis points instead, but a cone rising over a terrain still
//     sees the terrain's top through the lower part of its footprint.
//   The cone's own surface: facets coplanar with the surface the cone leaves have no projected area
//     as seen from it, so a cell whose mean plane is that surface's (normals within about 25
//     degrees, the origin at its own height above the cell's plane within half a cell) loses its
//     coverage in proportion to the match (m, times the coherence |N|). This replaces the level cap
//     of the other models, which narrows the cones near the horizon (docs/vct.md).
// `centre`: the volume's centre m.
// `profile` = (sigma / w, L / L_lit): what the sample's coverage and colour are per unit of the
// weight w and of the lit radiance, for cg_cone_sample_surface_as; 0 for an empty sample.
// `plane` = (N, N . (x - m)) of the sample's mean plane, in world units, for cg_cone_surface_recentre;
// 0 for an empty sample.
// cg_cone_sample_surface_from: the same once the first read, `a` of the radiance, is made.
vec4
cg_cone_sample_surface_from(vec4 a, vec3 uvw, float lod, float cell, float voxel, vec3 centre, vec3 d, vec3 origin,
                            vec4 surface, out vec2 profile, out vec4 plane)
{
    profile = vec2(0.0);
    plane = vec4(0.0);
    if (a.a <= 0.0)
        return vec4(0.0);   // empty: one read
    vec4 b = textureLod(cg_surface_sides, uvw, lod);
    vec4 c = textureLod(cg_surface_normals, uvw, lod);
    CG_READ(2);
    float w = a.a;
    vec3 alpha = vec3(max(w - b.a - c.a, 0.0), b.a, c.a);
    float cover = dot(abs(d), alpha);
    vec3 n = c.rgb / w;
    float coherence = length(n);
    float offset = b.g / w * voxel;
    float e = dot(n, origin - centre) - offset;
    float lit = 0.5 + 0.5 * clamp(e / (0.5 * cell), -1.0, 1.0);
    plane = vec4(n, offset);
    if (surface.w >= 0.0 && coherence > 0.0) {
        float facing = abs(dot(n, surface.xyz)) / coherence;
        float height = abs(abs(e) / coherence - surface.w);
        float m = smoothstep(0.85, 0.95, facing) * (1.0 - smoothstep(0.5, 1.0, height / cell)) * coherence;
        cover *= 1.0 - m;
    }
    profile = vec2(cover / w, mix(b.r / w, 1.0, lit));
    return vec4(a.rgb * (profile.y * profile.x), cover);
}

// A sample near one of cg_cone_sample_surface_from that reads the same surface: its weight and lit
// radiance read at uvw, its coverage and colour per unit of them taken from that sample's
// `profile`. One read instead of three: for the tail of a crossing's trilinear tent (cg_cone_step),
// whose texels are those of the surface the full sample read (one plane: the same normal, plane and
// per-axis coverage, so the same ratios), only nearer to or farther from the sample.
vec4
cg_cone_sample_surface_as(sampler3D radiance, vec3 uvw, float lod, vec2 profile)
{
    vec4 a = textureLod(radiance, uvw, lod);
    CG_READ(1);
    return vec4(a.rgb * (profile.y * profile.x), a.a * profile.x);
}

// Where a surface crossing reads the voxels, off the cone's axis. A mip level keeps a surface's
// coverage at the centre of the texel that holds it, so at a level with cells c wide an axis-aligned
// surface lies anywhere up to c/2 from where that level's trilinear tent across it peaks. A cone
// crossing it at theta from its normal meets the tent up to c / (2 cos theta) early or late along its
// path, which puts the surface c tan(theta) / 2 nearer to or farther from the cone's origin across:
// on builtin:plates, an outer cone whose tent lies on the near side fills up on a plate whose far edge
// already lets half of that cone pass (docs/vct.md, "Alignment"). The voxels hold the surface's plane
// (`plane` of cg_cone_sample_surface_from), so the crossing reads the volume moved along the plane's
// dominant axis k by the offset of that texel's centre from the plane: its tent then peaks on the plane.
// The move is one for all samples of a crossing (CgConeState.shift, set at its first sample), so the
// crossing stays a partition of unity (the white furnace). The grid is that of the nearer whole level
// (a fractional level mixes two). Only for a plane along one layer of texels: its height changes by
// tan(tilt) c across a cell, so the move fades from whole at |n_k| = 0.981 (a fifth of a cell) to none
// at 0.894 (half a cell: its offsets within the texels are spread and average out, as on the turned
// plates), and only where one plane fills the cell: none below a coherence |N| of 0.8 (the two faces of
// a corner give 0.71).
vec3
cg_cone_surface_recentre(CgVolume v, vec3 x, vec3 centre, float lod, vec4 plane)
{
    float coherence = length(plane.xyz);
    if (coherence <= 0.0)
        return vec3(0.0);
    vec3 n = plane.xyz / coherence;
    vec3 a = abs(n);
    int k = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    // The plane's coordinate along k where it passes x, from n . (q - m) = D.
    vec3 r = x - centre;
    float q = centre[k] + (plane.w / coherence - (dot(n, r) - n[k] * r[k])) / n[k];
    float cell = v.voxel_size * exp2(floor(lod + 0.5));
    float u = (q - v.origin[k]) / cell;
    vec3 shift = vec3(0.0);
    shift[k] = (floor(u) + 0.5 - u) * cell * smoothstep(0.894, 0.981, a[k]) * smoothstep(0.8, 0.95, coherence);
    return shift;
}

// Where a step on the axis at p reads the surface voxels: p, moved by the current crossing's shift.
vec3
cg_cone_read_position(CgConeState state, vec3 p)
{
    return p + state.shift;
}
#endif

// One filtered sample of the volume at level `lod` for a cone travelling along unit `d`.
// Anisotropic: the three directional chains facing d, weighted by |d_i| (not normalised;
// below level 1 blended with the isotropic level 0). Chain i holds the covered fraction of a
// cell's face across axis i; a path of length l along d crosses l |d_i| of the cell's depth
// along i, so sum_i |d_i| alpha_i is the coverage per cell of path: a wall across axis i
// (alpha_i = 1) is crossed over cell / |d_i| of path and adds exactly 1, at any angle, while a
// surface seen edge-on (alpha = its share of the cell) adds its share. The returned alpha can
// exceed 1 (up to sqrt 3): a coverage rate for cg_cone_composite_span, not an opacity.
vec4
cg_cone_sample(sampler3D volume, vec3 uvw, float lod, vec3 d)
{
#ifdef CG_CONE_ANISOTROPIC
    vec4 s = vec4(0.0);
    if (lod > 0.0) {
        float k = max(lod - 1.0, 0.0);
        CG_READ(3);
        vec3 w = abs(d);
        s = w.x * (d.x >= 0.0 ? textureLod(cg_aniso_px, uvw, k) : textureLod(cg_aniso_nx, uvw, k)) +
            w.y * (d.y >= 0.0 ? textureLod(cg_aniso_py, uvw, k) : textureLod(cg_aniso_ny, uvw, k)) +
            w.z * (d.z >= 0.0 ? textureLod(cg_aniso_pz, uvw, k) : textureLod(cg_aniso_nz, uvw, k));
    }
    if (lod < 1.0) {
        CG_READ(1);
        s = mix(textureLod(volume, uvw, 0.0), s, lod);
    }
    return s;
#else
    CG_READ(1);
    return textureLod(volume, uvw, lod);
#endif
}

// The matched level: the mip level whose filtered sample covers the cone's footprint.
// Eq. 8 (hybrid paper; VCT paper 3.2) picks the level whose voxel is as wide as the
// footprint diameter d, but a sample there is wider than d: the level is a 2x2x2 box pyramid
// (per-axis variance about s^2/12 for voxels s wide) and the trilinear tent that reads it
// adds s^2/6 on average over sample positions, s^2/4 in all, while the cone's disc of
// diameter d has the per-axis variance d^2/16. Equal for s = d/2: one level below eq. 8.
float
cg_cone_level(CgVolume v, float diameter)
{
    return cg_cone_lod(v, diameter) - 1.0;
}

// One step of the march with a premultiplied sample s read at a level whose voxels are
// `cell` wide, standing for the path length `span` (world units) around the sample.
// The voxels hold surfaces: alpha is the solid fraction of a cell, so alpha * span / cell
// is the length of solid the step crosses, in cells, and the coverage adds up, not
// multiplies (one wall is one occluder, not independent layers). A trilinear tent sampled
// at any spacing up to one cell sums to the cell count (partition of unity), so a wall one
// cell thick at the sampled level gathers exactly coverage 1, whatever the step and the
// phase of the samples: no leak, and the result does not depend on the step (docs/vct.md).
// The colour is the sample's (s.rgb / alpha) weighted by the coverage it adds.
void
cg_cone_composite_span(inout vec4 acc, vec4 s, float span, float cell)
{
    float alpha = max(s.a, 0.0);
    if (alpha <= 0.0)
        return;
    float w = min(alpha * span / cell, 1.0 - acc.a);
    acc.rgb += s.rgb * (w / alpha);
    acc.a += w;
}

// Where one step of a cone samples the 3D lightmap (cg_cone_step).
struct CgConeSample {
    vec3 position;  // world position of the sample: on the axis at t (VCT), or the centre of
                    // the fitting cube's intersection with the volume (hybrid eq. 15)
    float diameter; // the footprint's diameter there, never below the finest xel
    float height;   // the sample's height above the surface the cone leaves (see `surface`)
};

#ifdef CG_CONE_SURFACE
// cg_cone_step's level with surface voxels at `at`: the matched level plus the bias, held while a
// crossing lasts; `cell` its voxel size, `span` the step before the sample says whether it is occupied.
float
cg_cone_surface_level(CgVolume v, CgCone c, CgConeSample at, CgConeState state, out float cell, out float span)
{
    float lod = min(clamp(cg_cone_level(v, at.diameter) + c.lod_bias, 0.0, v.levels - 1.0), state.held_lod);
    cell = v.voxel_size * exp2(lod);
    span = min(c.step_factor * min(at.diameter, 2.0 * cell), cell);
    return lod;
}

// A sample that covers nothing: between surfaces, the next coverage starts a new crossing.
float
cg_cone_surface_gap(inout CgConeState state, float span)
{
    state.gained = 0.0;
    state.prev_span = span;
    state.held_lod = 1e30;
    state.shift = vec3(0.0);
    return span;
}

// A sample s (premultiplied, coverage > 0) at `at`, read at level `lod` with the surface `profile`
// (cg_cone_sample_surface_from): the crossing's half-cell step, the midpoint weight, and on entering a
// surface the reads behind it (see cg_cone_step). Returns the span.
float
cg_cone_surface_cover(sampler3D volume, CgVolume v, CgCone c, CgConeSample at, float lod, float cell, float span,
                      vec4 s, vec2 profile, float scale, inout CgConeState state, inout vec4 acc)
{
    // Half a cell: the trilinear tent sampled at half its cell sums to 1 across a plane at any
    // phase, so the white furnace (closed walls, where the coverage has no margin) is exact to
    // 0.01%. 3/4 of a cell takes a third fewer samples but not at every phase: the furnace's mean
    // 0.07% short and, with a height field, a worst pixel 0.63% off, over the hybrid's 0.5%
    // bound; a whole cell 0.6% and 2% (docs/vct.md, Cost).
    span = min(span, 0.5 * cell);
    float weight = state.prev_span < 0.0 ? span : 0.5 * (state.prev_span + span);
    if (state.gained <= 0.0 && state.prev_span > 0.0) {
        // Entering a surface: the level has grown since the previous sample, which read nothing
        // at its finer level, but the tent of this level may begin up to a cell before this
        // sample. Read the path behind again at this level, up to two previous spans back, so
        // that the crossing is integrated at one level from where its tent begins. The tent's
        // tail is the surface this sample reads, so one read each (cg_cone_sample_surface_as):
        // with three each (six reads in a branch, which llvmpipe runs for every lane of a lockstep
        // group, taken or not) the gather took 1.8x its time (docs/vct.md, Cost).
        float h = state.prev_span;
        vec3 read = cg_cone_read_position(state, at.position);
        vec4 back0 = cg_cone_sample_surface_as(volume, cg_volume_uvw(v, read - c.direction * h), lod, profile);
        vec4 back1 = vec4(0.0);
        if (back0.a > 0.0)  // the second only where the first is this surface's too
            back1 = cg_cone_sample_surface_as(volume, cg_volume_uvw(v, read - c.direction * (2.0 * h)), lod, profile);
        float before = acc.a;
        cg_cone_composite_span(acc, vec4(back1.rgb * scale, back1.a), h, cell);
        cg_cone_composite_span(acc, vec4(back0.rgb * scale, back0.a), h, cell);
        state.gained += acc.a - before;
    }
    state.prev_span = span;
    state.held_lod = lod;
    float before = acc.a;
    cg_cone_composite_span(acc, vec4(s.rgb * scale, s.a), weight, cell);
    state.gained += acc.a - before;
    return span;
}
#endif

#ifdef CG_CONE_SURFACE
// The sample of a step whose read position (cg_cone_read_position) is occupied, `a` the radiance read
// there at `lod`: the sides and normals read there too and, at a crossing's first sample, the
// crossing's shift (cg_cone_surface_recentre) and the radiance read again where it moves the reads.
// Returns the premultiplied sample and its `profile`, as cg_cone_sample_surface_from.
vec4
cg_cone_surface_sample_at(sampler3D volume, CgVolume v, CgCone c, vec4 surface, CgConeSample at, float lod, float cell,
                          vec3 centre, vec4 a, inout CgConeState state, out vec2 profile)
{
    vec4 plane;
    vec4 s = cg_cone_sample_surface_from(a, cg_volume_uvw(v, cg_cone_read_position(state, at.position)), lod, cell,
                                         v.voxel_size, centre, c.direction, c.origin, surface, profile, plane);
    if (s.a > 0.0 && state.held_lod > 1e29) {
        state.shift = cg_cone_surface_recentre(v, at.position, centre, lod, plane);
        s = cg_cone_sample_surface_as(volume, cg_volume_uvw(v, cg_cone_read_position(state, at.position)), lod, profile);
    }
    return s;
}
#endif

// One step of a cone through the 3D lightmap, the step both tracers take (cone_gather's march
// below and hybrid_gather's Case 1), at `at.position` for a footprint `at.diameter` wide: the matched
// level of the footprint plus the lod bias, the sample (the directional chains with
// CG_CONE_ANISOTROPIC, the surface voxels with CG_CONE_SURFACE), composited by
// cg_cone_composite_span over its span. `surface` = (unit normal of the surface the cone leaves,
// height of c.origin above it), or w < 0 for a cone with no surface behind it. The sample's colour
// is multiplied by `scale` (1 for a march that scales its sum once, v.radiance_scale for one that
// mixes in other radiance). `state` carries what one step tells the next (cg_cone_state() before the
// first). Returns the span: the path length the step stands for, by which the march must advance.
//
// The radiance models (two-sided voxels): a sample reads the voxels within one voxel of its own
// (the trilinear support), and the surface's voxels at a level with voxels s wide have centres up
// to s / 2 off its plane, along the normal n at most 1.5 s |n|_1 away: below that height the
// sample would read the cone's own surface (self-occlusion and self-illumination: black
// ceilings, bright lit floors). So the level is capped at the coarsest whole level whose
// support stays above the plane, and the span at one voxel of that level (step 0.5), which
// keeps cg_cone_composite_span exact.
//
// The surface model (one-sided voxels that leave their own plane out, cg_cone_sample_surface_from): no
// cap. Instead each surface crossing is integrated at one level: while the previous sample read
// coverage the level may not grow (a crossing whose level grows half-way meets two different
// profiles of the wall, and the coverage that has no margin here, exactly 1 across a plane, falls
// short: up to 30% at oblique angles), the steps inside are half a cell, and each sample is weighted
// by the mean of the spans before and after it (the midpoint rule on uneven steps), so that the
// trilinear tent, a partition of unity, sums to 1 across the crossing (docs/vct.md).
float
cg_cone_step(sampler3D volume, CgVolume v, CgCone c, vec4 surface, CgConeSample at, float scale,
             inout CgConeState state, inout vec4 acc)
{
#ifdef CG_CONE_SURFACE
    float cell, span;
    float lod = cg_cone_surface_level(v, c, at, state, cell, span);
    vec3 centre = v.origin + 0.5 * cg_volume_extent(v);
    vec2 profile;
    vec4 a = textureLod(volume, cg_volume_uvw(v, cg_cone_read_position(state, at.position)), lod);
    CG_READ(1);
    vec4 s = cg_cone_surface_sample_at(volume, v, c, surface, at, lod, cell, centre, a, state, profile);
    return s.a > 0.0 ? cg_cone_surface_cover(volume, v, c, at, lod, cell, span, s, profile, scale, state, acc)
                     : cg_cone_surface_gap(state, span);
#else
    float lod = cg_cone_level(v, at.diameter) + c.lod_bias;
    if (surface.w >= 0.0) {
        // A fractional level blends in the next coarser level, whose support is twice as
        // deep: that one must clear the plane, hence the 1 below the bound.
        // The height in voxels is guarded, not the height in metres: a sample on or below the
        // plane (height <= 0) gets level 0 through the clamp below, at any scene size.
        float support = 1.5 * (abs(surface.x) + abs(surface.y) + abs(surface.z));
        lod = min(lod, log2(max(at.height / (support * v.voxel_size), 1e-30)) - 1.0);
    }
    lod = clamp(lod, 0.0, v.levels - 1.0);
    float cell = v.voxel_size * exp2(lod);
    float span = c.step_factor * min(at.diameter, 2.0 * cell);
    vec4 s = cg_cone_sample(volume, cg_volume_uvw(v, at.position), lod, c.direction);
    cg_cone_composite_span(acc, vec4(s.rgb * scale, s.a), span, cell);
    return span;
#endif
}

// The VCT march of one cone from a surface (`surface` as in cg_cone_step): steps along the
// axis until the cone is opaque, past c.t_max, or its whole footprint has left the volume.
// Returns the gathered radiance (rgb, already scaled to radiance) and the cone's coverage (a).
vec4
cg_cone_trace_surface(sampler3D volume, CgVolume v, CgCone c, vec4 surface)
{
    vec4 acc = vec4(0.0);
    vec3 extent = cg_volume_extent(v);
    float t = c.t_start;
    float rise = dot(c.direction, surface.xyz);
    CgConeState state = cg_cone_state();
#ifdef CG_CONE_SURFACE
    // cg_cone_step's march (the same samples, levels, spans and weights, so the same result),
    // arranged for lockstep groups: llvmpipe runs every texture read of a loop's body for every
    // lane of a group, also in a branch that no lane takes (gather time on the open world grows
    // by a third with two reads in a branch never taken: docs/vct.md, Cost), but leaves a loop once
    // no lane is left in it. So the inner loop holds one read, the radiance's, and crosses empty
    // space, most of a march (VCT paper 3.2: the cone is marched front to back; nothing here
    // changes what it gathers); the reads of an occupied sample (the radiance at its own level,
    // the sides, the normals) and those behind a surface's entry (cg_cone_surface_cover) are made
    // once the inner loop stops at one.
    vec3 centre = v.origin + 0.5 * extent;
    bool done = false;
    for (int i = 0; i < 4096 && !done; i++) {
        CgConeSample at;
        vec3 uvw;
        vec4 a;
        float lod, cell, span;
        for (; i < 4096; i++) {
            done = !(t < c.t_max && acc.a < CG_CONE_OPAQUE);
            if (done)
                break;
            at = CgConeSample(c.origin + c.direction * t, cg_cone_diameter(c, v, t), surface.w + t * rise);
            uvw = cg_volume_uvw(v, at.position);
            vec3 reach = 0.5 * at.diameter / extent;
            done = any(lessThan(uvw, vec3(-reach))) || any(greaterThan(uvw, vec3(1.0 + reach)));
            if (done)
                break;  // the whole footprint is outside the volume: nothing more to gather
            lod = cg_cone_surface_level(v, c, at, state, cell, span);
            uvw = cg_volume_uvw(v, cg_cone_read_position(state, at.position));
            // Empty at the fractional level `lod` (its two levels mixed) is empty at ceil(lod): the
            // 2x2x2 texels that a read there touches hold, as their children, every texel of the
            // finer level's read (dyadic, aligned grids), and a mip texel has coverage wherever a
            // child has (voxel_light's mip rule). So the test reads one level, 8 texels, not 16.
            CG_READ(1);
            if (textureLod(cg_surface_occupancy, uvw, ceil(lod)).a > 0.0)
                break;
            t += cg_cone_surface_gap(state, span);
        }
        if (done)
            break;
        vec2 profile;
        a = textureLod(volume, uvw, lod);
        CG_READ(1);
        vec4 s = cg_cone_surface_sample_at(volume, v, c, surface, at, lod, cell, centre, a, state, profile);
        t += s.a > 0.0 ? cg_cone_surface_cover(volume, v, c, at, lod, cell, span, s, profile, 1.0, state, acc)
                       : cg_cone_surface_gap(state, span);
    }
#else
    // The loop bound is a safety net against a zero step; steps grow with t, so real
    // marches end far earlier (about log(t_max / t_start) / log(1 + 2 step tan) steps).
    for (int i = 0; i < 4096 && t < c.t_max && acc.a < CG_CONE_OPAQUE; i++) {
        CgConeSample at = CgConeSample(c.origin + c.direction * t, cg_cone_diameter(c, v, t), surface.w + t * rise);
        vec3 uvw = cg_volume_uvw(v, at.position);
        vec3 reach = 0.5 * at.diameter / extent;
        if (any(lessThan(uvw, vec3(-reach))) || any(greaterThan(uvw, vec3(1.0 + reach))))
            break;  // the whole footprint is outside the volume: nothing more to gather
        t += cg_cone_step(volume, v, c, surface, at, 1.0, state, acc);
    }
#endif
    acc.rgb *= v.radiance_scale;
    return acc;
}

// A cone with no surface behind it (see cg_cone_trace_surface).
vec4
cg_cone_trace(sampler3D volume, CgVolume v, CgCone c)
{
    return cg_cone_trace_surface(volume, v, c, vec4(0.0, 0.0, 0.0, -1.0));
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
    return max_distance > 0.0 ? max_distance : length(cg_volume_extent(v));
}

// The diffuse gather of one surface point (VCT paper 3.2.1; hybrid eq. 3-4) with the cone set
// of cg_cone_set_block, frame = the point's tangent frame. Returns sum_k W_k L_k (rgb; L_k with the
// sky seen through what cone k left open, cg_sky_gather) and the
// ambient visibility sum_k W_k (1 - a_k) (a). cone_gather and hybrid_gather (without a 2D
// lightmap) both call this, so that they agree bit for bit. `height`: the origin's height above
// the surface (start_offset voxels), which cg_cone_trace_surface keeps every sample off.
vec4
cg_cone_gather_diffuse(sampler3D volume, CgVolume v, vec3 origin, mat3 frame, float t_max, float height)
{
    CgMarch march = cg_cone_march();
    vec4 surface = vec4(frame[2], height);
    vec4 diffuse = vec4(0.0);
    for (int k = cg_cone_first; k < cg_cone_count(); k += cg_cone_stride) {
        CgCone cone = CgCone(origin, cg_cone_direction(frame, k), cg_cone_tan_half(k), v.voxel_size, t_max,
                             march.step, march.lod_bias);
        // What the cone left open sees the sky (common/sky.glsl).
        cg_cone_accumulate(diffuse, k, cg_sky_gather(cg_cone_trace_surface(volume, v, cone, surface), cone.direction,
                                                     cone.tan_half));
    }
    return diffuse;
}

// Orthonormal tangent frame for a unit normal, NaN-free for every normal including the
// axes (Duff et al. 2017); the same construction as cgp_cone_frame() in passes/sdk/cone.c.
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
