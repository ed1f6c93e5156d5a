/* core/src/builtin_scenes.c: the procedural built-in scenes ("builtin:NAME?key=value&...").
 *
 * Every scene is a pure function of its parameters: a private splitmix64 generator and
 * integer-lattice value noise, no global state, so the same seed gives a bit-identical scene.
 *
 *   openworld  height-field terrain (most of the triangles), coloured buildings standing on it,
 *              a bridge over a valley and a stone arch (space under them: no height field can
 *              hold them), a sun and a camera. ?triangles=N&seed=S.
 *   cornell    a 1 m Cornell box, open at +z, lit by a spot light under the ceiling
 *              pointing down (a perspective shadow map covers its cone).
 *   furnace    a closed box, normals inward, uniform albedo and emitted radiance, camera inside.
 *              ?scale=S&albedo=A&radiance=L.
 */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/scene.h"
#include "scene_internal.h"

#define PI 3.14159265358979323846

static const char *const builtin_names[] = { "openworld", "cornell", "furnace", NULL };

static const char *const builtin_docs[] = {
    "procedural open world: height-field terrain, buildings, a bridge and an arch, sun, camera; "
    "?triangles=N (5000..8000000, default 200000: the total follows N within 1%)&seed=S "
    "(unsigned integer, default 1)",
    "Cornell box, 1 m, red left and green right walls, two white blocks, open front, spot light "
    "under the ceiling pointing down; no parameters",
    "closed box with inward normals for energy tests: every surface has albedo A and emits "
    "radiance L, camera at the centre; ?scale=S (metres, 1e-6..1e7, default 1)&albedo=A "
    "(0..1, default 0.5)&radiance=L (0..1e6, default 1)",
};

const char *const *
cg_scene_builtin_names(void)
{
    return builtin_names;
}

const char *
cg_scene_builtin_doc(const char *name)
{
    for (int i = 0; builtin_names[i]; i++)
        if (name && !strcmp(name, builtin_names[i]))
            return builtin_docs[i];
    return NULL;
}

/* ---------------------------------------------------------------- parameters */

typedef struct param_spec {
    const char *key;
    double min, max, value; /* value: the default, replaced by the query's */
    bool integer;           /* then `count` holds the exact value too */
    uint64_t count;
    bool seen;
} param_spec;

static bool
parse_params(const char *scene, const char *query, param_spec *specs, int count, cg_error *err)
{
    if (!query || !query[0])
        return true;
    const char *p = query;
    while (*p) {
        const char *end = strchr(p, '&');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        char item[128];
        if (len == 0 || len >= sizeof item)
            return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: malformed parameter list '%s'",
                           scene, query);
        memcpy(item, p, len);
        item[len] = '\0';
        char *eq = strchr(item, '=');
        if (!eq)
            return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: parameter '%s' has no '=value'",
                           scene, item);
        *eq = '\0';
        const char *value = eq + 1;
        param_spec *spec = NULL;
        for (int i = 0; i < count; i++)
            if (!strcmp(item, specs[i].key))
                spec = &specs[i];
        if (!spec) {
            char known[256] = "";
            for (int i = 0; i < count; i++)
                snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s",
                         i ? ", " : "", specs[i].key);
            return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: unknown parameter '%s' (known: %s)",
                           scene, item, count ? known : "none");
        }
        if (spec->seen)
            return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: parameter '%s' given twice", scene,
                           item);
        spec->seen = true;
        char *rest = NULL;
        errno = 0;
        double v;
        if (spec->integer) {
            if (value[0] == '-' || value[0] == '+')
                return cg_fail(err, CG_ERR_SCENE_PARAM,
                               "builtin:%s: %s=%s: expected an unsigned integer", scene, item, value);
            spec->count = strtoull(value, &rest, 10);
            v = (double)spec->count;
        } else {
            v = strtod(value, &rest);
        }
        if (!value[0] || *rest || errno || !isfinite(v))
            return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: %s=%s: expected %s", scene, item,
                           value, spec->integer ? "an unsigned integer" : "a number");
        if (v < spec->min || v > spec->max)
            return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: %s=%s out of range [%g, %g]",
                           scene, item, value, spec->min, spec->max);
        spec->value = v;
        if (!end)
            break;
        p = end + 1;
    }
    return true;
}

/* ---------------------------------------------------------------- random numbers and noise */

/* splitmix64 (Steele, Lea, Flood 2014): tiny, full period, good enough for placement. */
typedef struct rng {
    uint64_t state;
} rng;

static uint64_t
mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static uint64_t
rng_next(rng *r)
{
    return mix64(r->state += 0x9E3779B97F4A7C15ull);
}

/* Uniform in [lo, hi). */
static double
rng_range(rng *r, double lo, double hi)
{
    return lo + (hi - lo) * (double)(rng_next(r) >> 11) * 0x1.0p-53;
}

static double
lattice(int64_t ix, int64_t iz, uint64_t seed)
{
    uint64_t h = mix64(seed ^ mix64((uint64_t)ix * 0x9E3779B97F4A7C15ull ^ (uint64_t)iz));
    return (double)(h >> 11) * 0x1.0p-53;
}

static double
quintic(double t)
{
    return t * t * t * (t * (t * 6 - 15) + 10);
}

/* Value noise in [0, 1): smooth interpolation of random values on the integer lattice. */
static double
value_noise(double x, double z, uint64_t seed)
{
    double fx = floor(x), fz = floor(z);
    int64_t ix = (int64_t)fx, iz = (int64_t)fz;
    double u = quintic(x - fx), v = quintic(z - fz);
    double a = lattice(ix, iz, seed), b = lattice(ix + 1, iz, seed);
    double c = lattice(ix, iz + 1, seed), d = lattice(ix + 1, iz + 1, seed);
    return (a + (b - a) * u) + ((c + (d - c) * u) - (a + (b - a) * u)) * v;
}

/* Fractal Brownian motion: 5 octaves, each half the amplitude and twice the frequency;
 * the result is centred on 0 and lies in about [-1, 1]. */
static double
fbm(double x, double z, uint64_t seed)
{
    double sum = 0, amp = 1, norm = 0;
    for (int o = 0; o < 5; o++) {
        sum += amp * (2 * value_noise(x, z, seed + (uint64_t)o * 7919) - 1);
        norm += amp;
        amp *= 0.5;
        x = x * 2.03 + 17.1;
        z = z * 2.03 - 5.3;
    }
    return sum / norm;
}

/* ---------------------------------------------------------------- mesh building */

typedef struct mesh_builder {
    float *positions, *normals, *texcoords;
    uint32_t *indices;
    uint32_t vertex_count, vertex_cap, index_count, index_cap;
    bool failed;
} mesh_builder;

static bool
grow(void **p, uint32_t *cap, uint32_t need, size_t elem)
{
    if (need <= *cap)
        return true;
    uint32_t c = *cap ? *cap : 64;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, (size_t)c * elem);
    if (!q)
        return false;
    *p = q;
    *cap = c;
    return true;
}

static uint32_t
mb_vertex(mesh_builder *b, const double p[3], const double n[3])
{
    uint32_t cap = b->vertex_cap;
    if (!grow((void **)&b->positions, &cap, b->vertex_count + 1, 3 * sizeof(float)) ||
        (cap = b->vertex_cap, !grow((void **)&b->normals, &cap, b->vertex_count + 1, 3 * sizeof(float)))) {
        b->failed = true;
        return 0;
    }
    b->vertex_cap = cap;
    for (int k = 0; k < 3; k++) {
        b->positions[3 * b->vertex_count + k] = (float)p[k];
        b->normals[3 * b->vertex_count + k] = (float)n[k];
    }
    return b->vertex_count++;
}

static void
mb_triangle(mesh_builder *b, uint32_t i0, uint32_t i1, uint32_t i2)
{
    if (!grow((void **)&b->indices, &b->index_cap, b->index_count + 3, sizeof(uint32_t))) {
        b->failed = true;
        return;
    }
    b->indices[b->index_count++] = i0;
    b->indices[b->index_count++] = i1;
    b->indices[b->index_count++] = i2;
}

static void
face_normal(const double a[3], const double b[3], const double c[3], double n[3])
{
    double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    double e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        n[k] = len > 0 ? n[k] / len : (k == 1);
}

/* A flat triangle, counter-clockwise seen from the side its normal points to. */
static void
mb_flat_triangle(mesh_builder *b, const double p0[3], const double p1[3], const double p2[3])
{
    double n[3];
    face_normal(p0, p1, p2, n);
    uint32_t i0 = mb_vertex(b, p0, n), i1 = mb_vertex(b, p1, n), i2 = mb_vertex(b, p2, n);
    mb_triangle(b, i0, i1, i2);
}

/* A flat quad p0 p1 p2 p3, counter-clockwise seen from its front. */
static void
mb_quad(mesh_builder *b, const double p0[3], const double p1[3], const double p2[3], const double p3[3])
{
    double n[3];
    face_normal(p0, p1, p2, n);
    uint32_t i0 = mb_vertex(b, p0, n), i1 = mb_vertex(b, p1, n);
    uint32_t i2 = mb_vertex(b, p2, n), i3 = mb_vertex(b, p3, n);
    mb_triangle(b, i0, i1, i2);
    mb_triangle(b, i0, i2, i3);
}

/* An oriented box: centre c, half extents h along the axes rotated by `yaw` about +y.
 * Faces point outwards; `bottom` adds the underside (left out where it is buried). */
static void
mb_box(mesh_builder *b, const double c[3], const double h[3], double yaw, bool bottom)
{
    double cs = cos(yaw), sn = sin(yaw);
    double v[8][3];
    for (int i = 0; i < 8; i++) {
        double lx = (i & 1) ? h[0] : -h[0], ly = (i & 2) ? h[1] : -h[1], lz = (i & 4) ? h[2] : -h[2];
        v[i][0] = c[0] + cs * lx + sn * lz;
        v[i][1] = c[1] + ly;
        v[i][2] = c[2] - sn * lx + cs * lz;
    }
    mb_quad(b, v[4], v[5], v[7], v[6]); /* +z */
    mb_quad(b, v[1], v[0], v[2], v[3]); /* -z */
    mb_quad(b, v[5], v[1], v[3], v[7]); /* +x */
    mb_quad(b, v[0], v[4], v[6], v[2]); /* -x */
    mb_quad(b, v[2], v[6], v[7], v[3]); /* +y */
    if (bottom)
        mb_quad(b, v[0], v[1], v[5], v[4]); /* -y */
}

static void
mb_free(mesh_builder *b)
{
    free(b->positions);
    free(b->normals);
    free(b->texcoords);
    free(b->indices);
    memset(b, 0, sizeof *b);
}

static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };

/* Moves the builder's arrays into a new mesh with one instance at `world`. */
static bool
mb_commit(cg_scene *scene, mesh_builder *b, const char *name, int material, cg_mesh_kind kind,
          const float world[16], cg_error *err)
{
    if (b->failed) {
        mb_free(b);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory building mesh '%s'",
                       scene->name, name);
    }
    cg_mesh m = {
        .vertex_count = b->vertex_count,
        .index_count = b->index_count,
        .positions = b->positions,
        .normals = b->normals,
        .texcoords = b->texcoords,
        .indices = b->indices,
        .material = material,
        .kind = kind,
    };
    cg_copy_name(m.name, name);
    cg_mesh_compute_bounds(&m);
    memset(b, 0, sizeof *b);
    int index = cg_scene_add_mesh(scene, &m, err);
    if (index < 0) {
        free(m.positions);
        free(m.normals);
        free(m.texcoords);
        free(m.indices);
        return false;
    }
    return cg_scene_add_instance(scene, index, world, err) >= 0;
}

static int
add_material(cg_scene *scene, const char *name, float r, float g, float b, cg_error *err)
{
    cg_material m = cg_material_default(name);
    m.base_color[0] = r;
    m.base_color[1] = g;
    m.base_color[2] = b;
    return cg_scene_add_material(scene, &m, err);
}

/* Camera-to-world matrix of a camera at `eye` looking at `target` with +y up (glTF: the
 * camera looks down its local -z, +x right, +y up). */
static void
look_at_world(const double eye[3], const double target[3], float world[16])
{
    double f[3] = { target[0] - eye[0], target[1] - eye[1], target[2] - eye[2] };
    double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int k = 0; k < 3; k++)
        f[k] /= fl;
    double r[3] = { -f[2], 0, f[0] }; /* f x (0,1,0) */
    double rl = sqrt(r[0] * r[0] + r[2] * r[2]);
    r[0] /= rl;
    r[2] /= rl;
    double u[3] = { r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0] };
    float m[16] = { (float)r[0], (float)r[1], (float)r[2], 0,
                    (float)u[0], (float)u[1], (float)u[2], 0,
                    (float)-f[0], (float)-f[1], (float)-f[2], 0,
                    (float)eye[0], (float)eye[1], (float)eye[2], 1 };
    memcpy(world, m, sizeof m);
}

static bool
add_perspective_camera(cg_scene *scene, const char *name, const double eye[3], const double target[3],
                       float yfov, float znear, float zfar, cg_error *err)
{
    cg_camera cam = { .type = CG_CAMERA_PERSPECTIVE, .yfov = yfov, .aspect = 0,
                      .znear = znear, .zfar = zfar };
    cg_copy_name(cam.name, name);
    look_at_world(eye, target, cam.world);
    return cg_scene_add_camera(scene, &cam, err) >= 0;
}

static void
normalize3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
}

/* ---------------------------------------------------------------- openworld */

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
    double h = OW_RELIEF * fbm(x / 90.0, z / 90.0, t->seed);
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
    return mb_commit(scene, &b, "terrain", material, CG_MESH_HEIGHTFIELD, identity, err);
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
    double rise = bd->hz * tan(35 * PI / 180);
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
        double a0 = PI * k / ARCH_SEGMENTS, a1 = PI * (k + 1) / ARCH_SEGMENTS;
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
    param_spec p[] = {
        { "triangles", 5000, 8000000, 200000, true, 200000, false },
        { "seed", 0, 18446744073709551615.0, 1, true, 1, false },
    };
    if (!parse_params("openworld", query, p, 2, err))
        return false;
    uint64_t seed = p[1].count; /* exact: a double holds integers only below 2^53 */
    long target = (long)p[0].count;
    rng r = { mix64(seed ^ 0x6F70656E776F726Cull) };

    int m_grass = add_material(scene, "grass", 0.30f, 0.42f, 0.20f, err);
    int m_colour[4] = {
        add_material(scene, "wall_red", 0.75f, 0.12f, 0.08f, err),
        add_material(scene, "wall_blue", 0.12f, 0.25f, 0.75f, err),
        add_material(scene, "wall_yellow", 0.85f, 0.70f, 0.15f, err),
        add_material(scene, "wall_white", 0.80f, 0.80f, 0.78f, err),
    };
    int m_roof = add_material(scene, "roof_tiles", 0.55f, 0.22f, 0.12f, err);
    int m_stone = add_material(scene, "stone", 0.55f, 0.53f, 0.50f, err);
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
        bd.hx = rng_range(&r, 3, 9);
        bd.hz = rng_range(&r, 3, 8);
        bd.x = rng_range(&r, -170, 170);
        bd.z = rng_range(&r, -175, 15);
        bd.yaw = rng_range(&r, -0.4, 0.4);
        bd.height = rng_range(&r, 5, 22); /* above the ground, fixed below */
        bd.colour = (int)(rng_next(&r) % 4);
        bd.roof = rng_next(&r) % 2 ? ROOF_GABLE : ROOF_FLAT;
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
        ok = ok && mb_commit(scene, &walls[c], wall_names[c], m_colour[c], CG_MESH_COMPLEX, identity, err);
    }
    ok = ok && mb_commit(scene, &roofs, "roofs", m_roof, CG_MESH_COMPLEX, identity, err);
    ok = ok && mb_commit(scene, &bridge, "bridge", m_stone, CG_MESH_COMPLEX, identity, err);
    ok = ok && mb_commit(scene, &arch, "arch", m_stone, CG_MESH_COMPLEX, identity, err);
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
    normalize3(sun.direction);
    cg_copy_name(sun.name, "sun");
    if (cg_scene_add_light(scene, &sun, err) < 0)
        return false;
    double eye[3] = { -150, 75, 175 }, at[3] = { 0, 0, -20 };
    return add_perspective_camera(scene, "overview", eye, at, 0.9f, 0.5f, 1500.0f, err);
}

/* ---------------------------------------------------------------- cornell */

/* A unit cube [-0.5, 0.5]^3 with outward faces, placed by instance transforms. */
static void
unit_cube(mesh_builder *b)
{
    double c[3] = { 0, 0, 0 }, h[3] = { 0.5, 0.5, 0.5 };
    mb_box(b, c, h, 0, true);
}

static void
trs_matrix(double tx, double ty, double tz, double yaw, double sx, double sy, double sz, float m[16])
{
    double c = cos(yaw), s = sin(yaw);
    float out[16] = { (float)(c * sx), 0, (float)(-s * sx), 0,
                      0, (float)sy, 0, 0,
                      (float)(s * sz), 0, (float)(c * sz), 0,
                      (float)tx, (float)ty, (float)tz, 1 };
    memcpy(m, out, sizeof out);
}

static bool
build_cornell(cg_scene *scene, const char *query, cg_error *err)
{
    if (!parse_params("cornell", query, NULL, 0, err))
        return false;
    int white = add_material(scene, "white", 0.73f, 0.73f, 0.73f, err);
    int red = add_material(scene, "red", 0.63f, 0.065f, 0.05f, err);
    int green = add_material(scene, "green", 0.14f, 0.45f, 0.091f, err);
    if (white < 0 || red < 0 || green < 0)
        return false;
    /* Box x in [-0.5, 0.5], y in [0, 1], z in [-0.5, 0.5], open at z = +0.5; faces point in. */
    double p[8][3];
    for (int i = 0; i < 8; i++) {
        p[i][0] = (i & 1) ? 0.5 : -0.5;
        p[i][1] = (i & 2) ? 1.0 : 0.0;
        p[i][2] = (i & 4) ? 0.5 : -0.5;
    }
    mesh_builder shell = { 0 }, left = { 0 }, right = { 0 }, cube = { 0 };
    mb_quad(&shell, p[0], p[4], p[5], p[1]); /* floor, +y */
    mb_quad(&shell, p[2], p[3], p[7], p[6]); /* ceiling, -y */
    mb_quad(&shell, p[0], p[1], p[3], p[2]); /* back, +z */
    mb_quad(&left, p[0], p[2], p[6], p[4]);  /* left, +x */
    mb_quad(&right, p[1], p[5], p[7], p[3]); /* right, -x */
    unit_cube(&cube);
    /* The two blocks are one unit cube placed twice by instance transforms (scaled, turned). */
    float tall[16], low[16];
    trs_matrix(-0.17, 0.30, -0.15, 0.30, 0.28, 0.60, 0.28, tall);
    trs_matrix(0.18, 0.15, 0.14, -0.30, 0.28, 0.30, 0.28, low);
    bool ok = mb_commit(scene, &shell, "white_walls", white, CG_MESH_COMPLEX, identity, err) &&
              mb_commit(scene, &left, "left_wall", red, CG_MESH_COMPLEX, identity, err) &&
              mb_commit(scene, &right, "right_wall", green, CG_MESH_COMPLEX, identity, err) &&
              mb_commit(scene, &cube, "block", white, CG_MESH_COMPLEX, tall, err) &&
              cg_scene_add_instance(scene, scene->mesh_count - 1, low, err) >= 0;
    mb_free(&shell);
    mb_free(&left);
    mb_free(&right);
    mb_free(&cube);
    if (!ok)
        return false;

    /* The light: a spot 3 cm under the ceiling pointing straight down. Its 60-degree outer
     * cone fits one perspective shadow map (120-degree field of view). Intensity 2 W/sr
     * gives E = 2 / 0.97^2 = 2.1 W/m^2 at the centre of the floor. */
    cg_light spot = { .type = CG_LIGHT_SPOT, .color = { 1, 1, 1 }, .intensity = 2.0f,
                      .position = { 0, 0.97f, 0 }, .direction = { 0, -1, 0 },
                      .inner_cone_angle = 0.75f, .outer_cone_angle = (float)(PI / 3) };
    cg_copy_name(spot.name, "ceiling_spot");
    if (cg_scene_add_light(scene, &spot, err) < 0)
        return false;
    double eye[3] = { 0, 0.5, 1.85 }, at[3] = { 0, 0.5, 0 };
    return add_perspective_camera(scene, "front", eye, at, 0.70f, 0.05f, 5.0f, err);
}

/* ---------------------------------------------------------------- furnace */

static bool
build_furnace(cg_scene *scene, const char *query, cg_error *err)
{
    param_spec p[] = {
        { "scale", 1e-6, 1e7, 1, false, 0, false },
        { "albedo", 0, 1, 0.5, false, 0, false },
        { "radiance", 0, 1e6, 1, false, 0, false },
    };
    if (!parse_params("furnace", query, p, 3, err))
        return false;
    if (!(p[0].value > 0))
        return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:furnace: scale must be > 0");
    double s = p[0].value * 0.5;
    float a = (float)p[1].value;
    cg_material m = cg_material_default("furnace");
    m.base_color[0] = m.base_color[1] = m.base_color[2] = a;
    /* glTF keeps emissiveFactor in [0, 1]: the radiance goes in the strength. */
    m.emissive[0] = m.emissive[1] = m.emissive[2] = 1;
    m.emissive_strength = (float)p[2].value;
    int mat = cg_scene_add_material(scene, &m, err);
    if (mat < 0)
        return false;
    double v[8][3];
    for (int i = 0; i < 8; i++) {
        v[i][0] = (i & 1) ? s : -s;
        v[i][1] = (i & 2) ? s : -s;
        v[i][2] = (i & 4) ? s : -s;
    }
    mesh_builder b = { 0 };
    /* The faces of mb_box, wound the other way round: normals point into the box. */
    mb_quad(&b, v[4], v[6], v[7], v[5]); /* z = +s, facing -z */
    mb_quad(&b, v[1], v[3], v[2], v[0]); /* z = -s, facing +z */
    mb_quad(&b, v[5], v[7], v[3], v[1]); /* x = +s, facing -x */
    mb_quad(&b, v[0], v[2], v[6], v[4]); /* x = -s, facing +x */
    mb_quad(&b, v[2], v[3], v[7], v[6]); /* y = +s, facing -y */
    mb_quad(&b, v[0], v[4], v[5], v[1]); /* y = -s, facing +y */
    if (!mb_commit(scene, &b, "furnace_box", mat, CG_MESH_COMPLEX, identity, err))
        return false;
    double eye[3] = { 0, 0, 0 }, at[3] = { 0, 0, -s };
    return add_perspective_camera(scene, "inside", eye, at, 1.2f, (float)(s * 1e-2), (float)(s * 4), err);
}

/* ---------------------------------------------------------------- dispatch */

bool
cg_builtin_scene_load(const char *name, const char *query, cg_scene *out, cg_error *err)
{
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "builtin:%s", name);
    cg_material white = cg_material_default("default");
    if (cg_scene_add_material(out, &white, err) < 0)
        return false;
    bool ok;
    if (!strcmp(name, "openworld"))
        ok = build_openworld(out, query, err);
    else if (!strcmp(name, "cornell"))
        ok = build_cornell(out, query, err);
    else if (!strcmp(name, "furnace"))
        ok = build_furnace(out, query, err);
    else {
        char known[256] = "";
        for (int i = 0; builtin_names[i]; i++)
            snprintf(known + strlen(known), sizeof known - strlen(known), "%sbuiltin:%s",
                     i ? ", " : "", builtin_names[i]);
        ok = cg_fail(err, CG_ERR_SCENE_UNKNOWN, "builtin:%s: unknown built-in scene (known: %s)",
                     name, known);
    }
    if (!ok)
        cg_scene_free(out);
    return ok;
}
