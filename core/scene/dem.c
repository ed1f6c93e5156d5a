/* core/scene/dem.c: a height-field scene from a digital elevation model (DEM) image,
 * "dem:PATH?key=value&..." (docs/scenes.md), with glTF meshes placed on it if asked.
 *
 * The image's samples (channel 0, as stored: a 16-bit PNG gives 0..65535, a float TIFF metres)
 * are the heights of a regular grid: sample (i, j) of the image (row j from the top) is the
 * vertex x = i s - X/2, z = j s - Z/2, y = value * scale + offset, s = spacing * stride (x east,
 * z south: the image's top is north, -z). Two triangles per cell, counter-clockwise seen from
 * above; smooth normals from central differences. The terrain is one mesh, a height field by
 * construction (its kind is set, not classified). A directional sun and an overview camera are
 * added. Meshes of a glTF file (`meshes=FILE`) join the scene: their materials, textures,
 * lights and cameras too, and their kinds are classified by eq. 5 with the rest (or taken from
 * their "conegraph_kind" extras); `place` sets them on the ground.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/image.h"

#include "builtin/builtin_internal.h"
#include "scene_internal.h"

enum { PLACE_NONE, PLACE_SCENE, PLACE_INSTANCES };

typedef struct dem_params {
    double spacing, scale, offset, nodata, albedo, sun, sun_azimuth, sun_elevation;
    long stride;
    bool has_nodata;
    char meshes[1024];
    int place;
} dem_params;

static bool
parse_number(const char *path, const char *key, const char *v, double lo, double hi, double *out, cg_error *err)
{
    char *end = NULL;
    errno = 0;
    double x = strtod(v, &end);
    if (!v[0] || *end || errno || !isfinite(x) || x < lo || x > hi)
        return cg_fail(err, CG_ERR_SCENE_PARAM, "dem:%s: %s=%s: expected a number in [%g, %g]", path, key, v, lo, hi);
    *out = x;
    return true;
}

static bool
parse_params(const char *path, const char *query, dem_params *p, cg_error *err)
{
    *p = (dem_params){ .spacing = 1, .scale = 1, .offset = 0, .albedo = 0.3, .sun = 3, .sun_azimuth = 135,
                       .sun_elevation = 35, .stride = 1, .place = PLACE_NONE };
    static const char *const keys[] = { "spacing", "scale", "offset", "stride", "nodata", "albedo", "sun",
                                        "sun_azimuth", "sun_elevation", "meshes", "place" };
    enum { KEY_COUNT = sizeof keys / sizeof keys[0] };
    bool seen[KEY_COUNT] = { false };
    for (const char *q = query; q && *q;) {
        const char *end = strchr(q, '&');
        size_t len = end ? (size_t)(end - q) : strlen(q);
        char item[1100];
        if (len >= sizeof item)
            return cg_fail(err, CG_ERR_SCENE_PARAM, "dem:%s: parameter '%.40s...' too long", path, q);
        memcpy(item, q, len);
        item[len] = '\0';
        q = end ? end + 1 : q + len;
        char *eq = strchr(item, '=');
        if (!eq)
            return cg_fail(err, CG_ERR_SCENE_PARAM, "dem:%s: parameter '%s' has no '=value'", path, item);
        *eq = '\0';
        const char *v = eq + 1;
        int k = 0;
        while (k < KEY_COUNT && strcmp(item, keys[k]))
            k++;
        if (k == KEY_COUNT)
            return cg_fail(err, CG_ERR_SCENE_PARAM,
                           "dem:%s: unknown parameter '%s' (known: spacing, scale, offset, stride, nodata, albedo, "
                           "sun, sun_azimuth, sun_elevation, meshes, place, and the classification keys)",
                           path, item);
        if (seen[k])
            return cg_fail(err, CG_ERR_SCENE_PARAM, "dem:%s: parameter '%s' given twice", path, item);
        seen[k] = true;
        double x;
        bool ok = true;
        switch (k) {
        case 0: ok = parse_number(path, item, v, 1e-6, 1e7, &p->spacing, err); break;
        case 1: ok = parse_number(path, item, v, -1e7, 1e7, &p->scale, err); break;
        case 2: ok = parse_number(path, item, v, -1e9, 1e9, &p->offset, err); break;
        case 3:
            ok = parse_number(path, item, v, 1, 4096, &x, err) &&
                 (x == floor(x) || cg_fail(err, CG_ERR_SCENE_PARAM, "dem:%s: stride=%s: expected an integer", path, v));
            p->stride = (long)x;
            break;
        case 4: ok = parse_number(path, item, v, -1e30, 1e30, &p->nodata, err); p->has_nodata = true; break;
        case 5: ok = parse_number(path, item, v, 0, 1, &p->albedo, err); break;
        case 6: ok = parse_number(path, item, v, 0, 1e9, &p->sun, err); break;
        case 7: ok = parse_number(path, item, v, -360, 360, &p->sun_azimuth, err); break;
        case 8: ok = parse_number(path, item, v, 0, 90, &p->sun_elevation, err); break;
        case 9:
            if (!v[0] || strlen(v) >= sizeof p->meshes)
                return cg_fail(err, CG_ERR_SCENE_PARAM, "dem:%s: meshes=: expected a .gltf or .glb path", path);
            snprintf(p->meshes, sizeof p->meshes, "%s", v);
            break;
        default:
            if (!strcmp(v, "none")) p->place = PLACE_NONE;
            else if (!strcmp(v, "scene")) p->place = PLACE_SCENE;
            else if (!strcmp(v, "instances")) p->place = PLACE_INSTANCES;
            else return cg_fail(err, CG_ERR_SCENE_PARAM, "dem:%s: place=%s: expected none, scene or instances", path, v);
        }
        if (!ok)
            return false;
    }
    return true;
}

/* The terrain grid, as the mesh has it. */
typedef struct dem_grid {
    int nx, nz;             /* vertices along x and z */
    double step, x0, z0;    /* vertex (i, j) at (x0 + i step, z0 + j step) */
    float *y;               /* nx x nz heights, row-major in z */
} dem_grid;

/* Height of the triangulated terrain at (x, z), clamped to the grid (cells split along the
 * diagonal from (i+1, j) to (i, j+1), as the triangles). */
static double
grid_height(const dem_grid *g, double x, double z)
{
    double fx = (x - g->x0) / g->step, fz = (z - g->z0) / g->step;
    fx = fmin(fmax(fx, 0), g->nx - 1);
    fz = fmin(fmax(fz, 0), g->nz - 1);
    int i = (int)fx, j = (int)fz;
    if (i > g->nx - 2) i = g->nx - 2;
    if (j > g->nz - 2) j = g->nz - 2;
    double u = fx - i, v = fz - j;
    const float *r0 = g->y + (size_t)j * g->nx, *r1 = r0 + g->nx;
    if (u + v <= 1)
        return r0[i] + u * (r0[i + 1] - r0[i]) + v * (r1[i] - r0[i]);
    return r1[i + 1] + (1 - u) * (r1[i] - r1[i + 1]) + (1 - v) * (r0[i + 1] - r1[i + 1]);
}

/* Lowest terrain height under the xz rectangle (vertices inside it and its corners). */
static double
grid_min_under(const dem_grid *g, double x0, double z0, double x1, double z1)
{
    double lo = fmin(fmin(grid_height(g, x0, z0), grid_height(g, x1, z0)),
                     fmin(grid_height(g, x0, z1), grid_height(g, x1, z1)));
    int i0 = (int)ceil((x0 - g->x0) / g->step), i1 = (int)floor((x1 - g->x0) / g->step);
    int j0 = (int)ceil((z0 - g->z0) / g->step), j1 = (int)floor((z1 - g->z0) / g->step);
    for (int j = j0 < 0 ? 0 : j0; j <= j1 && j < g->nz; j++)
        for (int i = i0 < 0 ? 0 : i0; i <= i1 && i < g->nx; i++)
            lo = fmin(lo, g->y[(size_t)j * g->nx + i]);
    return lo;
}

static bool
build_grid(const char *path, const cg_image_samples *s, const dem_params *p, dem_grid *g, cg_error *err)
{
    g->nx = (int)((s->width - 1) / p->stride + 1);
    g->nz = (int)((s->height - 1) / p->stride + 1);
    if (g->nx < 2 || g->nz < 2)
        return cg_fail(err, CG_ERR_SCENE_PARAM, "dem:%s: stride=%ld leaves %dx%d samples of %dx%d: at least 2x2 needed",
                       path, p->stride, g->nx, g->nz, s->width, s->height);
    g->step = p->spacing * (double)p->stride;
    g->x0 = -0.5 * g->step * (g->nx - 1);
    g->z0 = -0.5 * g->step * (g->nz - 1);
    g->y = malloc((size_t)g->nx * g->nz * sizeof(float));
    if (!g->y)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "dem:%s: out of memory for %dx%d heights", path, g->nx, g->nz);
    /* Missing samples (nodata) take the lowest height present, so they read as flat low ground. */
    double lowest = INFINITY;
    for (size_t k = 0; k < (size_t)s->width * s->height; k++)
        if (!(p->has_nodata && s->value[k] == (float)p->nodata) && isfinite(s->value[k]))
            lowest = fmin(lowest, s->value[k]);
    if (!isfinite(lowest))
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "dem:%s: no sample holds a height (all are nodata or not finite)", path);
    for (int j = 0; j < g->nz; j++)
        for (int i = 0; i < g->nx; i++) {
            float v = s->value[(size_t)j * p->stride * s->width + (size_t)i * p->stride];
            if ((p->has_nodata && v == (float)p->nodata) || !isfinite(v))
                v = (float)lowest;
            double y = v * p->scale + p->offset;
            if (!isfinite((float)y))
                return cg_fail(err, CG_ERR_IMAGE_FORMAT, "dem:%s: sample (%d, %d) = %g gives a height beyond a float",
                               path, i * (int)p->stride, j * (int)p->stride, v);
            g->y[(size_t)j * g->nx + i] = (float)y;
        }
    return true;
}

static bool
build_terrain(cg_scene *scene, const dem_grid *g, int material, cg_error *err)
{
    size_t nv = (size_t)g->nx * g->nz, ni = (size_t)(g->nx - 1) * (g->nz - 1) * 6;
    if (ni > 0xFFFFFFFFu || nv > 0xFFFFFFFFu)
        return cg_fail(err, CG_ERR_SCENE_PARAM, "%s: %dx%d samples make more than 2^32 indices (use the stride key)",
                       scene->name, g->nx, g->nz);
    mesh_builder b = { 0 };
    b.positions = malloc(nv * 3 * sizeof(float));
    b.normals = malloc(nv * 3 * sizeof(float));
    b.texcoords = malloc(nv * 2 * sizeof(float));
    b.indices = malloc(ni * sizeof(uint32_t));
    if (!b.positions || !b.normals || !b.texcoords || !b.indices) {
        b.failed = true;
        return mb_commit(scene, &b, "terrain", material, CG_MESH_HEIGHTFIELD, bs_identity, err);
    }
    b.vertex_count = (uint32_t)nv;
    b.index_count = (uint32_t)ni;
    for (int j = 0; j < g->nz; j++)
        for (int i = 0; i < g->nx; i++) {
            size_t v = (size_t)j * g->nx + i;
            b.positions[3 * v + 0] = (float)(g->x0 + i * g->step);
            b.positions[3 * v + 1] = g->y[v];
            b.positions[3 * v + 2] = (float)(g->z0 + j * g->step);
            b.texcoords[2 * v + 0] = (float)(i / (double)(g->nx - 1));
            b.texcoords[2 * v + 1] = (float)(j / (double)(g->nz - 1));
            int i0 = i > 0 ? i - 1 : i, i1 = i < g->nx - 1 ? i + 1 : i;
            int j0 = j > 0 ? j - 1 : j, j1 = j < g->nz - 1 ? j + 1 : j;
            double sx = (g->y[(size_t)j * g->nx + i1] - g->y[(size_t)j * g->nx + i0]) / ((i1 - i0) * g->step);
            double sz = (g->y[(size_t)j1 * g->nx + i] - g->y[(size_t)j0 * g->nx + i]) / ((j1 - j0) * g->step);
            double len = sqrt(sx * sx + 1 + sz * sz);
            b.normals[3 * v + 0] = (float)(-sx / len);
            b.normals[3 * v + 1] = (float)(1 / len);
            b.normals[3 * v + 2] = (float)(-sz / len);
        }
    size_t k = 0;
    for (int j = 0; j + 1 < g->nz; j++)
        for (int i = 0; i + 1 < g->nx; i++) {
            uint32_t v00 = (uint32_t)((size_t)j * g->nx + i), v10 = v00 + 1;
            uint32_t v01 = v00 + (uint32_t)g->nx, v11 = v01 + 1;
            /* Counter-clockwise seen from above (+y): the surface faces up. */
            b.indices[k++] = v00, b.indices[k++] = v01, b.indices[k++] = v10;
            b.indices[k++] = v10, b.indices[k++] = v01, b.indices[k++] = v11;
        }
    return mb_commit(scene, &b, "terrain", material, CG_MESH_HEIGHTFIELD, bs_identity, err);
}

/* World box of instance `inst` of `scene` (its mesh's local box through its transform). */
static void
instance_box(const cg_scene *scene, const cg_instance *inst, double lo[3], double hi[3])
{
    const cg_mesh *m = &scene->meshes[inst->mesh];
    for (int k = 0; k < 3; k++)
        lo[k] = INFINITY, hi[k] = -INFINITY;
    for (int c = 0; c < 8; c++) {
        float p[3] = { (c & 1) ? m->bounds_max[0] : m->bounds_min[0], (c & 2) ? m->bounds_max[1] : m->bounds_min[1],
                       (c & 4) ? m->bounds_max[2] : m->bounds_min[2] };
        for (int r = 0; r < 3; r++) {
            double w = (double)inst->world[r] * p[0] + (double)inst->world[4 + r] * p[1] +
                       (double)inst->world[8 + r] * p[2] + inst->world[12 + r];
            lo[r] = fmin(lo[r], w);
            hi[r] = fmax(hi[r], w);
        }
    }
}

/* Moves what `add` holds (a loaded glTF) into `scene`, emptying `add`: materials (add's default
 * material 0 becomes scene's), textures, meshes with their kind sources, instances, lights and
 * cameras, indices renumbered. */
static bool
merge_scene(cg_scene *scene, cg_scene *add, cg_error *err)
{
    int tex0 = scene->texture_count, mat0 = scene->material_count - 1, mesh0 = scene->mesh_count;
    for (int i = 0; i < add->texture_count; i++) {
        if (cg_scene_add_texture(scene, &add->textures[i], err) < 0)
            return false;
        add->textures[i].rgba = NULL;
    }
    for (int i = 1; i < add->material_count; i++) {
        cg_material m = add->materials[i];
        if (m.base_color_texture >= 0) m.base_color_texture += tex0;
        if (m.emissive_texture >= 0) m.emissive_texture += tex0;
        if (m.metallic_roughness_texture >= 0) m.metallic_roughness_texture += tex0;
        if (m.normal_texture >= 0) m.normal_texture += tex0;
        if (m.occlusion_texture >= 0) m.occlusion_texture += tex0;
        if (m.transmission_texture >= 0) m.transmission_texture += tex0;
        if (cg_scene_add_material(scene, &m, err) < 0)
            return false;
    }
    for (int i = 0; i < add->mesh_count; i++) {
        cg_mesh m = add->meshes[i];
        if (m.material > 0)
            m.material += mat0;
        int index = cg_scene_add_mesh(scene, &m, err);
        if (index < 0)
            return false;
        memset(&add->meshes[i], 0, sizeof add->meshes[i]);
        cg_kind_source source = i < add->mesh_class_count ? add->mesh_class[i].source : CG_KIND_CLASSIFIED;
        if (!cg_scene_set_kind_source(scene, index, source, err))
            return false;
    }
    for (int i = 0; i < add->instance_count; i++)
        if (cg_scene_add_instance(scene, add->instances[i].mesh + mesh0, add->instances[i].world, err) < 0)
            return false;
    for (int i = 0; i < add->light_count; i++)
        if (cg_scene_add_light(scene, &add->lights[i], err) < 0)
            return false;
    for (int i = 0; i < add->camera_count; i++)
        if (cg_scene_add_camera(scene, &add->cameras[i], err) < 0)
            return false;
    return true;
}

/* `place`: the instances from `first` on are moved up or down so that the bottom of their box
 * (each one's, or all of them together) lies on the lowest terrain under it. */
static void
place_on_ground(cg_scene *scene, int first, int place, const dem_grid *g)
{
    if (place == PLACE_NONE || first >= scene->instance_count)
        return;
    double all_lo[3] = { INFINITY, INFINITY, INFINITY }, all_hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int i = first; i < scene->instance_count; i++) {
        double lo[3], hi[3];
        instance_box(scene, &scene->instances[i], lo, hi);
        if (place == PLACE_INSTANCES) {
            scene->instances[i].world[13] += (float)(grid_min_under(g, lo[0], lo[2], hi[0], hi[2]) - lo[1]);
            continue;
        }
        for (int k = 0; k < 3; k++)
            all_lo[k] = fmin(all_lo[k], lo[k]), all_hi[k] = fmax(all_hi[k], hi[k]);
    }
    if (place == PLACE_SCENE) {
        double dy = grid_min_under(g, all_lo[0], all_lo[2], all_hi[0], all_hi[2]) - all_lo[1];
        for (int i = first; i < scene->instance_count; i++)
            scene->instances[i].world[13] += (float)dy;
    }
}

static bool
add_sun_and_camera(cg_scene *scene, const dem_params *p, const dem_grid *g, cg_error *err)
{
    if (p->sun > 0) {
        /* Azimuth from north (-z) towards east (+x); the light travels away from the sun. */
        double az = p->sun_azimuth * BS_PI / 180, el = p->sun_elevation * BS_PI / 180;
        cg_light sun = { .type = CG_LIGHT_DIRECTIONAL, .color = { 1.0f, 0.95f, 0.85f }, .intensity = (float)p->sun };
        sun.direction[0] = (float)(-cos(el) * sin(az));
        sun.direction[1] = (float)(-sin(el));
        sun.direction[2] = (float)(cos(el) * cos(az));
        cg_copy_name(sun.name, "sun");
        if (cg_scene_add_light(scene, &sun, err) < 0)
            return false;
    }
    double lo = INFINITY, hi = -INFINITY, sum = 0;
    for (size_t k = 0; k < (size_t)g->nx * g->nz; k++)
        lo = fmin(lo, g->y[k]), hi = fmax(hi, g->y[k]), sum += g->y[k];
    double sx = g->step * (g->nx - 1), sz = g->step * (g->nz - 1), side = fmax(sx, sz);
    double mean = sum / ((double)g->nx * g->nz);
    /* From the south-west, above the highest point, looking at the middle (as builtin:openworld). */
    double eye[3] = { -0.375 * side, hi + 0.19 * side, 0.44 * side }, at[3] = { 0, mean, -0.05 * side };
    double reach = 2.5 * side + (hi - lo);
    return bs_add_perspective_camera(scene, "overview", eye, at, 0.9f, (float)(1.25e-3 * reach), (float)reach, err);
}

bool
cg_dem_load(const char *path, const char *query, cg_scene *out, cg_error *err)
{
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "dem:%s", path);
    dem_params p;
    if (!parse_params(path, query, &p, err))
        return false;
    /* 2^28 samples are read as doubles (2 GiB) before they are reduced to floats. */
    cg_image_samples s;
    if (!cg_image_read_samples(path, 1ll << 28, &s, err))
        return false;
    dem_grid g = { 0 };
    bool ok = build_grid(path, &s, &p, &g, err);
    cg_image_samples_free(&s);
    cg_material white = cg_material_default("default");
    ok = ok && cg_scene_add_material(out, &white, err) >= 0;
    int ground = ok ? bs_add_material(out, "terrain", (float)p.albedo, (float)p.albedo, (float)p.albedo, err) : -1;
    ok = ok && ground >= 0 && build_terrain(out, &g, ground, err) && cg_scene_set_kind_source(out, 0, CG_KIND_SCENE, err);
    ok = ok && add_sun_and_camera(out, &p, &g, err);
    if (ok && p.meshes[0]) {
        cg_scene add;
        int first = out->instance_count;
        ok = cg_gltf_load(p.meshes, &add, NULL, err);
        if (ok) {
            ok = merge_scene(out, &add, err);
            cg_scene_free(&add);
        }
        if (ok)
            place_on_ground(out, first, p.place, &g);
    }
    free(g.y);
    if (!ok)
        cg_scene_free(out);
    return ok;
}
