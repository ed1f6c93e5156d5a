/* bench: the path-traced reference of each scene (cached on disk) and the path tracer's own
 * error against its sample count, through cg/pt_render.h: see bench.h. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "app_common.h"
#include "bench.h"
#include "cg/fs.h"

static uint64_t
fnv1a_bytes(uint64_t h, const void *data, size_t size)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < size; i++) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

uint64_t
bench_hash_text(const char *text)
{
    return fnv1a_bytes(0xcbf29ce484222325ull, text, strlen(text));
}

/* A hash of everything the path tracer reads from a scene, so that a cached reference is
 * never reused for a scene that changed under the same name (built-in scenes change with
 * the code that builds them; files can be rewritten). */
static uint64_t
scene_hash(const cg_scene *s)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (int i = 0; i < s->mesh_count; i++) {
        const cg_mesh *m = &s->meshes[i];
        h = fnv1a_bytes(h, &m->material, sizeof m->material);
        h = fnv1a_bytes(h, m->positions, sizeof(float) * 3 * m->vertex_count);
        h = fnv1a_bytes(h, m->normals, sizeof(float) * 3 * m->vertex_count);
        if (m->texcoords)
            h = fnv1a_bytes(h, m->texcoords, sizeof(float) * 2 * m->vertex_count);
        h = fnv1a_bytes(h, m->indices, sizeof(uint32_t) * m->index_count);
    }
    for (int i = 0; i < s->instance_count; i++) {
        h = fnv1a_bytes(h, &s->instances[i].mesh, sizeof s->instances[i].mesh);
        h = fnv1a_bytes(h, s->instances[i].world, sizeof s->instances[i].world);
    }
    for (int i = 0; i < s->material_count; i++) {
        const cg_material *m = &s->materials[i];
        h = fnv1a_bytes(h, m->base_color, sizeof m->base_color);
        h = fnv1a_bytes(h, &m->base_color_texture, sizeof m->base_color_texture);
        h = fnv1a_bytes(h, m->emissive, sizeof m->emissive);
        h = fnv1a_bytes(h, &m->emissive_texture, sizeof m->emissive_texture);
        h = fnv1a_bytes(h, &m->emissive_strength, sizeof m->emissive_strength);
    }
    for (int i = 0; i < s->texture_count; i++) {
        const cg_texture *t = &s->textures[i];
        h = fnv1a_bytes(h, &t->width, sizeof t->width);
        h = fnv1a_bytes(h, &t->height, sizeof t->height);
        h = fnv1a_bytes(h, &t->srgb, sizeof t->srgb);
        h = fnv1a_bytes(h, t->rgba, (size_t)t->width * (size_t)t->height * 4);
    }
    for (int i = 0; i < s->light_count; i++) {
        const cg_light *l = &s->lights[i];
        h = fnv1a_bytes(h, &l->type, sizeof l->type);
        h = fnv1a_bytes(h, l->color, sizeof l->color);
        h = fnv1a_bytes(h, &l->intensity, sizeof l->intensity);
        h = fnv1a_bytes(h, l->position, sizeof l->position);
        h = fnv1a_bytes(h, l->direction, sizeof l->direction);
        h = fnv1a_bytes(h, &l->range, sizeof l->range);
        h = fnv1a_bytes(h, &l->inner_cone_angle, sizeof l->inner_cone_angle);
        h = fnv1a_bytes(h, &l->outer_cone_angle, sizeof l->outer_cone_angle);
    }
    /* The sky lights the scene and is seen where no surface is (a Preetham sky follows the
     * first directional light, hashed above). The default light is a light and a sky. */
    h = fnv1a_bytes(h, &s->sky.type, sizeof s->sky.type);
    h = fnv1a_bytes(h, s->sky.radiance, sizeof s->sky.radiance);
    h = fnv1a_bytes(h, &s->sky.turbidity, sizeof s->sky.turbidity);
    h = fnv1a_bytes(h, &s->sky.scale, sizeof s->sky.scale);
    return h;
}

/* The cache file of one image of the reference for (scene, camera, size, spp, bounces, seed):
 * `part` "full" or a pt_part_name. Files are keyed by a hash of all of these, the scene by its
 * contents (lights and sky included), the camera by the view's matrices. */
static void
cache_entry(const bench_config *c, const bench_scene *bs, const char *part, char *key, size_t key_size, char *path,
            size_t path_size)
{
    const cg_view *view = &bs->session.frame.view;
    uint64_t view_hash = fnv1a_bytes(0xcbf29ce484222325ull, view->inv_view_proj, sizeof view->inv_view_proj);
    snprintf(key, key_size,
             "conegraph-reference-v3|pt %d|%s|scene %016llx|view %016llx|%dx%d|spp %d|bounces %d %d %d|caustics %d|"
             "seed %d|%s",
             PT_RENDER_VERSION, bs->source, (unsigned long long)scene_hash(&bs->session.scene),
             (unsigned long long)view_hash, c->width, c->height, c->ref_spp, c->ref_bounces, c->ref_glossy_bounces,
             c->ref_transmission_bounces, (int)c->ref_caustics, c->ref_seed, part);
    snprintf(path, path_size, "%s/ref-%016llx.exr", c->cache_dir, (unsigned long long)bench_hash_text(key));
}

/* 1: read from the cache; 0: not there (or of another size); -1: unreadable (err filled). */
static int
read_cached(const bench_config *c, const char *path, cg_image *out, cg_error *err)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return 0;
    if (!cg_image_read(path, out, err))
        return -1;
    if (out->width == c->width && out->height == c->height)
        return 1;
    cg_image_free(out);
    return 0;
}

/* The image and, beside it, a readable note of what the hashed file holds. */
static bool
write_cached(const bench_config *c, const char *path, const char *key, const cg_image *img, cg_error *err)
{
    if (!app_make_dirs(c->cache_dir, err) || !cg_image_write(path, img, CG_EXR_FLOAT, err))
        return false;
    char note[4200];
    snprintf(note, sizeof note, "%.4095s.txt", path);
    cg_atomic_file f;
    if (!cg_atomic_open(&f, note, err))
        return false;
    fprintf(f.fp, "%s\n", key);
    return cg_atomic_commit(&f, err);
}

/* The reference and its parts from one trace (pt_render_parts): the parts add up to the image,
 * and their noise is the image's, so that differences of them (the truths) carry no noise of a
 * second render. */
static bool
render_reference(const bench_config *c, bench_scene *bs, cg_error *err)
{
    fprintf(stderr, "bench: %s: rendering the reference, %dx%d, %d spp, %d bounces\n", bs->source, c->width,
            c->height, c->ref_spp, c->ref_bounces);
    float *parts[PT_PART_COUNT] = { 0 };
    bool ok = cg_image_alloc(&bs->ref, c->width, c->height, err);
    for (int k = 0; ok && k < PT_PART_COUNT; k++) {
        ok = cg_image_alloc(&bs->ref_parts[k], c->width, c->height, err);
        if (ok)
            parts[k] = bs->ref_parts[k].rgba;
    }
    pt_settings s = pt_settings_default();
    s.spp = c->ref_spp;
    s.bounces = c->ref_bounces;
    s.glossy_bounces = c->ref_glossy_bounces;
    s.transmission_bounces = c->ref_transmission_bounces;
    s.caustics = c->ref_caustics;
    s.seed = (uint32_t)c->ref_seed;
    s.progress = true;
    double t0 = app_now_ms(), cpu0 = app_cpu_ms();
    uint64_t rays = 0;
    ok = ok && pt_render_parts(bs->pts, &bs->session.frame.view, &s, bs->ref.rgba, parts, &rays, err);
    if (ok) {
        double ms = app_now_ms() - t0, cpu = app_cpu_ms() - cpu0;
        fprintf(stderr, "bench: reference took %.1f s, %.2f M rays/s (%.2f M per CPU second)\n", ms / 1e3,
                (double)rays / ms / 1e3, (double)rays / cpu / 1e3);
    }
    return ok;
}

/* The sum of some parts into out (allocated), in the order given, alpha 1. */
static bool
sum_parts(const cg_image *parts, const pt_part *which, int count, cg_image *out, cg_error *err)
{
    if (!cg_image_alloc(out, parts[which[0]].width, parts[which[0]].height, err))
        return false;
    size_t n = (size_t)out->width * (size_t)out->height * 4;
    for (size_t i = 0; i < n; i++) {
        float sum = 0.0f;
        for (int k = 0; k < count; k++)
            sum += parts[which[k]].rgba[i];
        out->rgba[i] = i % 4 == 3 ? 1.0f : sum;
    }
    return true;
}

static double
mean_luminance(const cg_image *img)
{
    size_t n = (size_t)img->width * (size_t)img->height;
    double sum = 0.0;
    for (size_t i = 0; i < n; i++)
        sum += cg_luminance(&img->rgba[4 * i]);
    return n ? sum / (double)n : NAN;
}

/* A graph's direct image stands for the emission it sees and the punctual lights' direct light
 * (its G-buffer's emission and its raster direct pass). */
static const pt_part own_direct_parts[2] = { PT_PART_EMITTED, PT_PART_DIRECT_PUNCTUAL };

bool
bench_reference(const bench_config *c, bench_scene *bs, cg_error *err)
{
    double t0 = app_now_ms();
    if (!pt_scene_create(&bs->session.scene, &bs->pts, err))
        return false;
    bs->bvh_ms = app_now_ms() - t0;
    enum { FILES = 1 + PT_PART_COUNT };
    char key[FILES][2048], path[FILES][4096];
    cg_image *images[FILES] = { &bs->ref };
    cache_entry(c, bs, "full", key[0], sizeof key[0], path[0], sizeof path[0]);
    for (int k = 0; k < PT_PART_COUNT; k++) {
        cache_entry(c, bs, pt_part_name((pt_part)k), key[1 + k], sizeof key[1 + k], path[1 + k], sizeof path[1 + k]);
        images[1 + k] = &bs->ref_parts[k];
    }
    int found = 1;
    for (int i = 0; i < FILES && found == 1; i++)
        found = read_cached(c, path[i], images[i], err);
    if (found < 0)
        return false;
    if (found == 1) {
        fprintf(stderr, "bench: %s: reference (%d spp, %d bounces) and its parts from the cache %s and beside it\n",
                bs->source, c->ref_spp, c->ref_bounces, path[0]);
    } else {
        for (int i = 0; i < FILES; i++)
            cg_image_free(images[i]);
        if (!render_reference(c, bs, err))
            return false;
        for (int i = 0; i < FILES; i++)
            if (!write_cached(c, path[i], key[i], images[i], err))
                return false;
    }
    /* The light reflected at most once: what 0 bounces gives in expectation. */
    const pt_part once[4] = { PT_PART_EMITTED, PT_PART_DIRECT_PUNCTUAL, PT_PART_DIRECT_EMITTERS, PT_PART_DIRECT_SKY };
    if (!sum_parts(bs->ref_parts, once, 4, &bs->ref_direct, err) ||
        !cg_image_subtract(&bs->ref, &bs->ref_direct, &bs->ref_indirect, err) ||
        !sum_parts(bs->ref_parts, own_direct_parts, 2, &bs->truth_direct, err) ||
        !cg_image_subtract(&bs->ref, &bs->truth_direct, &bs->truth_gi, err))
        return false;
    bs->ref_luminance = mean_luminance(&bs->ref);
    for (int k = 0; k < PT_PART_COUNT; k++)
        bs->part_luminance[k] = mean_luminance(&bs->ref_parts[k]);
    return true;
}

/* The path tracer at each --pt-spp (seed other than the reference's), timed wall-clock; its
 * parts come from the same trace (pt_render computes them anyway; asking costs their copy). */
bool
bench_path_tracer(const bench_config *c, bench_scene *bs, int scene_index, bench_rows *rows, cg_error *err)
{
    cg_image img = { 0 }, parts[PT_PART_COUNT] = { { 0 } }, own_direct = { 0 };
    float *part_rgba[PT_PART_COUNT] = { 0 };
    bool ok = cg_image_alloc(&img, c->width, c->height, err);
    for (int k = 0; ok && k < 2; k++) {
        ok = cg_image_alloc(&parts[own_direct_parts[k]], c->width, c->height, err);
        part_rgba[own_direct_parts[k]] = parts[own_direct_parts[k]].rgba;
    }
    for (int k = 0; ok && k < c->pt_count; k++) {
        pt_settings s = pt_settings_default();
        s.spp = c->pt_spp[k];
        s.bounces = c->ref_bounces;
        s.glossy_bounces = c->ref_glossy_bounces;
        s.transmission_bounces = c->ref_transmission_bounces;
        s.caustics = c->ref_caustics;
        s.seed = (uint32_t)c->ref_seed + 1000003u;
        double t0 = app_now_ms(), cpu0 = app_cpu_ms();
        uint64_t rays = 0;
        if (!pt_render_parts(bs->pts, &bs->session.frame.view, &s, img.rgba, part_rgba, &rays, err)) {
            ok = false;
            break;
        }
        double ms = app_now_ms() - t0, cpu = app_cpu_ms() - cpu0;
        bench_row *row = bench_row_add(rows, err);
        ok = row && sum_parts(parts, own_direct_parts, 2, &own_direct, err) &&
             bench_measure_errors(bs, &img, &own_direct, row, err);
        cg_image_free(&own_direct);
        if (!ok)
            break;
        row->scene = scene_index;
        row->is_pt = true;
        row->run = -1;
        row->combo = k;
        row->spp = s.spp;
        row->ms = ms;
        snprintf(row->graph, sizeof row->graph, "path_trace");
        snprintf(row->params, sizeof row->params, "spp=%d bounces=%d", s.spp, s.bounces);
        snprintf(row->pass_ms, sizeof row->pass_ms, "%.2f M rays/s, %.2f M rays per CPU second",
                 (double)rays / ms / 1e3, (double)rays / cpu / 1e3);
        fprintf(stderr, "bench: %s path_trace %4d spp: %9.1f ms, %.2f M rays/s (%.2f M per CPU second), relMSE %.5f, "
                "GI energy %.3f, nRMSE %.3f\n", bs->source, s.spp, ms, (double)rays / ms / 1e3,
                (double)rays / cpu / 1e3, row->full.rel_mse, row->gi.energy, row->gi.nrmse);
    }
    cg_image_free(&img);
    for (int k = 0; k < PT_PART_COUNT; k++)
        cg_image_free(&parts[k]);
    return ok;
}
