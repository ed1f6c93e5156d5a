/* builtin:openworld: height-field terrain (most of the triangles), coloured buildings standing on it,
 * a bridge over a valley and a stone arch (space under them: no height field can hold them), a
 * sun and a camera. ?triangles=N&seed=S. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

#define OW_SIZE 400.0        /* terrain side, metres; x and z in [-200, 200] */
#define OW_RELIEF 14.0       /* fbm amplitude, metres */
#define OW_VALLEY_Z 60.0     /* the valley runs along x at this z */
#define OW_VALLEY_DEPTH 16.0
#define OW_VALLEY_WIDTH 16.0
#define OW_BRIDGE_X 20.0
#define OW_ARCH_X -70.0      /* a gate in front of the town, facing the camera */
#define OW_ARCH_Z 24.0

typedef struct terrain {
    uint64_t seed;
    int gx, gz;             /* cells along x and z */
    double dx, dz;          /* cell size */
    float *height;          /* (gx+1) x (gz+1) vertex heights, row-major in z */
} terrain;

static double
terrain_height_analytic(const terrain *t, double x, double z)
{
    double h = OW_RELIEF * bs_fbm(x / 90.0, z / 90.0, t->seed);
    /* Hills rise towards the far edge so the camera sees a skyline. */
    h += 10.0 * (1.0 - z / (OW_SIZE / 2)) * 0.5 - 5.0;
    double dv = (z - OW_VALLEY_Z) / OW_VALLEY_WIDTH;
    return h - OW_VALLEY_DEPTH * exp(-dv * dv);
}

/* Height of the triangulated terrain (not the noise): what the mesh really has at (x, z).
 * Cells split along the diagonal from (i+1, j) to (i, j+1). */
static double
terrain_mesh_height(const terrain *t, double x, double z)
{
    double fx = (x + OW_SIZE / 2) / t->dx, fz = (z + OW_SIZE / 2) / t->dz;
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
                double x = -OW_SIZE / 2 + i * t->dx, z = -OW_SIZE / 2 + j * t->dz;
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

static bool
overlaps(const building *all, int count, double x, double z, double r)
{
    for (int i = 0; i < count; i++) {
        double rx = x - all[i].x, rz = z - all[i].z;
        double ri = sqrt(all[i].hx * all[i].hx + all[i].hz * all[i].hz);
        if (rx * rx + rz * rz < (r + ri + 3) * (r + ri + 3))
            return true;
    }
    return false;
}

/* Triangles of a building: 5 box faces (the buried underside left out); a gable roof
 * adds 2 slopes and 2 gable ends. */
static int
building_triangles(const building *bd)
{
    return 10 + (bd->roof == ROOF_GABLE ? 6 : 0);
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
    double rise = bd->hz * tan(35 * BS_PI / 180);
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

/* A road bridge across the valley along z at x = OW_BRIDGE_X: a deck, two parapets and
 * three piers down into the ground. The deck spans the valley with metres of air below. */
static int
bridge_triangles(void)
{
    return 12 + 2 * 12 + 3 * 10;
}

static void
build_bridge(mesh_builder *b, const terrain *t)
{
    double z0 = OW_VALLEY_Z - 2.6 * OW_VALLEY_WIDTH, z1 = OW_VALLEY_Z + 2.6 * OW_VALLEY_WIDTH;
    double bank = terrain_mesh_height(t, OW_BRIDGE_X, z0);
    double bank1 = terrain_mesh_height(t, OW_BRIDGE_X, z1);
    double deck = (bank > bank1 ? bank : bank1) + 1.0;
    double len = (z1 - z0) * 0.5 + 4;
    double deck_c[3] = { OW_BRIDGE_X, deck, OW_VALLEY_Z }, deck_h[3] = { 4, 0.6, len };
    mb_box(b, deck_c, deck_h, 0, true);
    for (int s = -1; s <= 1; s += 2) {
        double pc[3] = { OW_BRIDGE_X + s * 3.8, deck + 1.1, OW_VALLEY_Z }, ph[3] = { 0.2, 0.5, len };
        mb_box(b, pc, ph, 0, true);
    }
    for (int k = -1; k <= 1; k++) {
        double pz = OW_VALLEY_Z + k * (z1 - z0) * 0.3;
        double ground = terrain_min_under(t, OW_BRIDGE_X - 1.5, pz - 1.5, OW_BRIDGE_X + 1.5, pz + 1.5) - 1.0;
        double top = deck - 0.6;
        double pc[3] = { OW_BRIDGE_X, (ground + top) * 0.5, pz }, ph[3] = { 1.5, (top - ground) * 0.5, 1.5 };
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

static bool
build_openworld(cg_scene *scene, const char *query, cg_error *err)
{
    bs_param p[] = {
        { "triangles", 5000, 8000000, 200000, true, 200000, false },
        { "seed", 0, 18446744073709551615.0, 1, true, 1, false },
    };
    if (!bs_parse_params("openworld", query, p, 2, err))
        return false;
    uint64_t seed = p[1].count; /* exact: a double holds integers only below 2^53 */
    long target = (long)p[0].count;
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
     * more of them in larger scenes: from 12 at 10k triangles to 400 from 1M on. */
    int nb = (int)(target / 2500);
    if (nb < 12) nb = 12;
    if (nb > 400) nb = 400;
    building *bs = calloc((size_t)nb, sizeof *bs);
    if (!bs)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "builtin:openworld: out of memory");
    int placed = 0;
    long other = bridge_triangles() + arch_triangles();
    for (int tries = 0; placed < nb && tries < nb * 50; tries++) {
        building bd;
        /* The town lies south of the valley (z < 20), leaving the valley and the bridge clear. */
        bd.hx = bs_rng_range(&r, 3, 9);
        bd.hz = bs_rng_range(&r, 3, 8);
        bd.x = bs_rng_range(&r, -170, 170);
        bd.z = bs_rng_range(&r, -175, 15);
        bd.yaw = bs_rng_range(&r, -0.4, 0.4);
        bd.height = bs_rng_range(&r, 5, 22); /* above the ground, fixed below */
        bd.colour = (int)(bs_rng_next(&r) % 4);
        bd.roof = bs_rng_next(&r) % 2 ? ROOF_GABLE : ROOF_FLAT;
        double rad = sqrt(bd.hx * bd.hx + bd.hz * bd.hz);
        /* Keep the arch's square free. */
        if (fabs(bd.x - OW_ARCH_X) < 14 + rad && fabs(bd.z - OW_ARCH_Z) < 8 + rad)
            continue;
        if (overlaps(bs, placed, bd.x, bd.z, rad))
            continue;
        bs[placed++] = bd;
        other += building_triangles(&bd);
    }

    /* Terrain grid: gx * gz cells, two triangles each, as close to what is left as the
     * integer grid allows (within 2 * gx triangles). */
    long left = target - other;
    terrain t = { .seed = seed };
    t.gx = (int)lround(sqrt(left / 2.0));
    if (t.gx < 2) t.gx = 2;
    t.gz = (int)lround(left / (2.0 * t.gx));
    if (t.gz < 2) t.gz = 2;
    t.dx = OW_SIZE / t.gx;
    t.dz = OW_SIZE / t.gz;
    t.height = malloc((size_t)(t.gx + 1) * (t.gz + 1) * sizeof(float));
    if (!t.height) {
        free(bs);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "builtin:openworld: out of memory for the terrain");
    }
    for (int j = 0; j <= t.gz; j++)
        for (int i = 0; i <= t.gx; i++)
            t.height[(size_t)j * (t.gx + 1) + i] =
                (float)terrain_height_analytic(&t, -OW_SIZE / 2 + i * t.dx, -OW_SIZE / 2 + j * t.dz);

    bool ok = build_terrain(scene, &t, m_grass, err);
    mesh_builder walls[4] = { { 0 } }, roofs = { 0 }, bridge = { 0 }, arch = { 0 };
    for (int i = 0; i < placed; i++) {
        building *bd = &bs[i];
        double ext = sqrt(bd->hx * bd->hx + bd->hz * bd->hz);
        double base = terrain_min_under(&t, bd->x - ext, bd->z - ext, bd->x + ext, bd->z + ext) - 0.3;
        double ground = terrain_mesh_height(&t, bd->x, bd->z);
        bd->height += ground;
        build_building(&walls[bd->colour], &roofs, bd, base);
    }
    build_bridge(&bridge, &t);
    build_arch(&arch, &t, OW_ARCH_X, OW_ARCH_Z);
    static const char *const wall_names[4] = { "buildings_red", "buildings_blue", "buildings_yellow",
                                               "buildings_white" };
    for (int c = 0; c < 4; c++) {
        if (walls[c].index_count == 0 && !walls[c].failed)
            continue;
        ok = ok && mb_commit(scene, &walls[c], wall_names[c], m_colour[c], CG_MESH_COMPLEX, bs_identity, err);
    }
    ok = ok && mb_commit(scene, &roofs, "roofs", m_roof, CG_MESH_COMPLEX, bs_identity, err);
    ok = ok && mb_commit(scene, &bridge, "bridge", m_stone, CG_MESH_COMPLEX, bs_identity, err);
    ok = ok && mb_commit(scene, &arch, "arch", m_stone, CG_MESH_COMPLEX, bs_identity, err);
    for (int c = 0; c < 4; c++)
        mb_free(&walls[c]);
    mb_free(&roofs);
    mb_free(&bridge);
    mb_free(&arch);
    free(bs);
    free(t.height);
    if (!ok)
        return false;

    /* The sun: low enough (37 degrees) for long shadows, from the west-south-west so the
     * shadows fall across the view; irradiance 3 W/m^2 on a surface facing it. */
    cg_light sun = { .type = CG_LIGHT_DIRECTIONAL, .color = { 1.0f, 0.95f, 0.85f }, .intensity = 3.0f,
                     .direction = { 0.72f, -0.60f, -0.35f } };
    bs_normalize3(sun.direction);
    cg_copy_name(sun.name, "sun");
    if (cg_scene_add_light(scene, &sun, err) < 0)
        return false;
    double eye[3] = { -150, 75, 175 }, at[3] = { 0, 0, -20 };
    return bs_add_perspective_camera(scene, "overview", eye, at, 0.9f, 0.5f, 1500.0f, err);
}

const cg_builtin_scene cg_builtin_openworld = {
    .name = "openworld",
    .doc = "procedural open world: height-field terrain, buildings, a bridge and an arch, sun, camera; "
    "?triangles=N (5000..8000000, default 200000: the total follows N within 1%)&seed=S "
    "(unsigned integer, default 1)",
    .build = build_openworld,
};
