// hybrid_gather: indirect light of every G-buffer pixel by hybrid cone tracing (hybrid cone
// tracing paper, section VI) through a mipped 3D lightmap of the complex meshes and a mipped 2D
// lightmap of the height-field meshes with its min/max height tables (HSAT).
//
// Diffuse cones and weights as cone_gather (eq. 3-4: the weights integrate the cosine lobe to 1,
// passes/sdk/cone.c); the output is sum_k W_k L_k (rgb) and the ambient visibility (a), which
// composite multiplies by the albedo.
//
// Without a 2D lightmap (HAS_2D undefined) the gather is cg_cone_gather_diffuse(), the VCT
// gather, so a scene without terrain gathers exactly what cone_gather does. With one, two
// methods (the pass's `method`, a define):
//
// METHOD_PAPER, the steps of section VI in the paper's order (trace_paper): per step an
//   axis-aligned fitting cube (eq. 10-11); the cube against the 3D lightmap's box (eq. 12), with
//   the latch of VI.C (once the cube lies inside the box, Case 1 only); the terrain's height range
//   under the cube by HSAT (eq. 13-14): skipped above the highest terrain, abandoned below the
//   lowest (VI.A); the 3D sample at the intersection's centre (eq. 15) unless its bounding ball
//   is below a threshold (VI.B), composited as Case 1 (VI.C); the 2D sample by the morphology
//   search of VI.B (projection segmentation of Fig. 5, sub-meshes visited by a DDA along the
//   cone's projected direction with backface culling and dynamic distance, their radiance
//   weighted by the normal and the cone direction); the terrain's occlusion by eq. 16 or eq. 17
//   (Case 2), after the 3D sample in a mixed step, whose 3D opacity raises the heights inside
//   the 3D lightmap's projection (the mix case); the next cube where this one ends.
//
// METHOD_HORIZON, ours (trace_horizon): the 3D lightmap is marched by cone_gather's own step
//   (cg_cone_step along the axis: the VCT march, so that a region without terrain gathers what
//   cone_gather gathers), and the terrain by its horizon: a height field blocks every direction
//   below the highest elevation at which it is seen from the surface point, so the part of the
//   cone's cell (cosine-weighted) below the running horizon is covered by the terrain where the
//   horizon rose, with its radiance. Empty spans, where no terrain can raise the horizon, are
//   skipped hierarchically with the min-max pyramid (HSAT mode pyramid), as maximum mipmaps do;
//   a point on the height field itself has no voxels of its own, so its 3D steps need no cap
//   near the surface (cg_cone_step's `surface` left out) and take the full steps.
//
// Decoupled resolution (CG_GATHER_DOWNSAMPLE, common/upsample.glsl, whose entry points these are
// with CG_GATHER_LOWRES or CG_GATHER_DEFERRED), as cone_gather's: the diffuse cones at one pixel of
// each block (the blocks that trace listed, then traced packed), every pixel's diffuse light
// upsampled from them or, where no block agrees, traced in a dispatch of those pixels alone; the
// material cones at every pixel (main below).
#version 450 core
#include "common/cone_trace.glsl"
#include "common/gather.glsl"
#ifdef HAS_2D
#include "common/heightmap.glsl"
#include "common/hsat.glsl"
#include "common/fitting_cube.glsl"
#endif
#ifdef CG_GATHER_DOWNSAMPLE
#include "common/upsample.glsl"
#endif

layout(binding = CG_UNIT_LIGHTMAP2D) uniform sampler2D u_lightmap;
layout(binding = CG_UNIT_HSAT) uniform usampler2D u_hsat;
#ifdef SPECULAR
layout(binding = 1, rgba32f) writeonly uniform image2D u_reflection;
#endif
#ifdef REFRACTION
layout(binding = 4, rgba32f) writeonly uniform image2D u_refraction;
#endif

// The cone set and march: cg_cone_set_block (common/cone_trace.glsl); the hybrid's own:
CG_UNIFORM_BLOCK(CgHybridGather, cg_hybrid_gather_block, CG_BINDING_GATHER, CG_HYBRID_GATHER_BLOCK);

bool
has_3d()
{
    return cg_hybrid_gather_block.maps.x != 0;
}

#define OCCLUSION_EQ16 0
#define OCCLUSION_EQ17 1
#define PI 3.14159265358979
#define MAX_SLOPE 31.8205159537739    // tan(0.49 pi): a horizon's slope, finite

#ifdef HAS_2D
// The 3D lightmap as the gather uses it: at most `levels3d` levels (0: all).
CgVolume
hybrid_volume()
{
    CgVolume v = cg_volume();
    if (cg_hybrid_gather_block.levels.x > 0)
        v.levels = min(v.levels, float(cg_hybrid_gather_block.levels.x));
    return v;
}

// The level offsets of the 3D step and of the 2D lightmap: cg_cone_step reads the matched level,
// one below eq. 8 (common/cone_trace.glsl); `level = eq8` asks for eq. 8 itself in both maps.
float
bias_3d()
{
    return cg_cone_march().lod_bias + (cg_hybrid_gather_block.levels.z != 0 ? 1.0 : 0.0);
}

// Eq. 8 for the 2D lightmap (xelworldsize = the texel), or one level finer (matched), plus the bias.
float
level_2d(CgHeightmap m, float d)
{
    float offset = cg_hybrid_gather_block.levels.z != 0 ? 0.0 : -1.0;
    return clamp(log2(d / cg_heightmap_xel(m)) + offset + cg_cone_march().lod_bias, 0.0, m.levels - 1.0);
}

// Eq. 12's 3D lightmap box: the complex meshes' bounds inside the volume.
void
box_3d(CgVolume v, out vec3 lo, out vec3 hi)
{
    lo = max(v.origin, cg_hybrid_gather_block.box3_lo.xyz);
    hi = min(v.origin + vec3(cg_volume_extent(v)), cg_hybrid_gather_block.box3_hi.xyz);
}

// Exit distance of the ray from the box, -1 when it misses (slab test).
float
ray_box_exit(vec3 o, vec3 d, vec3 lo, vec3 hi)
{
    vec3 inv = 1.0 / d;     // +-inf for a zero component: the slab is then all or nothing
    vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
    vec3 tmin = min(t0, t1), tmax = max(t0, t1);
    float enter = max(max(tmin.x, tmin.y), tmin.z), leave = min(min(tmax.x, tmax.y), tmax.z);
    return leave >= max(enter, 0.0) ? leave : -1.0;
}

// The 2D lightmap's box: its xz bounds, from its lowest to its highest height.
void
map_box(CgHeightmap m, out vec3 lo, out vec3 hi)
{
    lo = vec3(m.origin.x, m.y_min, m.origin.y);
    hi = vec3(m.origin.x + m.texel.x * m.resolution, m.y_max, m.origin.y + m.texel.y * m.resolution);
}

#ifdef METHOD_PAPER
// ------------------------------------------------------------------------------ the paper's steps

// What the morphology search found in one step (VI.B).
struct Search {
    vec3 radiance;      // the weighted radiance of the retained sub-meshes
    float volume;       // the terrain's volume inside the cube: occluded area x average height (eq. 16's h A)
    bool occludes;      // some sub-mesh rises into the cube
};

// Height and radiance of sub-mesh `cell` of level `level`; a cell outside the map has no terrain.
vec4
sub_mesh(ivec2 cell, int level, int n)
{
    if (any(lessThan(cell, ivec2(0))) || any(greaterThanEqual(cell, ivec2(n))))
        return vec4(0.0, 0.0, 0.0, -1e30);
    CG_READ(1);
    return texelFetch(u_lightmap, cell, level);
}

// VI.B, the morphology search over the cube's vertical projection F:
// 1. Fig. 5: F is cut by the edge lines of the 3D lightmap's projection P into at most 3 x 3
//    segments; a sub-mesh belongs to the inner segment F n P (the mix case: its height is raised
//    to the 3D sample's fill of the cube, y0 + a3 S, when `mix` is the paper's) or to an outer one.
// 2. The segments are subdivided into sub-meshes: the texels of level Lv2 - dda_refine (at most
//    8 per side: coarser where F is wider).
// 3. A DDA along the cone's projected direction w visits them front to back, line by line across
//    w. A sub-mesh below the cube's bottom is not sampled. Dynamic distance: on each line a
//    sub-mesh is retained only where it rises above the previous occluding height. Backface
//    culling: a sub-mesh whose normal (from the heights around it) faces away from the cone's
//    origin adds no radiance (it still occludes). Its radiance, the texel's (the centre point's),
//    is weighted by the normal and the cone direction, max(0, -n.v).
Search
morphology_search(CgHeightmap m, vec3 dir, CgFittingCube cube, float lod, vec3 p_lo, vec3 p_hi, float a3)
{
    Search s = Search(vec3(0.0), 0.0, false);
    vec3 c_lo = cube.centre - 0.5 * cube.side, c_hi = cube.centre + 0.5 * cube.side;
    int level = max(int(lod) - cg_hybrid_gather_block.paper.w, 0);
    ivec2 a, b;
    vec2 cs;
    for (;; level++) {
        cs = m.texel * float(1 << level);
        a = ivec2(floor((c_lo.xz - m.origin) / cs));
        b = ivec2(floor((c_hi.xz - m.origin) / cs));
        if (all(lessThanEqual(b - a, ivec2(7))) || level >= int(m.levels) - 1)
            break;
    }
    b = min(b, a + 7);
    int n = max(int(m.resolution) >> level, 1);
    vec2 w = dir.xz;
    // The DDA's axes: the major one along w's larger component, in w's direction.
    bool x_major = abs(w.x) >= abs(w.y);
    int major_sign = (x_major ? w.x : w.y) >= 0.0 ? 1 : -1, minor_sign = (x_major ? w.y : w.x) >= 0.0 ? 1 : -1;
    int major_count = x_major ? b.x - a.x + 1 : b.y - a.y + 1, minor_count = x_major ? b.y - a.y + 1 : b.x - a.x + 1;
    float h_occ[8];
    for (int k = 0; k < 8; k++)
        h_occ[k] = -1e30;
    bool mix_paper = cg_hybrid_gather_block.paper.z != 0, backface = cg_hybrid_gather_block.paper2.x != 0,
         weighting = cg_hybrid_gather_block.paper2.y != 0;
    float y0 = c_lo.y, y1 = c_hi.y;
    float weight_sum = 0.0;
    for (int i = 0; i < major_count; i++) {
        int mi = major_sign > 0 ? i : major_count - 1 - i;
        for (int j = 0; j < minor_count; j++) {
            int mj = minor_sign > 0 ? j : minor_count - 1 - j;
            ivec2 cell = a + (x_major ? ivec2(mi, mj) : ivec2(mj, mi));
            vec4 t = sub_mesh(cell, level, n);
            float h = t.a;
            vec2 centre = m.origin + (vec2(cell) + 0.5) * cs;
            vec2 lo = max(m.origin + vec2(cell) * cs, c_lo.xz), hi = min(m.origin + vec2(cell + 1) * cs, c_hi.xz);
            float area = max(hi.x - lo.x, 0.0) * max(hi.y - lo.y, 0.0);
            // Fig. 5's inner segment: where the 3D lightmap's projection holds the sub-mesh.
            bool inner = all(greaterThanEqual(centre, p_lo.xz)) && all(lessThanEqual(centre, p_hi.xz));
            if (mix_paper && inner && a3 > 0.0)
                h = max(h, y0 + a3 * (y1 - y0));
            if (h <= y0)
                continue;   // below the sample space
            s.occludes = true;
            s.volume += area * (min(h, y1) - y0);
            if (h <= h_occ[j])
                continue;   // dynamic distance: hidden behind the previous occluder of this line
            h_occ[j] = h;
            // The sub-mesh's normal from the heights around it (central differences at its level).
            float hx0 = sub_mesh(cell - ivec2(1, 0), level, n).a, hx1 = sub_mesh(cell + ivec2(1, 0), level, n).a;
            float hz0 = sub_mesh(cell - ivec2(0, 1), level, n).a, hz1 = sub_mesh(cell + ivec2(0, 1), level, n).a;
            hx0 = hx0 < -1e29 ? t.a : hx0, hx1 = hx1 < -1e29 ? t.a : hx1;
            hz0 = hz0 < -1e29 ? t.a : hz0, hz1 = hz1 < -1e29 ? t.a : hz1;
            vec3 normal = normalize(vec3(-(hx1 - hx0) / (2.0 * cs.x), 1.0, -(hz1 - hz0) / (2.0 * cs.y)));
            float facing = -dot(normal, dir);
            if (backface && facing <= 0.0)
                continue;
            float wi = weighting ? max(facing, 0.0) : 1.0;
            s.radiance += wi * t.rgb;
            weight_sum += wi;
        }
    }
    // The lightmap's pre-exposure (common/heightmap.glsl): stored rgb x radiance_scale = radiance.
    s.radiance = weight_sum > 0.0 ? m.radiance_scale * s.radiance / weight_sum : vec3(0.0);
    return s;
}

// One sample at the cube's centre instead of the search (dda = false).
Search
centre_sample(CgHeightmap m, CgFittingCube cube, float lod)
{
    CG_READ(1);
    vec4 t = textureLod(u_lightmap, cg_heightmap_uv(m, cube.centre.xz), lod);
    float y0 = cube.centre.y - 0.5 * cube.side;
    float column = clamp(t.a - y0, 0.0, cube.side);
    return Search(m.radiance_scale * t.rgb, cube.side * cube.side * column, t.a > y0);
}

// One cone by the paper's steps (see the top of the file); `origin` already offset along the
// normal (VI.B's self-influence).
vec4
trace_paper(sampler3D volume, vec3 origin, vec3 dir, float tan_half, float t_start, float t_max)
{
    CgVolume v = hybrid_volume();
    CgHeightmap m = cg_heightmap();
    CgMarch march = cg_cone_march();
    bool eq11 = cg_hybrid_gather_block.switches.x != 0, dda = cg_hybrid_gather_block.switches.z != 0,
         skip = cg_hybrid_gather_block.switches.w != 0;
    int occlusion = cg_hybrid_gather_block.switches.y;
    bool abandon = cg_hybrid_gather_block.paper.x != 0, latch = cg_hybrid_gather_block.paper.y != 0,
         advance_cube = cg_hybrid_gather_block.paper2.z != 0;
    float ball = cg_hybrid_gather_block.params.x * v.voxel_size;
    vec3 v_lo, v_hi;
    box_3d(v, v_lo, v_hi);
    vec3 m_lo, m_hi;
    map_box(m, m_lo, m_hi);
    float xel = cg_heightmap_xel(m);
    if (has_3d())
        xel = min(xel, v.voxel_size);
    float t_leave = ray_box_exit(origin, dir, m_lo, m_hi);
    if (has_3d())
        t_leave = max(t_leave, ray_box_exit(origin, dir, v_lo, v_hi));
    float half_angle = atan(tan_half);
    float l1 = abs(dir.x) + abs(dir.y) + abs(dir.z);
    CgCone cone = CgCone(origin, dir, tan_half, t_start, t_max, march.step, bias_3d());
    const vec4 no_surface = vec4(0.0, 0.0, 0.0, -1.0);  // the paper has no cap near the surface
    vec4 acc = vec4(0.0);
    CgConeState state = cg_cone_state();    // what one 3D step tells the next (cg_cone_step)
    float volume_prev = 0.0;
    bool latched = false;
    float t = t_start;
    for (int i = 0; i < 4096 && t < t_max && acc.a < CG_CONE_OPAQUE; i++) {
        // Eq. 8's diameter, never below the finest xel: log2 of zero is -inf.
        float d = max(2.0 * tan_half * t, xel);
        CgFittingCube cube = cg_fitting_cube(origin, dir, half_angle, t, d, eq11);
        vec3 c_lo = cube.centre - 0.5 * cube.side, c_hi = cube.centre + 0.5 * cube.side;
        // The next cube starts where this one ends along the axis (contiguous cubes), or a step
        // of `step` diameters.
        float t_next = advance_cube ? max(dot(cube.centre - origin, dir) + 0.5 * cube.side * l1, t + 1e-3 * d)
                                    : t + march.step * d;
        cone.step_factor = (t_next - t) / d;   // the 3D step's span: this step's length
        vec3 lo = max(c_lo, v_lo), hi = min(c_hi, v_hi);
        bool meets3 = has_3d() && all(lessThan(lo, hi));
        // Eq. 12's "3D lightmap contains fitting cube": from then on Case 1 only (VI.C), as long
        // as the cone stays in the 3D lightmap.
        if (latch && meets3 && all(greaterThanEqual(c_lo, v_lo)) && all(lessThanEqual(c_hi, v_hi)))
            latched = true;
        if (latched) {
            if (!meets3)
                break;
            vec3 centre = 0.5 * (lo + hi);
            cg_cone_step(volume, v, cone, no_surface, CgConeSample(centre, d, -1.0), v.radiance_scale, state, acc);
            t = t_next;
            continue;
        }
        // VI.B: an intersection whose bounding ball is below the threshold is not sampled.
        bool in3 = meets3 && 0.5 * length(hi - lo) >= ball;
        // The height field fills everything below its surface: its box reaches down without bound.
        bool in2 = all(lessThan(max(c_lo.xz, m_lo.xz), min(c_hi.xz, m_hi.xz))) && c_lo.y <= m_hi.y;
        float lod2 = level_2d(m, d);
        if (in2 && skip) {
            // VI.A: "sampling is started at the minimum height of the cone and abandoned at the
            // maximum height": a cube above the highest terrain under it is empty space; one below
            // the lowest is buried: the cone ends there, its open part lit by the terrain.
            vec2 range = cg_hsat_range(u_hsat, m, c_lo.xz, c_hi.xz, int(lod2));
            if (range.x > range.y || c_lo.y > range.y) {
                in2 = false;
            } else if (abandon && c_hi.y < range.x) {
                CG_READ(1);
                vec3 radiance = m.radiance_scale * textureLod(u_lightmap, cg_heightmap_uv(m, cube.centre.xz), lod2).rgb;
                acc.rgb += (1.0 - acc.a) * radiance;
                acc.a = 1.0;
                break;
            }
        }
        if (!in3 && !in2) {
            volume_prev = 0.0;
            if (t > t_leave)
                break;  // past both maps along the axis and meeting neither: nothing more to gather
            t = t_next;
            continue;
        }
        float a3 = 0.0;
        if (in3) {
            // Eq. 15: the intersection's geometric centre; Case 1 by the shared 3D step.
            float before = acc.a;
            vec3 centre = 0.5 * (lo + hi);
            cg_cone_step(volume, v, cone, no_surface, CgConeSample(centre, d, -1.0), v.radiance_scale, state, acc);
            a3 = (acc.a - before) / max(1.0 - before, 1e-6);
        }
        if (in2 && acc.a < CG_CONE_OPAQUE) {
            vec3 p_lo = meets3 ? v_lo : vec3(1e30), p_hi = meets3 ? v_hi : vec3(-1e30);
            Search s = dda ? morphology_search(m, dir, cube, lod2, p_lo, p_hi, a3) : centre_sample(m, cube, lod2);
            float alpha;
            if (occlusion == OCCLUSION_EQ17) {
                // Eq. 17: a = step_diameter / current_step_length wherever the cube meets the terrain.
                alpha = s.occludes ? min(d / t, 1.0) : 0.0;
            } else {
                // Eq. 16: a = (h2 A2 - h1 A1) / (h2 A2), the share of this step's occluded volume
                // that the previous step did not have (1 at a first contact; clamped at 0 past a crest).
                alpha = s.volume > 0.0 ? clamp((s.volume - volume_prev) / s.volume, 0.0, 1.0) : 0.0;
                volume_prev = s.volume;
            }
            cg_cone_composite(acc, vec4(alpha * s.radiance, alpha));
        } else {
            volume_prev = 0.0;
        }
        t = t_next;
    }
    return acc;
}

#else
// ------------------------------------------------------------------------------ ours: the horizon

#define QUAD_POINTS CG_HYBRID_CELL_POINTS

// The cone's cell as quadrature points of equal cosine weight (hybrid_gather.c, cell_points()),
// each standing for a band of elevations 2 w wide around its world elevation e. A band's share
// below the horizon's elevation E is its solid angle's share there, linear in sin E across the band:
// clamp((sin E - sin(e - w)) / (sin(e + w) - sin(e - w)), 0, 1) (a band ending at a pole ends at
// sin = +-1), kept per point as a rate and an offset, one multiply-add a point in the march's hot
// loop, from sin e, cos e (the point's y, a square root) and cos w, sin w (once per cone): no asin
// per point, no atan per terrain sample. `lowest`: the sine of the cell's lowest elevation (a
// horizon below it covers nothing).
struct Cell {
    float offset[QUAD_POINTS], rate[QUAD_POINTS];
    float lowest;
};

Cell
cell_of(int k, mat3 frame)
{
    Cell c;
    float half_width = cg_hybrid_gather_block.cell_width[k / 4][k % 4];
    float cos_w = cos(half_width), sin_w = sin(half_width);
    c.lowest = 1.0;
    for (int j = 0; j < QUAD_POINTS; j++) {
        float sin_e = clamp((frame * cg_hybrid_gather_block.cells[k * QUAD_POINTS + j].xyz).y, -1.0, 1.0);
        float cos_e = sqrt(max(1.0 - sin_e * sin_e, 0.0));
        float lo = sin_e <= -cos_w ? -1.0 : sin_e * cos_w - cos_e * sin_w;
        float hi = sin_e >= cos_w ? 1.0 : sin_e * cos_w + cos_e * sin_w;
        c.rate[j] = 1.0 / (hi - lo);
        c.offset[j] = -lo * c.rate[j];
        c.lowest = min(c.lowest, lo);
    }
    return c;
}

// The cosine-weighted share of the cell below the horizon whose elevation has the sine
// `sin_horizon`: each point's band covered continuously across its width. The horizon is the one
// along the cone's axis, taken for the whole cell.
float
cell_below(Cell c, float sin_horizon)
{
    float share = 0.0;
    for (int j = 0; j < QUAD_POINTS; j++)
        share += clamp(sin_horizon * c.rate[j] + c.offset[j], 0.0, 1.0);
    return share / float(QUAD_POINTS);
}

// Max of the level-0 heights over block `cell` of pyramid level `level` (HSAT mode pyramid).
float
block_max(ivec2 cell, int level)
{
    CG_READ(1);
    return uintBitsToFloat(texelFetch(u_hsat, cell, level).g);
}

bool
inside_map(vec2 uv)
{
    return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
}

// Where the ray o + t d meets the xz rectangle [lo, hi]: (enter, leave), enter > leave for a miss.
vec2
xz_interval(vec2 o, vec2 d, vec2 lo, vec2 hi)
{
    vec2 inv = 1.0 / d;
    vec2 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
    vec2 tmin = min(t0, t1), tmax = max(t0, t1);
    return vec2(max(tmin.x, tmin.y), min(tmax.x, tmax.y));
}

// Whether the point lies on the height field itself: the 2D lightmap's surface at its xz, within
// about a texel of it, facing the same way. Such a point has no voxels of its own.
bool
on_height_field(CgHeightmap m, vec3 p, vec3 n)
{
    vec2 uv = cg_heightmap_uv(m, p.xz);
    if (!inside_map(uv) || n.y <= 0.0)
        return false;
    vec2 du = vec2(1.0 / m.resolution, 0.0);
    CG_READ(5);
    float h = textureLod(u_lightmap, uv, 0.0).a;
    float hx = textureLod(u_lightmap, uv + du.xy, 0.0).a - textureLod(u_lightmap, uv - du.xy, 0.0).a;
    float hz = textureLod(u_lightmap, uv + du.yx, 0.0).a - textureLod(u_lightmap, uv - du.yx, 0.0).a;
    vec3 normal = normalize(vec3(-hx / (2.0 * m.texel.x), 1.0, -hz / (2.0 * m.texel.y)));
    return abs(p.y - h) <= 2.0 * cg_heightmap_xel(m) * (1.0 + length(normal.xz) / normal.y) && dot(normal, n) > 0.9;
}

// The share of a disc below a chord at height u (in radii from its centre): a circular segment.
float
disc_below(float u)
{
    return clamp(0.5 + (u * sqrt(1.0 - u * u) + asin(u)) / PI, 0.0, 1.0);
}

// How far the 3D step's footprint (a disc of diameter `d3` at `x3`) and the open segment's top
// (`top`, on a footprint `d` wide) are from the 3D lightmap's box [lo, hi]: below 0, the step may
// meet what the box holds.
float
footprint_gap(vec3 lo, vec3 hi, vec3 x3, float d3, vec3 top, float d)
{
    return min(length(max(max(lo - x3, x3 - hi), vec3(0.0))) - 0.5 * d3,
               length(max(max(lo - top, top - hi), vec3(0.0))) - 1e-3 * d);
}

// What the terrain walk carries from one sample to the next.
struct Horizon {
    float slope;        // the tan of the running horizon's elevation, compared with the terrain's
                        // rise over the distance, so that an elevation is computed only where it rises
    float covered;      // the cosine-weighted share of the cone's cell the terrain has covered
    float next;         // where the next terrain sample is due
    int level;          // the pyramid level the skipping tries first
    bool live;          // the terrain may still cover more of the cone
};

// One terrain sample at distance t along the axis (x, footprint d): the horizon raised by the
// texel under the axis, its newly covered share composited with the terrain's radiance; or, where
// `may_skip`, a jump over the coarsest pyramid block that cannot raise the horizon; or a jump to
// where the axis comes over the map.
void
terrain_sample(CgHeightmap m, vec3 p, vec3 dir, float t, vec3 x, float d, Cell cell, bool steep, float axis_slope,
               vec3 m_lo, vec3 m_hi, bool may_skip, inout Horizon h, inout vec4 acc)
{
    bool skip = cg_hybrid_gather_block.switches.w != 0;
    int top = int(m.levels) - 1;
    float horizontal = length(dir.xz);
    vec2 uv = cg_heightmap_uv(m, x.xz);
    float next = t + cg_hybrid_gather_block.params.y * d;
    if (!inside_map(uv)) {
        // No terrain here: on to where the axis comes over the map, or done.
        vec2 span = xz_interval(x.xz, dir.xz, m_lo.xz, m_hi.xz);
        if (!(span.x <= span.y) || span.y < 0.0)
            h.live = false;
        else
            next = max(next, t + span.x + 1e-4 * d);
        h.next = next;
        return;
    }
    float s = length(x.xz - p.xz);
    if (steep)
        s = max(s, 0.5 * d);
    // The ray at the horizon's elevation: terrain below it raises nothing. Along a block the axis
    // moves away from p, so the ray is lowest at the block's near side when it rises and at its far
    // side when it falls.
    float lod = clamp(level_2d(m, d) + cg_hybrid_gather_block.params.z, 0.0, m.levels - 1.0);
    int level = int(lod);
    bool fetch = true;
    // A cone whose axis is below the horizon may have it under the terrain: no skipping.
    if (skip && may_skip && axis_slope >= h.slope) {
        // Maximum-mipmap skipping: the coarsest pyramid block under the axis whose highest point
        // stays below that ray is passed in one jump, to where the axis leaves it; else the next
        // finer level is tried, down to the level sampled.
        int k = clamp(h.level, level, top);
        for (;;) {
            vec2 size = m.texel * float(1 << k);
            vec2 f = (x.xz - m.origin) / size;
            int n = max(int(m.resolution) >> k, 1);
            ivec2 c = clamp(ivec2(floor(f)), ivec2(0), ivec2(n - 1));
            vec2 edge = vec2(dir.x >= 0.0 ? float(c.x + 1) : float(c.x), dir.z >= 0.0 ? float(c.y + 1) : float(c.y));
            vec2 rate = dir.xz / size;
            vec2 exit = vec2(abs(rate.x) > 1e-20 ? (edge.x - f.x) / rate.x : 1e30,
                             abs(rate.y) > 1e-20 ? (edge.y - f.y) / rate.y : 1e30);
            float leave = max(min(exit.x, exit.y), 0.0);
            float s_ray = h.slope >= 0.0 ? s : length(x.xz + dir.xz * leave - p.xz);
            if (steep)
                s_ray = max(s_ray, 0.5 * d);
            if (block_max(c, k) > p.y + s_ray * h.slope) {
                if (k == level)
                    break;
                k--;
                continue;
            }
            next = max(next, t + leave + 1e-4 * d);
            fetch = false;
            k = min(k + 1, top);
            break;
        }
        h.level = k;
    }
    if (fetch) {
        // The texel under the axis, unfiltered: the horizon takes the highest of the samples, so a
        // filter would only flatten them, and one fetch is a sixteenth of the 3D step's trilinear one.
        int n = max(int(m.resolution) >> level, 1);
        CG_READ(1);
        vec4 texel = texelFetch(u_lightmap, clamp(ivec2(floor(uv * float(n))), ivec2(0), ivec2(n - 1)), level);
        if (texel.a - p.y > s * h.slope) {
            // Every direction of the cell below the new horizon meets the terrain here: the newly
            // covered share, with the terrain's radiance. The horizon's slope is the rise itself
            // and its elevation's sine the rise over the distance to the texel (at s = 0, 1):
            // llvmpipe runs this for every step of the march, where atan2 with tan after it made
            // the gather 1.05 times as dear, and atan (with an asin a point in cell_of) 1.03 times
            // (docs/hybrid.md).
            float dy = texel.a - p.y, rise = dy / s;
            float share = cell_below(cell, dy * inversesqrt(s * s + dy * dy));
            if (share > h.covered) {
                float w = min(share - h.covered, 1.0 - acc.a);
                acc.rgb += w * m.radiance_scale * texel.rgb;
                acc.a += w;
                h.covered = share;
            }
            h.slope = clamp(rise, -MAX_SLOPE, MAX_SLOPE);
        }
        // The axis under the terrain: the footprint's part below the terrain's height (its disc seen
        // across, vertical half extent r cos e) is covered, so that a cone whose axis runs into the
        // ground ends there, as the horizon of its one azimuth may not tell (a cone wider than the
        // terrain around it, a terrain ending at a wall).
        if (texel.a > x.y) {
            float across = 0.5 * d * max(horizontal, 1e-3);
            float buried = disc_below(clamp((texel.a - x.y) / across, -1.0, 1.0));
            if (buried > h.covered) {
                float w = min(buried - h.covered, 1.0 - acc.a);
                acc.rgb += w * m.radiance_scale * texel.rgb;
                acc.a += w;
                h.covered = buried;
            }
        }
    }
    // Done once even the highest terrain stays below the horizon's ray, and the ray no longer falls.
    if (h.covered >= 1.0 || (h.slope >= 0.0 && m.y_max <= p.y + s * h.slope))
        h.live = false;
    h.next = next;
}

// Where the 3D step samples the part of the footprint the terrain left open (a disc across the
// cone, cut by the horizon's chord): the centroid of the circular segment above the chord, in
// radii from the centre up across the cone, for the covered share `covered` (blocks.h's
// CG_SEGMENT_CENTROID_FIT: within 1.7e-5 radii; no table, no dynamic index into the block).
float
open_lift(float covered)
{
    float c = clamp(covered, 0.0, 1.0), open = 1.0 - c;
    float s = CG_SEGMENT_CENTROID_FIT(pow(min(c, open), 2.0 / 3.0));
    return c <= 0.5 ? s * c / open : s;
}

// One cone: `p` the surface point, `origin` the 3D march's origin (moved off the surface as
// cone_gather moves it), `surface` its cap (w < 0: none), `cell` its cell.
//
// Every step samples the 3D lightmap (cone_gather's step, eq. 12: wherever the footprint overlaps
// its box) and then, when one is due, the terrain. The terrain below the horizon has taken the
// lower part of the footprint (a disc across the cone, cut by the horizon's chord): the 3D step
// samples the open part, at its centroid and with its area's diameter, so that a cone whose axis
// has gone under the terrain still meets what its open part meets (a wall beyond the terrain's
// end). The terrain is sampled every `terrain_step` diameters and, once it covers part of the
// cone, with every 3D step too, so that the chord the 3D step samples follows the horizon.
//
// llvmpipe runs every texture read written in a loop body for every lane of a lockstep group,
// taken or not, and a 3D step on an occupied sample reads many texels. So the march is two loops:
// the inner one takes every step whose 3D sample is empty or off the box (with surface voxels, one
// occupancy read tells, as cone_gather's march crosses empty space: cg_cone_trace_surface) and
// the terrain samples with it; the outer one the 3D step on an occupied sample. The steps are the
// same as one loop's.
vec4
trace_horizon(sampler3D volume, vec3 p, vec3 origin, vec3 dir, float tan_half, float t_start, float t_max, vec4 surface,
              Cell cell)
{
    CgVolume v = hybrid_volume();
    CgHeightmap m = cg_heightmap();
    CgMarch march = cg_cone_march();
    vec3 v_lo, v_hi;
    box_3d(v, v_lo, v_hi);
    vec3 m_lo, m_hi;
    map_box(m, m_lo, m_hi);
    float xel = has_3d() ? min(v.voxel_size, cg_heightmap_xel(m)) : cg_heightmap_xel(m);
    CgCone cone = CgCone(origin, dir, tan_half, t_start, t_max, march.step, bias_3d());
    // A cone whose footprint holds the vertical has no one horizontal direction: its terrain is
    // seen at the rim of its footprint.
    float horizontal = length(dir.xz);
    bool steep = horizontal < tan_half / sqrt(1.0 + tan_half * tan_half);
    // Up across the cone: the footprint's direction towards the sky (any, for a vertical cone).
    vec3 up_across = vec3(0.0, 1.0, 0.0) - dir * dir.y;
    up_across = dot(up_across, up_across) > 1e-12 ? normalize(up_across) : vec3(1.0, 0.0, 0.0);
    vec4 acc = vec4(0.0);
    CgConeState state = cg_cone_state();    // what one 3D step tells the next (cg_cone_step)
    float lowest_slope = cell.lowest * inversesqrt(max(1.0 - cell.lowest * cell.lowest, 1e-12));
    Horizon h = Horizon(clamp(lowest_slope, -MAX_SLOPE, MAX_SLOPE), 0.0, t_start, int(m.levels) - 1, true);
    float chord_of = 0.0, lift = 0.0;
    float axis_slope = dir.y / max(horizontal, 1e-6);
    bool live3 = has_3d(), was_in3 = false;
    float t = t_start;
    // The farthest point of the 3D lightmap's box: past t_far3 / (1 - tan) a footprint cannot reach it.
    float t_far3 = length(max(abs(v_lo - origin), abs(v_hi - origin)));
    for (int i = 0; i < 4096 && t < t_max && acc.a < CG_CONE_OPAQUE && (live3 || h.live); i++) {
        // The step the inner loop stops at: its axis point, diameter and 3D sample.
        bool occupied = false;
        float d;
        vec3 x;
        CgConeSample at;
        for (; i < 4096 && t < t_max && acc.a < CG_CONE_OPAQUE; i++) {
            d = max(2.0 * tan_half * t, xel);
            x = origin + dir * t;
            float dt = 0.0, gap3 = 1e30;
            bool in3 = false;
            if (live3) {
                float open = 1.0 - h.covered;
                if (h.covered != chord_of) {
                    lift = open_lift(h.covered);
                    chord_of = h.covered;
                }
                // The open part's sample, and the open segment's top, half a diameter above the
                // axis: while that is in the box, the open part may still meet what the box holds.
                vec3 x3 = x + up_across * (lift * 0.5 * d);
                float d3 = max(d * sqrt(open), xel);
                gap3 = footprint_gap(v_lo, v_hi, x3, d3, x + up_across * (0.5 * d), d);
                in3 = gap3 < 0.0 && open > 1e-3;
                if (in3) {
                    at = CgConeSample(x3, d3, surface.w + dot(x3 - origin, surface.xyz));
#ifdef CG_CONE_SURFACE
                    float cell3, span3;
                    float lod3 = cg_cone_surface_level(v, cone, at, state, cell3, span3);
                    CG_READ(1);
                    occupied = textureLod(cg_surface_occupancy, cg_volume_uvw(v, cg_cone_read_position(state, x3)),
                                           ceil(lod3)).a > 0.0;
                    if (!occupied) {
                        was_in3 = true;
                        dt = cg_cone_surface_gap(state, span3);
                    }
#else
                    occupied = true;
#endif
                    if (occupied)
                        break;
                } else if (was_in3 || open <= 1e-3 || (tan_half < 1.0 && t > t_far3 / (1.0 - tan_half))) {
                    live3 = false;  // left the box (the footprint's gap is convex in t), under the
                                    // terrain, or out of its reach
                }
            }
            if (!in3 && !h.live && !live3)
                break;
            // Inside the 3D box the 3D steps pace the march and the terrain is sampled at nearly
            // every one of them: a skip there would only let a few of those steps pass without a
            // sample, and its descent through the pyramid costs a read a level at every step
            // (on builtin:openworld 7% of the gather, docs/hybrid.md). So the pyramid skips off
            // the box only.
            if (h.live && (t >= h.next || (in3 && h.covered > 0.0)))
                terrain_sample(m, p, dir, t, x, d, cell, steep, axis_slope, m_lo, m_hi, !in3, h, acc);
            // Off the box, on to the next terrain sample; a jump never takes the footprint into
            // the box unseen (its gap shrinks by at most 1 + tan per unit of t).
            if (!in3) {
                float jump = h.live ? h.next - t : 1e30;
                if (live3)
                    jump = min(jump, max(gap3 / (1.0 + tan_half), march.step * d));
                dt = max(jump, 1e-4 * d);
            }
            t += dt;
        }
        if (!occupied)
            break;
        // The 3D step on the occupied sample, then the terrain.
        was_in3 = true;
        float dt = cg_cone_step(volume, v, cone, surface, at, v.radiance_scale, state, acc);
        if (h.live && (t >= h.next || h.covered > 0.0) && acc.a < CG_CONE_OPAQUE)
            terrain_sample(m, p, dir, t, x, d, cell, steep, axis_slope, m_lo, m_hi, false, h, acc);
        t += dt;
    }
    return acc;
}
#endif
#endif

#if defined(CG_GATHER_MATERIAL) && (defined(SPECULAR) || defined(REFRACTION))
#if defined(HAS_2D) && !defined(METHOD_PAPER)
// The horizon's cell of a single cone (a material lobe's): every quadrature point on its axis, each
// point's band of elevations the cone's half angle wide either side (cell_of for a set's cone).
Cell
cell_of_axis(vec3 dir, float tan_half)
{
    Cell c;
    float half_width = atan(tan_half);
    float cos_w = cos(half_width), sin_w = sin(half_width);
    float sin_e = clamp(dir.y, -1.0, 1.0), cos_e = sqrt(max(1.0 - sin_e * sin_e, 0.0));
    float lo = sin_e <= -cos_w ? -1.0 : sin_e * cos_w - cos_e * sin_w;
    float hi = sin_e >= cos_w ? 1.0 : sin_e * cos_w + cos_e * sin_w;
    for (int j = 0; j < QUAD_POINTS; j++) {
        c.rate[j] = 1.0 / max(hi - lo, 1e-6);
        c.offset[j] = -lo * c.rate[j];
    }
    c.lowest = lo;
    return c;
}
#endif

// A material lobe's cone (common/gather.glsl: the specular or refracted cone, as cone_gather's)
// through this gather's march: the VCT march without a 2D lightmap, the paper's steps or the
// horizon with one (the surface's own voxels left out as for the diffuse cones, `own_voxels`); the
// sky through what it left open; rgb x the lobe's weight, a its coverage. Its 3D samples read
// CG_GATHER_LOBE_VOLUME (voxel_light's `glossy` where bound: one diffuse bounce further), its terrain
// samples the 2D lightmap the diffuse cones read, which has no such second volume: terrain seen in
// a mirror keeps one bounce fewer than the path tracer's (docs/vct.md, Per material).
vec4
trace_lobe(CgGatherLobe lobe, float t_max, float xel, bool own_voxels)
{
    vec4 traced;
#ifdef HAS_2D
#ifdef METHOD_PAPER
    traced = trace_paper(CG_GATHER_LOBE_VOLUME, lobe.origin, lobe.direction, lobe.tan_half, xel, t_max);
#else
    vec3 p = lobe.origin - lobe.surface.xyz * lobe.surface.w;
    traced = trace_horizon(CG_GATHER_LOBE_VOLUME, p, lobe.origin, lobe.direction, lobe.tan_half, xel, t_max,
                           own_voxels ? lobe.surface : vec4(lobe.surface.xyz, -1.0),
                           cell_of_axis(lobe.direction, lobe.tan_half));
#endif
#else
    CgVolume v = cg_volume();
    CgMarch march = cg_cone_march();
    CgCone c = CgCone(lobe.origin, lobe.direction, lobe.tan_half, v.voxel_size, t_max, march.step, march.lod_bias);
    traced = cg_cone_trace_surface(CG_GATHER_LOBE_VOLUME, v, c, lobe.surface);
#endif
    traced = cg_sky_gather(traced, lobe.direction, lobe.tan_half);
    return vec4(traced.rgb * lobe.weight, traced.a);
}

// cg_gather_reflection's march (common/gather.glsl): reach = (t_max, xel, own voxels, -).
vec4
cg_gather_trace_lobe(CgGatherLobe lobe, vec4 reach)
{
    return trace_lobe(lobe, reach.x, reach.y, reach.z > 0.0);
}
#endif

// The volume and terrain bounds' reach, the cones' voxel (the 3D lightmap's, or the terrain's xel
// without one) and whether the cones must keep off the surface's own voxels: what the diffuse and
// the material cones of a surface point share.
struct Reach {
    float t_max;
    float xel;
    bool own_voxels;
};

Reach
gather_reach(vec3 position, vec3 n)
{
    CgMarch march = cg_cone_march();
#ifdef HAS_2D
    CgVolume v = hybrid_volume();
    CgHeightmap m = cg_heightmap();
    vec3 lo, hi;
    map_box(m, lo, hi);
    if (has_3d()) {
        vec3 b_lo, b_hi;
        box_3d(v, b_lo, b_hi);
        lo = min(lo, b_lo);
        hi = max(hi, b_hi);
    }
    float t_max = march.max_distance > 0.0 ? march.max_distance : length(hi - lo);
#ifdef METHOD_PAPER
    // VI.B's self-influence: the cones start off the surface by the coarser of the two xels.
    float xel = has_3d() ? max(v.voxel_size, cg_heightmap_xel(m)) : cg_heightmap_xel(m);
    return Reach(t_max, xel, true);
#else
    // The 3D march starts as cone_gather's (start_offset voxels off the surface); the horizon
    // is seen from the surface point itself.
    float voxel = has_3d() ? v.voxel_size : cg_heightmap_xel(m);
    bool own_voxels = !(cg_hybrid_gather_block.levels.y != 0 && on_height_field(m, position, n));
    return Reach(t_max, voxel, own_voxels);
#endif
#else
    CgVolume v = cg_volume();
    return Reach(cg_cone_reach(v, march.max_distance), v.voxel_size, true);
#endif
}

// The diffuse cones of the surface point `position` with unit normal `n` (before the material's
// diffuse share): rgb the incident radiance integral E_i / pi, a the ambient visibility.
vec4
trace_diffuse(vec3 position, vec3 n, Reach r)
{
    mat3 frame = cg_tangent_frame(n);
    CgMarch march = cg_cone_march();
    vec4 diffuse = vec4(0.0);
#ifdef HAS_2D
    vec3 origin = position + n * (march.start_offset * r.xel);
#ifdef METHOD_PAPER
    // What each cone left open, past the volume and the terrain, sees the sky (common/sky.glsl).
    for (int k = cg_cone_first; k < cg_cone_count(); k += cg_cone_stride) {
        vec3 dir = cg_cone_direction(frame, k);
        float tan_half = cg_cone_tan_half(k);
        vec4 traced = trace_paper(cg_gather_volume, origin, dir, tan_half, r.xel, r.t_max);
        cg_cone_accumulate(diffuse, k, cg_sky_gather(traced, dir, tan_half));
    }
#else
    vec4 surface = r.own_voxels ? vec4(n, march.start_offset * r.xel) : vec4(n, -1.0);
    for (int k = cg_cone_first; k < cg_cone_count(); k += cg_cone_stride) {
        vec3 dir = cg_cone_direction(frame, k);
        float tan_half = cg_cone_tan_half(k);
        vec4 traced = trace_horizon(cg_gather_volume, position, origin, dir, tan_half, r.xel, r.t_max, surface,
                                    cell_of(k, frame));
        cg_cone_accumulate(diffuse, k, cg_sky_gather(traced, dir, tan_half));
    }
#endif
#else
    // No 2D lightmap: the VCT gather, the very function cone_gather calls.
    CgVolume v = cg_volume();
    diffuse = cg_cone_gather_diffuse(cg_gather_volume, v, cg_cone_origin(v, position, n, march.start_offset),
                                     frame, r.t_max, march.start_offset * v.voxel_size);
#endif
    return diffuse;
}

#ifdef CG_GATHER_DOWNSAMPLE
// The cones of the listed blocks and pixels (common/upsample.glsl's entry points).
vec4
cg_upsample_trace(ivec2 pixel, vec3 position, vec3 n)
{
    return trace_diffuse(position, n, gather_reach(position, n));
}

void
cg_upsample_untraced(ivec2 pixel)
{
}

vec3
cg_upsample_camera()
{
    return cg_hybrid_gather_block.camera.xyz;
}
#endif

#if !defined(CG_GATHER_LOWRES) && !defined(CG_GATHER_DEFERRED)
void
main()
{
    ivec2 pixel;
    if (!cg_gather_pixel(pixel))
        return;
    vec3 position, n;
    vec4 diffuse = vec4(0.0, 0.0, 0.0, 1.0);
    vec4 reflection = vec4(0.0), refraction = vec4(0.0);
    bool traced = false;    // the pixel's own diffuse cones, here (downsample 1)
    if (cg_gather_surface(pixel, position, n)) {
        // The material (common/gather.glsl): no diffuse cones where rho = 0, composite's factor.
#ifdef CG_GATHER_MATERIAL
        CgGatherMaterial mat = cg_gather_material(pixel);
        bool diffuse_lobe = any(greaterThan(mat.rho, vec3(0.0)));
        vec3 view = normalize(position - cg_hybrid_gather_block.camera.xyz);
#else
        bool diffuse_lobe = true;
#endif
        Reach reach = gather_reach(position, n);
#ifdef CG_GATHER_DOWNSAMPLE
        // No block agrees: its own cones, in the deferred dispatch (common/upsample.glsl).
        if (diffuse_lobe && !cg_upsample_diffuse(pixel, position, n, cg_hybrid_gather_block.camera.xyz, diffuse))
            cg_upsample_defer(pixel);
#else
        if (diffuse_lobe)
            diffuse = trace_diffuse(position, n, reach);
        traced = diffuse_lobe;
#endif
#ifdef CG_GATHER_MATERIAL
        diffuse.rgb *= cg_gather_diffuse_share(mat, cg_gather_brdf(max(dot(n, -view), 0.0), mat.roughness));
        float offset = cg_cone_march().start_offset * reach.xel;
#ifdef SPECULAR
        CgGatherLobe mirror = cg_gather_reflection_lobe(mat, position, n, view, offset);
        if (any(greaterThan(mirror.weight, vec3(0.0))))
            reflection = cg_gather_reflection(mat, mirror, view,
                                              vec4(reach.t_max, reach.xel, reach.own_voxels ? 1.0 : 0.0, 0.0));
#endif
#ifdef REFRACTION
        CgGatherLobe through = cg_gather_refraction_lobe(mat, position, n, view, offset);
        if (any(greaterThan(through.weight, vec3(0.0))))
            refraction = trace_lobe(through, reach.t_max, reach.xel, reach.own_voxels);
#endif
#endif
    }
    imageStore(cg_gather_radiance, pixel, diffuse);
#ifdef SPECULAR
    imageStore(u_reflection, pixel, reflection);
#endif
#ifdef REFRACTION
    imageStore(u_refraction, pixel, refraction);
#endif
    cg_reads_commit(traced);
}
#endif
