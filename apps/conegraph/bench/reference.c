/* bench: the path-traced reference of each scene (cached on disk) and the path tracer's own
 * error against its sample count, through cg/pt_render.h: see bench.h. */
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
 * `part` "full" or "direct". Files are keyed by a hash of all of these, the scene by its
 * contents (lights and sky included), the camera by the view's matrices. */
static void
cache_entry(const bench_config *c, const bench_scene *bs, const char *part, char *key, size_t key_size, char *path,
            size_t path_size)
{
    const cg_view *view = &bs->session.frame.view;
    uint64_t view_hash = fnv1a_bytes(0xcbf29ce484222325ull, view->inv_view_proj, sizeof view->inv_view_proj);
    snprintf(key, key_size,
             "conegraph-reference-v3|pt %d|%s|scene %016llx|view %016llx|%dx%d|spp %d|bounces %d|seed %d|%s",
             PT_RENDER_VERSION, bs->source, (unsigned long long)scene_hash(&bs->session.scene),
             (unsigned long long)view_hash, c->width, c->height, c->ref_spp, c->ref_bounces, c->ref_seed, part);
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
    snprintf(note, sizeof note, "%s.txt", path);
    cg_atomic_file f;
    if (!cg_atomic_open(&f, note, err))
        return false;
    fprintf(f.fp, "%s\n", key);
    return cg_atomic_commit(&f, err);
}

/* The reference and its direct part from one trace: the direct part is the light reflected at
 * most once (emission and sky seen; punctual lights, emitters and the sky reflected once:
 * pt_render_parts), which is what 0 bounces gives in expectation. One trace at the reference's
 * spp: a separate 0-bounce render needs as many samples now that emitters and the sky are
 * sampled (only punctual lights through pixel centres are exact with 1), and its noise would
 * not cancel in REF - REF_DIRECT as the parts' does. */
static bool
render_reference(const bench_config *c, bench_scene *bs, cg_error *err)
{
    fprintf(stderr, "bench: %s: rendering the reference, %dx%d, %d spp, %d bounces\n", bs->source, c->width,
            c->height, c->ref_spp, c->ref_bounces);
    enum { DIRECT_PARTS = 4 };
    const pt_part direct_parts[DIRECT_PARTS] = { PT_PART_EMITTED, PT_PART_DIRECT_PUNCTUAL, PT_PART_DIRECT_EMITTERS,
                                                 PT_PART_DIRECT_SKY };
    cg_image part_images[DIRECT_PARTS] = { { 0 } };
    float *parts[PT_PART_COUNT] = { 0 };
    bool ok = cg_image_alloc(&bs->ref, c->width, c->height, err) &&
              cg_image_alloc(&bs->ref_direct, c->width, c->height, err);
    for (int k = 0; ok && k < DIRECT_PARTS; k++) {
        ok = cg_image_alloc(&part_images[k], c->width, c->height, err);
        if (ok)
            parts[direct_parts[k]] = part_images[k].rgba;
    }
    pt_settings s = pt_settings_default();
    s.spp = c->ref_spp;
    s.bounces = c->ref_bounces;
    s.seed = (uint32_t)c->ref_seed;
    s.progress = true;
    double t0 = app_now_ms(), cpu0 = app_cpu_ms();
    uint64_t rays = 0;
    ok = ok && pt_render_parts(bs->pts, &bs->session.frame.view, &s, bs->ref.rgba, parts, &rays, err);
    if (ok) {
        double ms = app_now_ms() - t0, cpu = app_cpu_ms() - cpu0;
        fprintf(stderr, "bench: reference took %.1f s, %.2f M rays/s (%.2f M per CPU second)\n", ms / 1e3,
                (double)rays / ms / 1e3, (double)rays / cpu / 1e3);
        size_t n = (size_t)c->width * (size_t)c->height * 4;
        for (size_t i = 0; i < n; i++) {
            float sum = 0.0f;
            for (int k = 0; k < DIRECT_PARTS; k++)
                sum += part_images[k].rgba[i];
            bs->ref_direct.rgba[i] = i % 4 == 3 ? 1.0f : sum;
        }
    }
    for (int k = 0; k < DIRECT_PARTS; k++)
        cg_image_free(&part_images[k]);
    return ok;
}

bool
bench_reference(const bench_config *c, bench_scene *bs, cg_error *err)
{
    double t0 = app_now_ms();
    if (!pt_scene_create(&bs->session.scene, &bs->pts, err))
        return false;
    bs->bvh_ms = app_now_ms() - t0;
    char key[2][2048], path[2][4096];
    cache_entry(c, bs, "full", key[0], sizeof key[0], path[0], sizeof path[0]);
    cache_entry(c, bs, "direct", key[1], sizeof key[1], path[1], sizeof path[1]);
    int full = read_cached(c, path[0], &bs->ref, err);
    int direct = full == 1 ? read_cached(c, path[1], &bs->ref_direct, err) : 0;
    if (full < 0 || direct < 0)
        return false;
    if (full == 1 && direct == 1) {
        fprintf(stderr, "bench: %s: reference (%d spp, %d bounces) and its direct part from the cache %s, %s\n",
                bs->source, c->ref_spp, c->ref_bounces, path[0], path[1]);
    } else {
        cg_image_free(&bs->ref);
        cg_image_free(&bs->ref_direct);
        if (!render_reference(c, bs, err) || !write_cached(c, path[0], key[0], &bs->ref, err) ||
            !write_cached(c, path[1], key[1], &bs->ref_direct, err))
            return false;
    }
    return cg_image_subtract(&bs->ref, &bs->ref_direct, &bs->ref_indirect, err);
}

/* The path tracer at each --pt-spp (seed other than the reference's), timed wall-clock. */
bool
bench_path_tracer(const bench_config *c, bench_scene *bs, int scene_index, bench_rows *rows, cg_error *err)
{
    cg_image img = { 0 };
    if (!cg_image_alloc(&img, c->width, c->height, err))
        return false;
    for (int k = 0; k < c->pt_count; k++) {
        pt_settings s = pt_settings_default();
        s.spp = c->pt_spp[k];
        s.bounces = c->ref_bounces;
        s.seed = (uint32_t)c->ref_seed + 1000003u;
        double t0 = app_now_ms(), cpu0 = app_cpu_ms();
        uint64_t rays = 0;
        if (!pt_render(bs->pts, &bs->session.frame.view, &s, img.rgba, &rays, err)) {
            cg_image_free(&img);
            return false;
        }
        double ms = app_now_ms() - t0, cpu = app_cpu_ms() - cpu0;
        bench_row *row = bench_row_add(rows, err);
        if (!row || !bench_measure_errors(bs, &img, row, err)) {
            cg_image_free(&img);
            return false;
        }
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
        fprintf(stderr, "bench: %s path_trace %4d spp: %9.1f ms, %.2f M rays/s (%.2f M per CPU second), relMSE %.5f\n",
                bs->source, s.spp, ms, (double)rays / ms / 1e3, (double)rays / cpu / 1e3, row->full.rel_mse);
    }
    cg_image_free(&img);
    return true;
}
