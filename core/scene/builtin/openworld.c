/* builtin:openworld: height-field terrain (most of the triangles), coloured buildings standing on it,
 * a bridge over a valley and a stone arch (space under them: no height field can hold them), a
 * sun and a camera. ?triangles=N&seed=S&motion=none|sun|one|all&period=P&size=METRES.
 *
 * size (default 400) scales the world, not the things in it: the terrain's features and the
 * town's extent grow with k = size / 400 (the relief with sqrt(k): larger landscapes have gentler
 * slopes), while the buildings, the bridge's deck and the arch keep their real sizes; the town
 * keeps today's density (k^2 times the buildings, at most one per 32 triangles of N) and the
 * bridge gets piers along its longer span. The camera and the sun frame the world as at 400 m.
 * At the default every number is computed as before, so the scene is bit for bit what it was.
 *
 * The motions are the dynamic cases the papers' methods must serve, as a glTF animation of
 * one period P (seconds, default 20), after which the scene holds its last pose:
 *   sun  the sun turns once about the vertical, keeping its elevation;
 *   one  one building (the nearest to the view's centre) sinks into the ground, roof and all,
 *        by half the period and rises again;
 *   all  every complex object moves: each building turns once about its vertical axis (in
 *        alternate directions), the bridge and the arch rise 3 m and come down again.
 * Without motion (the default) the scene is what it always was, bit for bit. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

/* Lengths of the default 400 m world; positions and terrain lengths are multiplied by k = size / 400,
 * heights of the terrain by sqrt(k). */
#define OW_SIZE 400.0        /* terrain side, metres; x and z in [-200, 200] */
#define OW_RELIEF 14.0       /* fbm amplitude, metres */
#define OW_VALLEY_Z 60.0     /* the valley runs along x at this z */
#define OW_VALLEY_DEPTH 16.0
#define OW_VALLEY_WIDTH 16.0
#define OW_BRIDGE_X 20.0
#define OW_ARCH_X -70.0      /* a gate in front of the town, facing the camera */
#define OW_ARCH_Z 24.0
#define OW_CELL 32.0         /* placement grid: wider than the farthest two buildings can overlap (27.1 m) */

typedef struct terrain {
    uint64_t seed;
    double size;            /* side, metres */
    double k, rise;         /* size / OW_SIZE, and sqrt(k): how lengths and heights scale */
    int gx, gz;             /* cells along x and z */
    double dx, dz;          /* cell size */
    float *height;          /* (gx+1) x (gz+1) vertex heights, row-major in z */
} terrain;

static double
terrain_height_analytic(const terrain *t, double x, double z)
{
    double h = OW_RELIEF * t->rise * bs_fbm(x / (90.0 * t->k), z / (90.0 * t->k), t->seed);
    /* Hills rise towards the far edge so the camera sees a skyline. */
    h += 10.0 * t->rise * (1.0 - z / (t->size / 2)) * 0.5 - 5.0 * t->rise;
    double dv = (z - OW_VALLEY_Z * t->k) / (OW_VALLEY_WIDTH * t->k);
    return h - OW_VALLEY_DEPTH * t->rise * exp(-dv * dv);
}

/* Height of the triangulated terrain (not the noise): what the mesh really has at (x, z).
 * Cells split along the diagonal from (i+1, j) to (i, j+1). */
static double
terrain_mesh_height(const terrain *t, double x, double z)
{
    double fx = (x + t->size / 2) / t->dx, fz = (z + t->size / 2) / t->dz;
    if (fx < 0) fx = 0;
    if (fz < 0) fz = 0;
    if (fx > t->gx) fx = t->gx;
    if (fz > t->gz) fz = t->gz;
    int i = (int)fx, j = (int)fz;
    if (i >= t->gx) i = t->gx - 1;
    if (j >= t->gz) j = t->gz - 1;
    double u = fx - i, v = fz - j;
    int w = t->gx + 1;
    double h00 = t->height[j * w + i], h10 = t->height[j * w + i + 1];
    double h01 = t->height[(j + 1) * w + i], h11 = t->height[(j + 1) * w + i + 1];
    if (u + v <= 1)
        return h00 + u * (h10 - h00) + v * (h01 - h00);
    return h11 + (1 - u) * (h01 - h11) + (1 - v) * (h10 - h11);
}

/* Lowest mesh height under an axis-aligned rectangle (sampled at half a cell and at its corners). */
static double
terrain_min_under(const terrain *t, double x0, double z0, double x1, double z1)
{
    double step = 0.5 * (t->dx < t->dz ? t->dx : t->dz);
    int nx = (int)ceil((x1 - x0) / step), nz = (int)ceil((z1 - z0) / step);
    double lo = INFINITY;
    for (int a = 0; a <= nx; a++)
        for (int b = 0; b <= nz; b++) {
            double h = terrain_mesh_height(t, x0 + (x1 - x0) * a / nx, z0 + (z1 - z0) * b / nz);
            if (h < lo)
                lo = h;
        }
    return lo;
}

static bool
build_terrain(cg_scene *scene, terrain *t, int material, cg_error *err)
{
    int w = t->gx + 1, d = t->gz + 1;
    size_t nv = (size_t)w * d;
    size_t ni = (size_t)t->gx * t->gz * 6;
    mesh_builder b = { 0 };
    b.positions = malloc(nv * 3 * sizeof(float));
    b.normals = malloc(nv * 3 * sizeof(float));
    b.texcoords = malloc(nv * 2 * sizeof(float));
    b.indices = malloc(ni * sizeof(uint32_t));
    if (!b.positions || !b.normals || !b.texcoords || !b.indices)
        b.failed = true;
    else {
        b.vertex_count = (uint32_t)nv;
        b.index_count = (uint32_t)ni;
        for (int j = 0; j < d; j++)
            for (int i = 0; i < w; i++) {
                size_t v = (size_t)j * w + i;
                double x = -t->size / 2 + i * t->dx, z = -t->size / 2 + j * t->dz;
                b.positions[3 * v + 0] = (float)x;
                b.positions[3 * v + 1] = t->height[v];
                b.positions[3 * v + 2] = (float)z;
                b.texcoords[2 * v + 0] = (float)(i / (double)t->gx);
                b.texcoords[2 * v + 1] = (float)(j / (double)t->gz);
                /* Normal of the grid surface by central differences (one-sided at the edges). */
                int i0 = i > 0 ? i - 1 : i, i1 = i < t->gx ? i + 1 : i;
                int j0 = j > 0 ? j - 1 : j, j1 = j < t->gz ? j + 1 : j;
                double sx = (t->height[(size_t)j * w + i1] - t->height[(size_t)j * w + i0]) / ((i1 - i0) * t->dx);
                double sz = (t->height[(size_t)j1 * w + i] - t->height[(size_t)j0 * w + i]) / ((j1 - j0) * t->dz);
                double len = sqrt(sx * sx + 1 + sz * sz);
                b.normals[3 * v + 0] = (float)(-sx / len);
                b.normals[3 * v + 1] = (float)(1 / len);
                b.normals[3 * v + 2] = (float)(-sz / len);
            }
        size_t k = 0;
        for (int j = 0; j < t->gz; j++)
            for (int i = 0; i < t->gx; i++) {
                uint32_t v00 = (uint32_t)(j * w + i), v10 = v00 + 1;
                uint32_t v01 = v00 + (uint32_t)w, v11 = v01 + 1;
                /* Counter-clockwise seen from above (+y): the surface faces up. */
                b.indices[k++] = v00, b.indices[k++] = v01, b.indices[k++] = v10;
                b.indices[k++] = v10, b.indices[k++] = v01, b.indices[k++] = v11;
            }
    }
    return mb_commit(scene, &b, "terrain", material, CG_MESH_HEIGHTFIELD, bs_identity, err);
}

enum { ROOF_FLAT, ROOF_GABLE };

typedef struct building {
    double x, z, hx, hz, height, yaw;
    int colour;  /* 0..3 */
    int roof;
} building;

/* Buildings placed so far, bucketed by OW_CELL cells so that a town of tens of thousands is placed
 * in linear time; the answer is the one a test against every building would give. */
typedef struct town_grid {
    double x0, z0;
    int nx, nz;
    int *head;  /* nx * nz: first building in the cell, -1: none */
    int *next;  /* per building: the next in its cell */
} town_grid;

static void
grid_cell(const town_grid *g, double x, double z, int *cx, int *cz)
{
    *cx = (int)floor((x - g->x0) / OW_CELL);
    *cz = (int)floor((z - g->z0) / OW_CELL);
    *cx = *cx < 0 ? 0 : *cx >= g->nx ? g->nx - 1 : *cx;
    *cz = *cz < 0 ? 0 : *cz >= g->nz ? g->nz - 1 : *cz;
}

static bool
overlaps(const town_grid *g, const building *all, double x, double z, double r)
{
    int cx, cz;
    grid_cell(g, x, z, &cx, &cz);
    for (int b = cz - 1; b <= cz + 1; b++)
        for (int a = cx - 1; a <= cx + 1; a++) {
            if (a < 0 || b < 0 || a >= g->nx || b >= g->nz)
                continue;
            for (int i = g->head[b * g->nx + a]; i >= 0; i = g->next[i]) {
                double rx = x - all[i].x, rz = z - all[i].z;
                double ri = sqrt(all[i].hx * all[i].hx + all[i].hz * all[i].hz);
                if (rx * rx + rz * rz < (r + ri + 3) * (r + ri + 3))
                    return true;
            }
        }
    return false;
}

static void
grid_add(town_grid *g, const building *all, int index)
{
    int cx, cz;
    grid_cell(g, all[index].x, all[index].z, &cx, &cz);
    g->next[index] = g->head[cz * g->nx + cx];
    g->head[cz * g->nx + cx] = index;
}

/* Triangles of a building: 5 box faces (the buried underside left out); a gable roof
 * adds 2 slopes and 2 gable ends. */
static int
building_triangles(const building *bd)
{
    return 10 + (bd->roof == ROOF_GABLE ? 6 : 0);
}

/* How far a gable roof's ridge rises above the walls (35 degrees pitch); 0 for a flat roof. */
static double
roof_rise(const building *bd)
{
    return bd->roof == ROOF_GABLE ? bd->hz * tan(35 * BS_PI / 180) : 0;
}

static void
build_building(mesh_builder *walls, mesh_builder *roofs, const building *bd, double base)
{
    double top = bd->height;
    double c[3] = { bd->x, base + (top - base) * 0.5 + 0, bd->z };
    double hb = (top - base) * 0.5;
    double h[3] = { bd->hx, hb, bd->hz };
    mb_box(walls, c, h, bd->yaw, false);
    if (bd->roof != ROOF_GABLE)
        return;
    /* Ridge along the local x axis, 35 degrees pitch. */
    double cs = cos(bd->yaw), sn = sin(bd->yaw);
    double rise = roof_rise(bd);
    double local[6][3] = { { -bd->hx, top, -bd->hz }, { bd->hx, top, -bd->hz },
                           { bd->hx, top, bd->hz },   { -bd->hx, top, bd->hz },
                           { -bd->hx, top + rise, 0 }, { bd->hx, top + rise, 0 } };
    double p[6][3];
    for (int i = 0; i < 6; i++) {
        p[i][0] = bd->x + cs * local[i][0] + sn * local[i][2];
        p[i][1] = local[i][1];
        p[i][2] = bd->z - sn * local[i][0] + cs * local[i][2];
    }
    mb_quad(roofs, p[3], p[2], p[5], p[4]);  /* slope facing +z */
    mb_quad(roofs, p[1], p[0], p[4], p[5]);  /* slope facing -z */
    mb_flat_triangle(roofs, p[2], p[1], p[5]); /* gable +x */
    mb_flat_triangle(roofs, p[0], p[3], p[4]); /* gable -x */
}

/* A road bridge across the valley along z at x = OW_BRIDGE_X k: a deck, two parapets and
 * 2 m + 1 piers down into the ground (m = round(k), at least 1: about 25 m apart at any size).
 * The deck spans the valley with metres of air below. */
static int
bridge_piers_half(double k)
{
    long m = lround(k);
    return m < 1 ? 1 : (int)m;
}

static int
bridge_triangles(double k)
{
    return 12 + 2 * 12 + (2 * bridge_piers_half(k) + 1) * 10;
}

static void
build_bridge(mesh_builder *b, const terrain *t)
{
    double vz = OW_VALLEY_Z * t->k, vw = OW_VALLEY_WIDTH * t->k, bx = OW_BRIDGE_X * t->k;
    double z0 = vz - 2.6 * vw, z1 = vz + 2.6 * vw;
    double bank = terrain_mesh_height(t, bx, z0);
    double bank1 = terrain_mesh_height(t, bx, z1);
    double deck = (bank > bank1 ? bank : bank1) + 1.0;
    double len = (z1 - z0) * 0.5 + 4;
    double deck_c[3] = { bx, deck, vz }, deck_h[3] = { 4, 0.6, len };
    mb_box(b, deck_c, deck_h, 0, true);
    for (int s = -1; s <= 1; s += 2) {
        double pc[3] = { bx + s * 3.8, deck + 1.1, vz }, ph[3] = { 0.2, 0.5, len };
        mb_box(b, pc, ph, 0, true);
    }
    int m = bridge_piers_half(t->k);
    for (int k = -m; k <= m; k++) {
        double pz = vz + k * (z1 - z0) * 0.3 / m;
        double ground = terrain_min_under(t, bx - 1.5, pz - 1.5, bx + 1.5, pz + 1.5) - 1.0;
        double top = deck - 0.6;
        double pc[3] = { bx, (ground + top) * 0.5, pz }, ph[3] = { 1.5, (top - ground) * 0.5, 1.5 };
        mb_box(b, pc, ph, 0, false);
    }
}

/* A free-standing stone arch: two legs and a half-ring of ARCH_SEGMENTS voussoirs. */
#define ARCH_SEGMENTS 12
static int
arch_triangles(void)
{
    return 2 * 10 + ARCH_SEGMENTS * 12;
}

static void
build_arch(mesh_builder *b, const terrain *t, double x, double z)
{
    const double span = 10.0, leg = 1.8, depth = 2.0, leg_height = 8.0;
    double ground = terrain_min_under(t, x - span - leg, z - depth, x + span + leg, z + depth) - 0.5;
    double spring = terrain_mesh_height(t, x, z) + leg_height;
    for (int s = -1; s <= 1; s += 2) {
        /* Each leg stands under one end of the ring (centre line at radius `span`). */
        double c[3] = { x + s * span, (ground + spring) * 0.5, z };
        double h[3] = { leg * 0.5, (spring - ground) * 0.5, depth };
        mb_box(b, c, h, 0, false);
    }
    /* Voussoirs: ring of radius `span` (inner) to span + leg (outer), as boxes with all faces. */
    double r = span + 0.0;
    for (int k = 0; k < ARCH_SEGMENTS; k++) {
        double a0 = BS_PI * k / ARCH_SEGMENTS, a1 = BS_PI * (k + 1) / ARCH_SEGMENTS;
        double p[8][3];
        double rad[2] = { r - leg * 0.5, r + leg * 0.5 };
        for (int i = 0; i < 8; i++) {
            double a = (i & 1) ? a1 : a0, rr = rad[(i >> 1) & 1], zz = (i & 4) ? depth : -depth;
            p[i][0] = x + rr * cos(a);
            p[i][1] = spring + rr * sin(a);
            p[i][2] = z + zz;
        }
        mb_quad(b, p[4], p[6], p[7], p[5]); /* front, +z */
        mb_quad(b, p[0], p[1], p[3], p[2]); /* back, -z */
        mb_quad(b, p[2], p[3], p[7], p[6]); /* outer (extrados) */
        mb_quad(b, p[0], p[4], p[5], p[1]); /* inner (intrados): faces the opening below */
        mb_quad(b, p[0], p[2], p[6], p[4]); /* joint at a0 */
        mb_quad(b, p[1], p[5], p[7], p[3]); /* joint at a1 */
    }
}

enum { MOTION_NONE, MOTION_SUN, MOTION_ONE, MOTION_ALL };
#define OW_LIFT 3.0           /* metres the bridge and the arch rise with motion=all */

static void
free_animation(cg_animation *anim)
{
    for (int c = 0; c < anim->channel_count; c++) {
        free(anim->channels[c].times);
        free(anim->channels[c].values);
    }
    free(anim->channels);
    memset(anim, 0, sizeof *anim);
}

/* Appends a channel of `keys` keys to `anim`; `values` holds keys x 3 or 4 floats. */
static bool
add_channel(cg_animation *anim, int node, cg_anim_path path, int keys, const float *times, const float *values,
            cg_error *err)
{
    cg_anim_channel *bigger = realloc(anim->channels, sizeof *bigger * (size_t)(anim->channel_count + 1));
    if (!bigger)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "builtin:openworld: out of memory for the animation");
    anim->channels = bigger;
    cg_anim_channel *ch = &anim->channels[anim->channel_count];
    *ch = (cg_anim_channel){ .node = node, .path = path, .interpolation = CG_INTERP_LINEAR };
    if (!cg_anim_channel_alloc(ch, keys, err))
        return false;
    anim->channel_count++;
    memcpy(ch->times, times, sizeof(float) * (size_t)keys);
    memcpy(ch->values, values, sizeof(float) * (size_t)keys * (size_t)cg_anim_channel_components(ch));
    return true;
}

/* Hamilton product a b of quaternions (x, y, z, w). */
static void
quat_mul(const double a[4], const double b[4], double out[4])
{
    double r[4] = { a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
                    a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
                    a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
                    a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2] };
    memcpy(out, r, sizeof r);
}

/* A full turn about +y (sign +1) or -y starting from `rest`: keys a quarter turn apart, so that
 * slerp between them (the shorter arc) turns at a constant rate. */
static bool
add_turn(cg_animation *anim, int node, const double rest[4], int sign, double period, cg_error *err)
{
    float times[5], values[20];
    for (int k = 0; k < 5; k++) {
        double half = sign * k * BS_PI / 4; /* half of k quarter turns */
        double turn[4] = { 0, sin(half), 0, cos(half) }, q[4];
        quat_mul(turn, rest, q);
        times[k] = (float)(period * k / 4);
        for (int c = 0; c < 4; c++)
            values[4 * k + c] = (float)q[c];
    }
    return add_channel(anim, node, CG_ANIM_ROTATION, 5, times, values, err);
}

/* Down by `dy` (negative: up) at half the period and back. */
static bool
add_dip(cg_animation *anim, int node, double dy, double period, cg_error *err)
{
    const float times[3] = { 0, (float)(period / 2), (float)period };
    const float values[9] = { 0, 0, 0, 0, (float)-dy, 0, 0, 0, 0 };
    return add_channel(anim, node, CG_ANIM_TRANSLATION, 3, times, values, err);
}

/* A node whose parent is `parent`, translated by t; -1 on failure. */
static int
add_node(cg_scene *scene, const char *name, int parent, double tx, double ty, double tz, cg_error *err)
{
    cg_node n = cg_node_default(name);
    n.parent = parent;
    n.translation[0] = (float)tx, n.translation[1] = (float)ty, n.translation[2] = (float)tz;
    return cg_scene_add_node(scene, &n, err);
}

/* Attaches the instance mb_commit just made to `node`. */
static bool
attach_last(cg_scene *scene, int node, cg_error *err)
{
    return cg_scene_attach(scene, CG_ATTACH_INSTANCE, scene->instance_count - 1, node, err) >= 0;
}

/* A building of its own (its walls and its roof as meshes of their own) on `node`. */
static bool
commit_building(cg_scene *scene, const building *bd, double base, int index, int wall_material, int roof_material,
                int node, cg_error *err)
{
    mesh_builder walls = { 0 }, roof = { 0 };
    build_building(&walls, &roof, bd, base);
    char name[CG_NAME_MAX];
    snprintf(name, sizeof name, "building_%d", index);
    bool ok = mb_commit(scene, &walls, name, wall_material, CG_MESH_COMPLEX, bs_identity, err) &&
              attach_last(scene, node, err);
    if (ok && roof.index_count > 0) {
        snprintf(name, sizeof name, "building_%d_roof", index);
        ok = mb_commit(scene, &roof, name, roof_material, CG_MESH_COMPLEX, bs_identity, err) &&
             attach_last(scene, node, err);
    }
    mb_free(&walls);
    mb_free(&roof);
    return ok;
}

static bool
build_openworld(cg_scene *scene, const char *query, cg_error *err)
{
    static const char *const motions[] = { "none", "sun", "one", "all", NULL };
    bs_param p[] = {
        { "triangles", 5000, 8000000, 200000, true, 200000, false, NULL },
        { "seed", 0, 18446744073709551615.0, 1, true, 1, false, NULL },
        { "motion", 0, 3, 0, false, 0, false, motions },
        { "period", 0.1, 100000, 20, false, 0, false, NULL },
        { "size", 100, 64000, OW_SIZE, false, 0, false, NULL },
    };
    if (!bs_parse_params("openworld", query, p, 5, err))
        return false;
    uint64_t seed = p[1].count; /* exact: a double holds integers only below 2^53 */
    long target = (long)p[0].count;
    int motion = (int)p[2].count;
    double period = p[3].value;
    double size = p[4].value, k = size / OW_SIZE;
    if (p[3].seen && motion == MOTION_NONE)
        return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:openworld: period=%g is given without a motion "
                       "(motion=sun, one or all)", period);
    bs_rng r = { bs_mix64(seed ^ 0x6F70656E776F726Cull) };

    int m_grass = bs_add_material(scene, "grass", 0.30f, 0.42f, 0.20f, err);
    int m_colour[4] = {
        bs_add_material(scene, "wall_red", 0.75f, 0.12f, 0.08f, err),
        bs_add_material(scene, "wall_blue", 0.12f, 0.25f, 0.75f, err),
        bs_add_material(scene, "wall_yellow", 0.85f, 0.70f, 0.15f, err),
        bs_add_material(scene, "wall_white", 0.80f, 0.80f, 0.78f, err),
    };
    int m_roof = bs_add_material(scene, "roof_tiles", 0.55f, 0.22f, 0.12f, err);
    int m_stone = bs_add_material(scene, "stone", 0.55f, 0.53f, 0.50f, err);
    if (m_grass < 0 || m_colour[0] < 0 || m_colour[1] < 0 || m_colour[2] < 0 || m_colour[3] < 0 ||
        m_roof < 0 || m_stone < 0)
        return false;

    /* Buildings first (their count sets how many triangles are left for the terrain),
     * more of them in larger scenes: from 12 at 10k triangles to 400 from 1M on, on 400 m; a world
     * k times wider keeps the town's density (k^2 times as many), buildings taking at most half of
     * the triangles (16 each at most). */
    long nb0 = target / 2500;
    if (nb0 < 12) nb0 = 12;
    if (nb0 > 400) nb0 = 400;
    long nbl = lround((double)nb0 * k * k);
    if (nbl > target / 32) nbl = target / 32;
    if (nbl < 1) nbl = 1;
    int nb = (int)nbl;
    double arch_x = OW_ARCH_X * k, arch_z = OW_ARCH_Z * k;
    /* The town lies south of the valley (z < 15 k), leaving the valley and the bridge clear; its
     * buildings (12.1 m from centre to corner at most) stay on the terrain in a world under 400 m. */
    double town_x1 = fmin(170 * k, size / 2 - 13), town_x0 = -town_x1;
    double town_z0 = fmax(-175 * k, 13 - size / 2), town_z1 = 15 * k;
    town_grid grid = { .x0 = town_x0, .z0 = town_z0 };
    grid.nx = (int)ceil((town_x1 - town_x0) / OW_CELL) + 1;
    grid.nz = (int)ceil((town_z1 - town_z0) / OW_CELL) + 1;
    building *bs = calloc((size_t)nb, sizeof *bs);
    grid.head = malloc(sizeof *grid.head * (size_t)grid.nx * (size_t)grid.nz);
    grid.next = malloc(sizeof *grid.next * (size_t)nb);
    if (!bs || !grid.head || !grid.next) {
        free(bs);
        free(grid.head);
        free(grid.next);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "builtin:openworld: out of memory");
    }
    for (size_t c = 0; c < (size_t)grid.nx * (size_t)grid.nz; c++)
        grid.head[c] = -1;
    int placed = 0;
    long other = bridge_triangles(k) + arch_triangles();
    for (long tries = 0; placed < nb && tries < (long)nb * 50; tries++) {
        building bd;
        bd.hx = bs_rng_range(&r, 3, 9);
        bd.hz = bs_rng_range(&r, 3, 8);
        bd.x = bs_rng_range(&r, town_x0, town_x1);
        bd.z = bs_rng_range(&r, town_z0, town_z1);
        bd.yaw = bs_rng_range(&r, -0.4, 0.4);
        bd.height = bs_rng_range(&r, 5, 22); /* above the ground, fixed below */
        bd.colour = (int)(bs_rng_next(&r) % 4);
        bd.roof = bs_rng_next(&r) % 2 ? ROOF_GABLE : ROOF_FLAT;
        double rad = sqrt(bd.hx * bd.hx + bd.hz * bd.hz);
        /* Keep the arch's square free. */
        if (fabs(bd.x - arch_x) < 14 + rad && fabs(bd.z - arch_z) < 8 + rad)
            continue;
        if (overlaps(&grid, bs, bd.x, bd.z, rad))
            continue;
        bs[placed] = bd;
        grid_add(&grid, bs, placed++);
        other += building_triangles(&bd);
    }
    free(grid.head);
    free(grid.next);

    /* Terrain grid: gx * gz cells, two triangles each, as close to what is left as the
     * integer grid allows (within 2 * gx triangles). */
    long left = target - other;
    terrain t = { .seed = seed, .size = size, .k = k, .rise = sqrt(k) };
    t.gx = (int)lround(sqrt(left / 2.0));
    if (t.gx < 2) t.gx = 2;
    t.gz = (int)lround(left / (2.0 * t.gx));
    if (t.gz < 2) t.gz = 2;
    t.dx = size / t.gx;
    t.dz = size / t.gz;
    t.height = malloc((size_t)(t.gx + 1) * (t.gz + 1) * sizeof(float));
    if (!t.height) {
        free(bs);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "builtin:openworld: out of memory for the terrain");
    }
    for (int j = 0; j <= t.gz; j++)
        for (int i = 0; i <= t.gx; i++)
            t.height[(size_t)j * (t.gx + 1) + i] =
                (float)terrain_height_analytic(&t, -size / 2 + i * t.dx, -size / 2 + j * t.dz);

    bool ok = build_terrain(scene, &t, m_grass, err);
    mesh_builder walls[4] = { { 0 } }, roofs = { 0 }, bridge = { 0 }, arch = { 0 };
    /* motion=one moves the building nearest to the view's centre (the camera looks at (0, 0, -20 k)). */
    int moving = -1;
    for (int i = 0; motion == MOTION_ONE && i < placed; i++) {
        double d = hypot(bs[i].x, bs[i].z + 20 * k),
               best = moving < 0 ? INFINITY : hypot(bs[moving].x, bs[moving].z + 20 * k);
        if (d < best)
            moving = i;
    }
    double *bases = malloc(sizeof *bases * (size_t)(placed > 0 ? placed : 1));
    if (!bases)
        ok = cg_fail(err, CG_ERR_OUT_OF_MEMORY, "builtin:openworld: out of memory");
    for (int i = 0; ok && i < placed; i++) {
        building *bd = &bs[i];
        double ext = sqrt(bd->hx * bd->hx + bd->hz * bd->hz);
        bases[i] = terrain_min_under(&t, bd->x - ext, bd->z - ext, bd->x + ext, bd->z + ext) - 0.3;
        double ground = terrain_mesh_height(&t, bd->x, bd->z);
        bd->height += ground;
        if (motion != MOTION_ALL && i != moving)
            build_building(&walls[bd->colour], &roofs, bd, bases[i]);
    }
    build_bridge(&bridge, &t);
    build_arch(&arch, &t, arch_x, arch_z);
    static const char *const wall_names[4] = { "buildings_red", "buildings_blue", "buildings_yellow",
                                               "buildings_white" };
    for (int c = 0; c < 4; c++) {
        if (walls[c].index_count == 0 && !walls[c].failed)
            continue;
        ok = ok && mb_commit(scene, &walls[c], wall_names[c], m_colour[c], CG_MESH_COMPLEX, bs_identity, err);
    }
    if (roofs.index_count > 0 || roofs.failed)
        ok = ok && mb_commit(scene, &roofs, "roofs", m_roof, CG_MESH_COMPLEX, bs_identity, err);

    cg_animation anim = { .name = "motion" };
    if (ok && motion == MOTION_ONE && moving >= 0) {
        int node = add_node(scene, "moving_building", -1, 0, 0, 0, err);
        ok = node >= 0 &&
             commit_building(scene, &bs[moving], bases[moving], moving, m_colour[bs[moving].colour], m_roof, node,
                             err) &&
             add_dip(&anim, node, bs[moving].height + roof_rise(&bs[moving]) - bases[moving], period, err);
    }
    /* Each building turns about the vertical through its centre: translated there, turned,
     * translated back (its vertices are in world space). */
    for (int i = 0; ok && motion == MOTION_ALL && i < placed; i++) {
        char name[CG_NAME_MAX];
        snprintf(name, sizeof name, "building_%d", i);
        int pivot = add_node(scene, name, -1, bs[i].x, 0, bs[i].z, err);
        snprintf(name, sizeof name, "building_%d_turn", i);
        int turn = pivot < 0 ? -1 : add_node(scene, name, pivot, 0, 0, 0, err);
        snprintf(name, sizeof name, "building_%d_origin", i);
        int origin = turn < 0 ? -1 : add_node(scene, name, turn, -bs[i].x, 0, -bs[i].z, err);
        static const double identity[4] = { 0, 0, 0, 1 };
        ok = origin >= 0 &&
             commit_building(scene, &bs[i], bases[i], i, m_colour[bs[i].colour], m_roof, origin, err) &&
             add_turn(&anim, turn, identity, i % 2 ? -1 : 1, period, err);
    }
    int bridge_node = -1, arch_node = -1;
    if (ok && motion == MOTION_ALL) {
        bridge_node = add_node(scene, "bridge", -1, 0, 0, 0, err);
        arch_node = bridge_node < 0 ? -1 : add_node(scene, "arch", -1, 0, 0, 0, err);
        ok = arch_node >= 0 && add_dip(&anim, bridge_node, -OW_LIFT, period, err) &&
             add_dip(&anim, arch_node, -OW_LIFT, period, err);
    }
    ok = ok && mb_commit(scene, &bridge, "bridge", m_stone, CG_MESH_COMPLEX, bs_identity, err) &&
         (bridge_node < 0 || attach_last(scene, bridge_node, err));
    ok = ok && mb_commit(scene, &arch, "arch", m_stone, CG_MESH_COMPLEX, bs_identity, err) &&
         (arch_node < 0 || attach_last(scene, arch_node, err));
    free(bases);
    for (int c = 0; c < 4; c++)
        mb_free(&walls[c]);
    mb_free(&roofs);
    mb_free(&bridge);
    mb_free(&arch);
    free(bs);
    free(t.height);
    if (!ok) {
        free_animation(&anim);
        return false;
    }

    /* The sun: low enough (37 degrees) for long shadows, from the west-south-west so the
     * shadows fall across the view; irradiance 3 W/m^2 on a surface facing it. */
    cg_light sun = { .type = CG_LIGHT_DIRECTIONAL, .color = { 1.0f, 0.95f, 0.85f }, .intensity = 3.0f,
                     .direction = { 0.72f, -0.60f, -0.35f } };
    bs_normalize3(sun.direction);
    cg_copy_name(sun.name, "sun");
    int light = cg_scene_add_light(scene, &sun, err);
    ok = light >= 0;
    if (ok && motion == MOTION_SUN) {
        /* The sun's node turns -Z (the way a glTF light shines) onto its direction, then about +y. */
        cg_node n = cg_node_default("sun");
        double rest[4];
        bs_quat_from_minus_z(sun.direction, rest);
        for (int c = 0; c < 4; c++)
            n.rotation[c] = (float)rest[c];
        int node = cg_scene_add_node(scene, &n, err);
        ok = node >= 0 && cg_scene_attach(scene, CG_ATTACH_LIGHT, light, node, err) >= 0 &&
             add_turn(&anim, node, rest, 1, period, err);
    }
    /* The camera frames the whole world as at 400 m: every length times k. */
    double eye[3] = { -150 * k, 75 * k, 175 * k }, at[3] = { 0, 0, -20 * k };
    float znear = (float)(0.5 * k), zfar = (float)(1500.0 * k);
    /* The scene owns the channels once added (and frees them itself if adding fails). */
    if (ok && anim.channel_count > 0)
        return cg_scene_add_animation(scene, &anim, err) >= 0 &&
               bs_add_perspective_camera(scene, "overview", eye, at, 0.9f, znear, zfar, err);
    free_animation(&anim);
    if (!ok)
        return false;
    return bs_add_perspective_camera(scene, "overview", eye, at, 0.9f, znear, zfar, err);
}

const cg_builtin_scene cg_builtin_openworld = {
    .name = "openworld",
    .doc = "procedural open world: height-field terrain, buildings, a bridge and an arch, sun, camera; "
    "?triangles=N (5000..8000000, default 200000: the total follows N within 1%)&seed=S "
    "(unsigned integer, default 1)&motion=none|sun|one|all (default none: the sun turns about the vertical, "
    "one building sinks and rises, or every complex object moves)&period=P (seconds, 0.1..100000, default 20: "
    "the animation's length)&size=METRES (100..64000, default 400: the world's side; the terrain and the "
    "town's extent scale with it, buildings keep their size and the town its density)",
    .build = build_openworld,
};
