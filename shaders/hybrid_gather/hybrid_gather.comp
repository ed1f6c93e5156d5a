// hybrid_gather: indirect light of every G-buffer pixel by hybrid cone tracing (hybrid
// paper VI) through a mipped 3D lightmap of the complex meshes and a mipped 2D lightmap of
// the height-field meshes with its min/max height tables (HSAT).
//
// Diffuse cones and weights as cone_gather (hybrid eq. 3-4: the weights integrate the
// cosine lobe to 1, passes/sdk/cone.c); the output is sum_k W_k L_k (rgb) and the ambient
// visibility (a), which composite multiplies by the albedo.
//
// Without a 2D lightmap (HAS_2D undefined) the gather is cg_cone_gather_diffuse(), the VCT
// gather, so a scene without terrain gathers exactly what cone_gather does. With one, each step
// of a cone is an axis-aligned fitting cube (eq. 10-11, common/fitting_cube.glsl) and:
//   3D (Case 1): the cube meets the 3D lightmap's box (eq. 12) -> cg_cone_step(), the VCT
//     step, samples the intersection's geometric centre (eq. 15) at the matched level of the
//     cone's diameter (eq. 8, one level finer: common/cone_trace.glsl), capped near the
//     surface the cone leaves, and composites it over its span; the cone advances by that span.
//   2D (Case 2): the cube meets the height field's box -> HSAT gives the terrain's height
//     range under the cube's xz footprint; a cube above the highest terrain is empty space
//     and skipped; otherwise the 2D lightmap at its level of eq. 8 is walked along the
//     cone's projection by a 2D DDA, and the part of the cube below the terrain (its
//     coverage) occludes and lights the cone (eq. 16, or eq. 17 by a switch).
//   Mixed: 3D first, then 2D, in the same step (the paper's mix case).
#version 450 core
#include "common/cone_trace.glsl"
#include "common/gather.glsl"
#ifdef HAS_2D
#include "common/heightmap.glsl"
#include "common/hsat.glsl"
#include "common/fitting_cube.glsl"
#endif

layout(binding = CG_UNIT_LIGHTMAP2D) uniform sampler2D u_lightmap;
layout(binding = CG_UNIT_HSAT) uniform usampler2D u_hsat;

// The cone set and march: cg_cone_set_block (common/cone_trace.glsl); the hybrid's switches:
CG_UNIFORM_BLOCK(CgHybridGather, cg_hybrid_gather_block, CG_BINDING_GATHER, CG_HYBRID_GATHER_BLOCK);

bool
has_3d()
{
    return cg_hybrid_gather_block.maps.x != 0;
}

#define OCCLUSION_EQ16 0
#define OCCLUSION_EQ17 1
#define DDA_MAX_CELLS 16

#ifdef HAS_2D
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

// The occluded part of the step's cross-section (A in eq. 16, an area): the section is the
// disc whose vertical diameter is [y0, y1], and the part below the terrain height h a circular
// segment, u = the height of h across the disc in radii: (u sqrt(1 - u^2) + asin u) / pi + 1/2.
// A disc half under the terrain is half covered, as the linear fraction of [y0, y1] would say, but
// a disc whose centre is under it is covered faster (u = 1/2: 0.80, not 0.75); the linear reading
// let a cone grazing a floor into a wall stay partly open (docs/hybrid.md, the furnace).
float
coverage(float h, float y0, float y1)
{
    // y1 > y0 for every cube (its side is at least the finest xel); a zero-height section (an
    // underflowed side) is covered when the terrain reaches it. No floor in metres.
    if (!(y1 > y0))
        return h >= y0 ? 1.0 : 0.0;
    float u = clamp(2.0 * (h - y0) / (y1 - y0) - 1.0, -1.0, 1.0);
    return clamp(0.5 + (u * sqrt(1.0 - u * u) + asin(u)) / 3.14159265358979, 0.0, 1.0);
}

// The terrain in one step: rgb = stored radiance of the most occluding texel, a = its coverage of
// the cube's vertical extent. The DDA walks the texels of level `level` that the cone axis
// crosses between t0 and t1 (Amanatides and Woo 1987); at each, the cube is centred on the
// axis height there. When one texel occludes, later ones count only where they rise higher
// (the paper's "dynamic distance": the previous height decides whether a sample is kept).
vec4
terrain_sample(CgHeightmap m, vec3 origin, vec3 dir, float t0, float t1, CgFittingCube cube, float lod)
{
    float half_side = 0.5 * cube.side;
    if (cg_hybrid_gather_block.switches.z == 0) {   // no DDA: one sample at the cube's centre
        vec4 s = textureLod(u_lightmap, cg_heightmap_uv(m, cube.centre.xz), lod);
        return vec4(s.rgb, coverage(s.a, cube.centre.y - half_side, cube.centre.y + half_side));
    }
    int level = int(lod);
    int n = max(int(m.resolution) >> level, 1);
    vec2 cell_size = m.texel * float(1 << level);
    vec3 p0 = origin + dir * t0;
    vec2 a = (p0.xz - m.origin) / cell_size;
    vec2 span = dir.xz * (t1 - t0) / cell_size;     // texels crossed over the step (1e30: never, in texels)
    ivec2 cell = ivec2(floor(a));
    ivec2 stride = ivec2(sign(span));
    vec2 inv = vec2(span.x != 0.0 ? 1.0 / abs(span.x) : 1e30, span.y != 0.0 ? 1.0 / abs(span.y) : 1e30);
    // Parameter s in [0,1] along the step at which the walk crosses the next cell edge.
    vec2 next = vec2(span.x > 0.0 ? (floor(a.x) + 1.0 - a.x) : (a.x - floor(a.x)),
                     span.y > 0.0 ? (floor(a.y) + 1.0 - a.y) : (a.y - floor(a.y))) * inv;
    float s_in = 0.0;
    vec4 best = vec4(0.0);
    for (int i = 0; i < DDA_MAX_CELLS && s_in < 1.0; i++) {
        float s_out = min(min(next.x, next.y), 1.0);
        // A cell outside the map reads the border texel, as the cube-centre sample's
        // clamp-to-edge sampler does: the box test let the cube in because it overlaps the map,
        // and skipping such cells left its section open under the terrain's edge.
        vec4 texel = texelFetch(u_lightmap, clamp(cell, ivec2(0), ivec2(n - 1)), level);
        float y = p0.y + dir.y * (t1 - t0) * 0.5 * (s_in + s_out);
        float o = coverage(texel.a, y - half_side, y + half_side);
        if (o > best.a)
            best = vec4(texel.rgb, o);
        if (next.x < next.y) {
            cell.x += stride.x;
            next.x += inv.x;
        } else {
            cell.y += stride.y;
            next.y += inv.y;
        }
        s_in = s_out;
    }
    return best;
}

// One cone from a surface point (`surface` as in cg_cone_step: the normal and the origin's
// height above the surface). Returns (radiance, coverage) as cg_cone_trace_surface does.
vec4
hybrid_trace(vec3 origin, vec3 dir, float tan_half, float t_start, float t_max, vec4 surface)
{
    CgVolume v = cg_volume();
    CgHeightmap m = cg_heightmap();
    CgMarch march = cg_cone_march();
    bool eq11 = cg_hybrid_gather_block.switches.x != 0, skip = cg_hybrid_gather_block.switches.w != 0;
    int occlusion = cg_hybrid_gather_block.switches.y;
    vec3 v_lo = v.origin, v_hi = v.origin + vec3(cg_volume_extent(v));
    vec3 m_lo = vec3(m.origin.x, m.y_min, m.origin.y);
    vec3 m_hi = vec3(m.origin.x + m.texel.x * m.resolution, m.y_max, m.origin.y + m.texel.y * m.resolution);
    float xel = cg_heightmap_xel(m);
    if (has_3d())
        xel = min(xel, v.voxel_size);
    float t_leave = ray_box_exit(origin, dir, m_lo, m_hi);
    if (has_3d())
        t_leave = max(t_leave, ray_box_exit(origin, dir, v_lo, v_hi));
    float half_angle = atan(tan_half);
    float top2 = m.levels - 1.0;
    CgCone cone = CgCone(origin, dir, tan_half, t_start, t_max, march.step, march.lod_bias);
    vec4 acc = vec4(0.0);
    float covered = 0.0;    // part of the cone's section already below the terrain
    float t = t_start;
    for (int i = 0; i < 4096 && t < t_max && acc.a < CG_CONE_OPAQUE; i++) {
        // Eq. 8's diameter, never below the finest xel: log2 of zero is -inf.
        float d = max(2.0 * tan_half * t, xel);
        float dt = march.step * d;
        CgFittingCube cube = cg_fitting_cube(origin, dir, half_angle, t, d, eq11);
        vec3 c_lo = cube.centre - 0.5 * cube.side, c_hi = cube.centre + 0.5 * cube.side;
        bool alive = false;
        if (has_3d()) {
            // Eq. 12: the cube against the 3D lightmap's box; their intersection is a box.
            vec3 lo = max(c_lo, v_lo), hi = min(c_hi, v_hi);
            if (all(lessThan(lo, hi))) {
                alive = true;
                // Eq. 15: the mean of the intersection's corners, its centre, sampled by the VCT
                // step (matched level, surface cap, span compositing); the step then advances by
                // the span the sample stood for, so that its coverage is exact (cg_cone_step).
                vec3 centre = 0.5 * (lo + hi);
                CgConeSample at = CgConeSample(centre, d, surface.w + dot(centre - origin, surface.xyz));
                dt = cg_cone_step(cg_gather_volume, v, cone, surface, at, v.radiance_scale, acc);
            }
        }
        // The height field fills everything below its surface: its box reaches down without
        // bound (a flat terrain has y_min = y_max, and a cube under it is buried, not outside).
        if (acc.a < CG_CONE_OPAQUE && all(lessThan(max(c_lo.xz, m_lo.xz), min(c_hi.xz, m_hi.xz))) &&
            c_lo.y <= m_hi.y) {
            alive = true;
            // Eq. 8 with the 2D lightmap's xel.
            float lod = clamp(log2(d / cg_heightmap_xel(m)) + march.lod_bias, 0.0, top2);
            bool empty = false;
            if (skip) {
                vec2 range = cg_hsat_range(u_hsat, m, c_lo.xz, c_hi.xz, int(lod));
                empty = range.x > range.y || c_lo.y > range.y;
            }
            if (!empty) {
                vec4 s = terrain_sample(m, origin, dir, t, t + dt, cube, lod);
                s.rgb *= m.radiance_scale;  // the lightmap's pre-exposure (common/heightmap.glsl)
                if (occlusion == OCCLUSION_EQ17) {
                    // Eq. 17: a = step_diameter / current_step_length wherever the cube meets the
                    // terrain, an opacity composited front to back.
                    float alpha = s.a > 0.0 ? min(d / t, 1.0) : 0.0;
                    cg_cone_composite(acc, vec4(alpha * s.rgb, alpha));
                } else if (s.a > covered) {
                    // Eq. 16: the newly occluded part of the section is a coverage, added as the
                    // 3D steps add theirs (cg_cone_composite_span over one cell: w = min(new, 1 - a)):
                    // the terrain and the voxels cover disjoint parts of the section.
                    float fresh = s.a - covered;
                    covered = s.a;
                    cg_cone_composite_span(acc, vec4(fresh * s.rgb, fresh), 1.0, 1.0);
                }
            }
        }
        // Past both maps along the axis and meeting neither: nothing more to gather.
        if (!alive && t > t_leave)
            break;
        t += dt;
    }
    return acc;
}
#endif

void
main()
{
    ivec2 pixel;
    if (!cg_gather_pixel(pixel))
        return;
    vec3 position, n;
    vec4 diffuse = vec4(0.0, 0.0, 0.0, 1.0);
    if (cg_gather_surface(pixel, position, n)) {
        mat3 frame = cg_tangent_frame(n);
        CgMarch march = cg_cone_march();
        diffuse = vec4(0.0);
#ifdef HAS_2D
        CgVolume v = cg_volume();
        CgHeightmap m = cg_heightmap();
        // The coarser of the two xels: off the surface's own voxels and texels (self-influence, VI.B).
        float xel = has_3d() ? max(v.voxel_size, cg_heightmap_xel(m)) : cg_heightmap_xel(m);
        vec3 origin = position + n * (march.start_offset * xel);
        vec4 surface = vec4(n, march.start_offset * xel);
        vec3 lo = vec3(m.origin.x, m.y_min, m.origin.y);
        vec3 hi = vec3(m.origin.x + m.texel.x * m.resolution, m.y_max, m.origin.y + m.texel.y * m.resolution);
        if (has_3d()) {
            lo = min(lo, v.origin);
            hi = max(hi, v.origin + vec3(cg_volume_extent(v)));
        }
        float t_max = march.max_distance > 0.0 ? march.max_distance : length(hi - lo);
        for (int k = 0; k < cg_cone_count(); k++) {
            // What the cone left open, past the volume and the terrain, sees the sky (common/sky.glsl).
            vec3 dir = cg_cone_direction(frame, k);
            cg_cone_accumulate(diffuse, k, cg_sky_gather(hybrid_trace(origin, dir, cg_cone_tan_half(k), xel, t_max, surface),
                                                         dir, cg_cone_tan_half(k)));
        }
#else
        // No 2D lightmap: the VCT gather, the very function cone_gather calls.
        CgVolume v = cg_volume();
        diffuse = cg_cone_gather_diffuse(cg_gather_volume, v, cg_cone_origin(v, position, n, march.start_offset), frame,
                                         cg_cone_reach(v, march.max_distance), march.start_offset * v.voxel_size);
#endif
    }
    imageStore(cg_gather_radiance, pixel, diffuse);
}
