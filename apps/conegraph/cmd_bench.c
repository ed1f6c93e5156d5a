/* conegraph bench: the speed/accuracy/memory trade of GI settings against the path-traced
 * reference. For each scene: the reference (cached on disk), the path tracer's own error
 * against its sample count, then every graph setting of the sweep: per-pass milliseconds
 * (median over frames after warm-up), GI memory, error (full and indirect part) and the
 * equal-error speed-up over the path tracer. Writes CSV, Markdown and PNG plots. */
#include <ctype.h>
#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "app_common.h"
#include "app_session.h"
#include "cg/camera.h"
#include "cg/error.h"
#include "cg/fg.h"
#include "cg/fs.h"
#include "cg/gl.h"
#include "cg/gpu_scene.h"
#include "cg/graphfile.h"
#include "cg/image.h"
#include "cg/log.h"
#include "cg/metrics.h"
#include "cg/scene.h"
#include "commands.h"
#include "cg/pt_render.h"
#include "bench/plot.h"

#define BENCH_MAX_SCENES 16
#define BENCH_MAX_SETTINGS 64
#define BENCH_MAX_SETS 16
#define BENCH_MAX_VARY 4
#define BENCH_MAX_VALUES 16
#define BENCH_MAX_SPP 16
#define BENCH_TEXT 256

typedef struct bench_vary {
    char param[BENCH_TEXT];                 /* pass.param */
    char values[BENCH_MAX_VALUES][64];
    int count;
} bench_vary;

typedef struct bench_setting {
    char graph[BENCH_TEXT];
    char sets[BENCH_MAX_SETS][BENCH_TEXT];  /* pass.param=value, fixed for this setting */
    int set_count;
    bench_vary vary[BENCH_MAX_VARY];        /* every combination is one run */
    int vary_count;
} bench_setting;

typedef struct bench_config {
    char scenes[BENCH_MAX_SCENES][BENCH_TEXT];
    int scene_count;
    int width, height;
    char camera[BENCH_TEXT];
    int frames, warmup;
    int ref_spp, ref_bounces, ref_seed;
    int pt_spp[BENCH_MAX_SPP];
    int pt_count;
    bench_setting settings[BENCH_MAX_SETTINGS];
    int setting_count;
    char out_dir[BENCH_TEXT];
    char cache_dir[BENCH_TEXT];
    cg_context_backend backend;
    bool images;
} bench_config;

typedef struct bench_row {
    int scene;
    bool is_pt;
    int spp;
    char graph[BENCH_TEXT];
    char params[1024];
    char pass_ms[1024];
    double ms;              /* median frame (sum of the passes' medians' frame), or path tracer wall time */
    size_t gi_bytes, peak_bytes;
    cg_metrics full, indirect;
    double pt_equal_ms;     /* path tracer time at the same relMSE (estimated) */
    double speedup;
    bool pareto_time, pareto_memory;
} bench_row;

typedef struct bench_rows {
    bench_row *rows;
    int count, capacity;
} bench_rows;

/* ------------------------------------------------------------ usage and parsing */

static void
bench_usage(FILE *out)
{
    fprintf(out,
        "usage: conegraph bench [--sweep FILE.json] [--scene SCENE]... [--graph FILE\n"
        "                       [--set PASS.PARAM=V]... [--vary PASS.PARAM=V1,V2,...]...]...\n"
        "                       [options]\n"
        "\n"
        "Measures every setting of a sweep against the path-traced reference and writes\n"
        "OUT/bench.csv, OUT/bench.md and, per scene, OUT/SCENE-time.png and OUT/SCENE-memory.png\n"
        "(relMSE against time per frame and against GI memory, Pareto front ringed in red).\n"
        "\n"
        "Per scene: the reference (path_trace at --ref-spp, --ref-bounces; pixel centres like the\n"
        "raster camera) and its direct part (0 bounces) are rendered once and cached in the cache\n"
        "directory; the path tracer is timed at each --pt-spp against the reference; then each\n"
        "setting runs --warmup frames and --frames timed frames (synchronous timing: glFinish and\n"
        "a CPU clock around each pass) and is compared with the reference: full image, and the\n"
        "indirect part (TEST - REF_DIRECT against REF - REF_DIRECT). The equal-error speed-up is\n"
        "the path tracer's time to reach the setting's relMSE (interpolated log-log between the\n"
        "measured sample counts, extrapolated with the 1/N law) over the setting's frame time.\n"
        "\n"
        "  --sweep FILE.json     a sweep file (below); flags given as well override its fields,\n"
        "                        and --graph adds settings to its list\n"
        "  --scene SCENE         scene to measure; repeatable (default builtin:cornell)\n"
        "  --graph FILE          a graph file (as for render: from the graph directory when not a\n"
        "                        path); repeatable; default direct.json and vct.json when present\n"
        "  --set PASS.PARAM=V    fix a parameter of the last --graph; repeatable\n"
        "  --vary PASS.PARAM=V1,V2,...  run the last --graph once per value; several --vary\n"
        "                        give every combination\n"
        "  --size WxH            image size (default 320x180)\n"
        "  --camera NAME|INDEX   scene camera (default the first)\n"
        "  --frames N            timed frames per setting (default 5; the median is reported)\n"
        "  --warmup N            untimed frames first (default 2: shader JIT, caches)\n"
        "  --ref-spp N           reference samples per pixel (default 1024)\n"
        "  --ref-bounces N       diffuse bounces of the reference (default 1, as the GI graphs)\n"
        "  --pt-spp LIST         path tracer sample counts to time, e.g. 1,4,16,64 (default)\n"
        "  --out DIR             output directory (default bench-out)\n"
        "  --cache DIR           reference cache (default OUT/cache); entries are keyed by the\n"
        "                        scene's contents, view, size, spp, bounces, seed and tracer version\n"
        "  --images              also write each setting's image, error heat map and the\n"
        "                        reference as PNG (linear radiance, clamped, sRGB-encoded)\n"
        "  --context egl|osmesa|glfw  GL context (default: $CONEGRAPH_CONTEXT, else EGL, then OSMesa)\n"
        "Pass plugins in the directories of $CONEGRAPH_PLUGIN_PATH are loaded.\n"
        "\n"
        "Sweep file:\n"
        "  { \"scenes\": [\"builtin:cornell\"], \"size\": \"320x180\", \"frames\": 5, \"warmup\": 2,\n"
        "    \"reference\": { \"spp\": 1024, \"bounces\": 1, \"seed\": 1 },\n"
        "    \"path_tracer_spp\": [1, 4, 16, 64],\n"
        "    \"settings\": [ { \"graph\": \"direct.json\" },\n"
        "                  { \"graph\": \"vct.json\", \"set\": { \"gather.cones\": 6 },\n"
        "                    \"vary\": { \"vox.resolution\": [64, 128] } } ] }\n"
        "\n"
        "Exit codes: 0 done, 1 failed while running, 2 bad usage, sweep file, scene or graph.\n"
        "Progress goes to stderr; the Markdown table also to stdout.\n");
}

static int
usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "conegraph bench: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, " (see conegraph bench --help)\n");
    return 2;
}

static bool
copy_text(char *dst, const char *src)
{
    if (strlen(src) >= BENCH_TEXT)
        return false;
    strcpy(dst, src);
    return true;
}

static bool
parse_spp_list(const char *text, bench_config *c)
{
    char buf[BENCH_TEXT];
    if (!copy_text(buf, text))
        return false;
    c->pt_count = 0;
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        long v;
        if (c->pt_count == BENCH_MAX_SPP || !app_parse_int(tok, 1, 65536, &v))
            return false;
        c->pt_spp[c->pt_count++] = (int)v;
    }
    return c->pt_count > 0;
}

/* "pass.param=v1,v2,..." into a vary entry. */
static bool
parse_vary(const char *text, bench_vary *v)
{
    const char *eq = strchr(text, '=');
    if (!eq || eq == text || !eq[1] || (size_t)(eq - text) >= sizeof v->param)
        return false;
    memcpy(v->param, text, (size_t)(eq - text));
    v->param[eq - text] = '\0';
    char buf[1024];
    if (strlen(eq + 1) >= sizeof buf)
        return false;
    strcpy(buf, eq + 1);
    v->count = 0;
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        if (v->count == BENCH_MAX_VALUES || strlen(tok) >= sizeof v->values[0])
            return false;
        strcpy(v->values[v->count++], tok);
    }
    return v->count > 0;
}

/* A JSON scalar as the text a --set would carry. */
static bool
json_scalar_text(const json_t *v, char *out, size_t size)
{
    if (json_is_string(v))
        snprintf(out, size, "%s", json_string_value(v));
    else if (json_is_integer(v))
        snprintf(out, size, "%lld", (long long)json_integer_value(v));
    else if (json_is_real(v))
        snprintf(out, size, "%.17g", json_real_value(v));
    else if (json_is_boolean(v))
        snprintf(out, size, "%s", json_is_true(v) ? "true" : "false");
    else
        return false;
    return true;
}

static int
sweep_error(const char *path, const char *what)
{
    fprintf(stderr, "conegraph bench: %s: %s\n", path, what);
    return 2;
}

static int
json_positive_int(const char *path, json_t *root, const char *key, long max, int *out)
{
    json_t *v = json_object_get(root, key);
    if (!v)
        return 0;
    if (!json_is_integer(v) || json_integer_value(v) < 0 || json_integer_value(v) > max) {
        fprintf(stderr, "conegraph bench: %s: \"%s\" must be an integer from 0 to %ld\n", path, key, max);
        return 2;
    }
    *out = (int)json_integer_value(v);
    return 0;
}

static int
load_sweep(const char *path, bench_config *c)
{
    json_error_t jerr;
    json_t *root = json_load_file(path, 0, &jerr);
    if (!root) {
        fprintf(stderr, "conegraph bench: %s:%d:%d: %s\n", path, jerr.line, jerr.column, jerr.text);
        return 2;
    }
    int code = 0;
    char text[BENCH_TEXT];
    if (!json_is_object(root)) {
        code = sweep_error(path, "expected a JSON object at the top");
        goto done;
    }
    const char *key;
    json_t *value;
    json_object_foreach(root, key, value) {
        static const char *const known[] = { "scenes", "size", "camera", "frames", "warmup", "reference",
                                              "path_tracer_spp", "settings", NULL };
        bool ok = false;
        for (int i = 0; known[i]; i++)
            ok |= !strcmp(key, known[i]);
        if (!ok) {
            fprintf(stderr, "conegraph bench: %s: unknown field \"%s\"\n", path, key);
            code = 2;
            goto done;
        }
    }
    json_t *scenes = json_object_get(root, "scenes");
    if (scenes) {
        if (!json_is_array(scenes) || json_array_size(scenes) == 0 || json_array_size(scenes) > BENCH_MAX_SCENES) {
            code = sweep_error(path, "\"scenes\" must be a non-empty array of at most 16 strings");
            goto done;
        }
        c->scene_count = 0;
        size_t i;
        json_array_foreach(scenes, i, value) {
            if (!json_is_string(value) || !copy_text(c->scenes[c->scene_count++], json_string_value(value))) {
                code = sweep_error(path, "\"scenes\" entries must be strings (shorter than 256 bytes)");
                goto done;
            }
        }
    }
    json_t *size = json_object_get(root, "size");
    if (size && (!json_is_string(size) || !app_parse_size(json_string_value(size), &c->width, &c->height))) {
        code = sweep_error(path, "\"size\" must be a string \"WxH\"");
        goto done;
    }
    json_t *camera = json_object_get(root, "camera");
    if (camera && !(json_scalar_text(camera, text, sizeof text) && copy_text(c->camera, text))) {
        code = sweep_error(path, "\"camera\" must be a name or an index");
        goto done;
    }
    if ((code = json_positive_int(path, root, "frames", 10000, &c->frames)) ||
        (code = json_positive_int(path, root, "warmup", 10000, &c->warmup)))
        goto done;
    if (c->frames < 1) {
        code = sweep_error(path, "\"frames\" must be at least 1");
        goto done;
    }
    json_t *ref = json_object_get(root, "reference");
    if (ref) {
        if (!json_is_object(ref)) {
            code = sweep_error(path, "\"reference\" must be an object { spp, bounces, seed }");
            goto done;
        }
        if ((code = json_positive_int(path, ref, "spp", 65536, &c->ref_spp)) ||
            (code = json_positive_int(path, ref, "bounces", 16, &c->ref_bounces)) ||
            (code = json_positive_int(path, ref, "seed", 2147483647L, &c->ref_seed)))
            goto done;
        if (c->ref_spp < 1) {
            code = sweep_error(path, "\"reference\".\"spp\" must be at least 1");
            goto done;
        }
    }
    json_t *spp = json_object_get(root, "path_tracer_spp");
    if (spp) {
        if (!json_is_array(spp) || json_array_size(spp) == 0 || json_array_size(spp) > BENCH_MAX_SPP) {
            code = sweep_error(path, "\"path_tracer_spp\" must be a non-empty array of at most 16 counts");
            goto done;
        }
        c->pt_count = 0;
        size_t i;
        json_array_foreach(spp, i, value) {
            if (!json_is_integer(value) || json_integer_value(value) < 1 || json_integer_value(value) > 65536) {
                code = sweep_error(path, "\"path_tracer_spp\" entries must be integers from 1 to 65536");
                goto done;
            }
            c->pt_spp[c->pt_count++] = (int)json_integer_value(value);
        }
    }
    json_t *settings = json_object_get(root, "settings");
    if (settings) {
        if (!json_is_array(settings) || json_array_size(settings) > BENCH_MAX_SETTINGS) {
            code = sweep_error(path, "\"settings\" must be an array of at most 64 objects");
            goto done;
        }
        size_t i;
        json_array_foreach(settings, i, value) {
            bench_setting *s = &c->settings[c->setting_count++];
            memset(s, 0, sizeof *s);
            json_t *graph = json_object_get(value, "graph");
            if (!json_is_object(value) || !json_is_string(graph) || !copy_text(s->graph, json_string_value(graph))) {
                code = sweep_error(path, "each setting must be an object with a string \"graph\"");
                goto done;
            }
            const char *pkey;
            json_t *pval;
            json_object_foreach(value, pkey, pval) {
                if (strcmp(pkey, "graph") && strcmp(pkey, "set") && strcmp(pkey, "vary")) {
                    fprintf(stderr, "conegraph bench: %s: setting %zu: unknown field \"%s\"\n", path, i, pkey);
                    code = 2;
                    goto done;
                }
            }
            json_t *set = json_object_get(value, "set");
            if (set) {
                json_object_foreach(set, pkey, pval) {
                    if (s->set_count == BENCH_MAX_SETS || !json_scalar_text(pval, text, sizeof text) ||
                        snprintf(s->sets[s->set_count], BENCH_TEXT, "%s=%s", pkey, text) >= BENCH_TEXT) {
                        code = sweep_error(path, "\"set\" must map at most 16 PASS.PARAM names to scalars");
                        goto done;
                    }
                    s->set_count++;
                }
            }
            json_t *vary = json_object_get(value, "vary");
            if (vary) {
                json_object_foreach(vary, pkey, pval) {
                    if (s->vary_count == BENCH_MAX_VARY || !json_is_array(pval) || json_array_size(pval) == 0 ||
                        json_array_size(pval) > BENCH_MAX_VALUES || strlen(pkey) >= BENCH_TEXT) {
                        code = sweep_error(path, "\"vary\" must map at most 4 PASS.PARAM names to arrays of 1 to 16 values");
                        goto done;
                    }
                    bench_vary *v = &s->vary[s->vary_count++];
                    strcpy(v->param, pkey);
                    size_t k;
                    json_t *item;
                    json_array_foreach(pval, k, item) {
                        if (!json_scalar_text(item, v->values[v->count], sizeof v->values[0])) {
                            code = sweep_error(path, "\"vary\" values must be strings, numbers or booleans");
                            goto done;
                        }
                        v->count++;
                    }
                }
            }
        }
    }
done:
    json_decref(root);
    return code;
}

static int
parse_args(int argc, char **argv, bench_config *c)
{
    memset(c, 0, sizeof *c);
    c->width = 320;
    c->height = 180;
    c->frames = 5;
    c->warmup = 2;
    c->ref_spp = 1024;
    c->ref_bounces = 1;
    c->ref_seed = 1;
    c->pt_spp[0] = 1, c->pt_spp[1] = 4, c->pt_spp[2] = 16, c->pt_spp[3] = 64;
    c->pt_count = 4;
    strcpy(c->out_dir, "bench-out");
    /* The sweep file first, so that flags override it wherever they appear. */
    for (int i = 1; i + 1 < argc; i++)
        if (!strcmp(argv[i], "--sweep")) {
            int code = load_sweep(argv[i + 1], c);
            if (code)
                return code;
        }
    bool scenes_from_flags = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--images")) {
            c->images = true;
            continue;
        }
        if (a[0] != '-')
            return usage_error("unexpected argument '%s'", a);
        const char *v = i + 1 < argc ? argv[++i] : NULL;
        if (!v)
            return usage_error("%s needs a value", a);
        long n;
        if (!strcmp(a, "--sweep")) {
            continue;
        } else if (!strcmp(a, "--scene")) {
            if (!scenes_from_flags)
                c->scene_count = 0;
            scenes_from_flags = true;
            if (c->scene_count == BENCH_MAX_SCENES || !copy_text(c->scenes[c->scene_count++], v))
                return usage_error("%s: too many scenes or too long a name", v);
        } else if (!strcmp(a, "--graph")) {
            if (c->setting_count == BENCH_MAX_SETTINGS)
                return usage_error("%s: too many settings", v);
            bench_setting *s = &c->settings[c->setting_count++];
            memset(s, 0, sizeof *s);
            if (!copy_text(s->graph, v))
                return usage_error("%s: path too long", v);
        } else if (!strcmp(a, "--set") || !strcmp(a, "--vary")) {
            if (c->setting_count == 0)
                return usage_error("%s applies to a --graph given before it", a);
            bench_setting *s = &c->settings[c->setting_count - 1];
            if (!strcmp(a, "--set")) {
                if (s->set_count == BENCH_MAX_SETS || !strchr(v, '=') || !copy_text(s->sets[s->set_count++], v))
                    return usage_error("--set wants PASS.PARAM=VALUE (at most 16 per graph), not '%s'", v);
            } else if (s->vary_count == BENCH_MAX_VARY || !parse_vary(v, &s->vary[s->vary_count++])) {
                return usage_error("--vary wants PASS.PARAM=V1,V2,... (at most 4 per graph, 16 values), not '%s'", v);
            }
        } else if (!strcmp(a, "--size")) {
            if (!app_parse_size(v, &c->width, &c->height))
                return usage_error("--size wants WxH with 1..65536 pixels each, not '%s'", v);
        } else if (!strcmp(a, "--camera")) {
            if (!copy_text(c->camera, v))
                return usage_error("--camera '%s' is too long", v);
        } else if (!strcmp(a, "--frames")) {
            if (!app_parse_int(v, 1, 10000, &n))
                return usage_error("--frames wants 1 to 10000, not '%s'", v);
            c->frames = (int)n;
        } else if (!strcmp(a, "--warmup")) {
            if (!app_parse_int(v, 0, 10000, &n))
                return usage_error("--warmup wants 0 to 10000, not '%s'", v);
            c->warmup = (int)n;
        } else if (!strcmp(a, "--ref-spp")) {
            if (!app_parse_int(v, 1, 65536, &n))
                return usage_error("--ref-spp wants 1 to 65536, not '%s'", v);
            c->ref_spp = (int)n;
        } else if (!strcmp(a, "--ref-bounces")) {
            if (!app_parse_int(v, 0, 16, &n))
                return usage_error("--ref-bounces wants 0 to 16, not '%s'", v);
            c->ref_bounces = (int)n;
        } else if (!strcmp(a, "--pt-spp")) {
            if (!parse_spp_list(v, c))
                return usage_error("--pt-spp wants up to 16 counts from 1 to 65536 like 1,4,16, not '%s'", v);
        } else if (!strcmp(a, "--out")) {
            if (!copy_text(c->out_dir, v))
                return usage_error("--out '%s' is too long", v);
        } else if (!strcmp(a, "--cache")) {
            if (!copy_text(c->cache_dir, v))
                return usage_error("--cache '%s' is too long", v);
        } else if (!strcmp(a, "--context")) {
            if (!cg_context_backend_parse(v, &c->backend))
                return usage_error("--context wants egl, osmesa, glfw or auto, not '%s'", v);
        } else {
            return usage_error("unknown option '%s'", a);
        }
    }
    if (c->scene_count == 0) {
        strcpy(c->scenes[0], "builtin:cornell");
        c->scene_count = 1;
    }
    if (c->setting_count == 0) {
        strcpy(c->settings[c->setting_count++].graph, "direct.json");
        char path[4096];
        snprintf(path, sizeof path, "%s/vct.json", app_graph_dir());
        struct stat st;
        if (stat(path, &st) == 0)
            strcpy(c->settings[c->setting_count++].graph, "vct.json");
    }
    if (!c->cache_dir[0] && snprintf(c->cache_dir, BENCH_TEXT, "%s/cache", c->out_dir) >= BENCH_TEXT)
        return usage_error("--out '%s' is too long", c->out_dir);
    return 0;
}

/* ------------------------------------------------------------ files */

static bool
make_dirs(const char *path, cg_error *err)
{
    char buf[4096];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf)
        return cg_fail(err, CG_ERR_USAGE, "%s: path too long", path);
    for (char *p = buf + 1;; p++) {
        if (*p == '/' || *p == '\0') {
            char saved = *p;
            *p = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return cg_fail(err, CG_ERR_IO, "%s: cannot create directory: %s", buf, strerror(errno));
            *p = saved;
            if (!saved)
                break;
        }
    }
    return true;
}

/* "builtin:openworld?triangles=10000" -> "builtin-openworld-triangles-10000". */
static void
slug(const char *text, char *out, size_t size)
{
    size_t n = 0;
    for (const char *s = text; *s && n + 1 < size; s++)
        out[n++] = isalnum((unsigned char)*s) || *s == '.' ? *s : '-';
    out[n] = '\0';
}

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

static uint64_t
fnv1a(const char *text)
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
    return h;
}

/* ------------------------------------------------------------ references */

typedef struct bench_scene {
    const char *source;
    app_session session;    /* scene, camera and view at the bench size, registry, graph, context */
    pt_scene *pts;
    double bvh_ms;
    cg_image ref, ref_direct, ref_indirect;
} bench_scene;

/* The reference image for (scene, camera, size, spp, bounces, seed), from the cache or rendered
 * and cached. Files are keyed by a hash of all of these, the scene by its contents. */
static bool
reference_image(const bench_config *c, bench_scene *bs, int spp, int bounces, cg_image *out, cg_error *err)
{
    char key[2048];
    struct stat st;
    /* The view's matrices stand for the camera; the scene by the hash of its contents. */
    uint64_t view_hash = fnv1a_bytes(0xcbf29ce484222325ull, bs->session.frame.view.inv_view_proj, sizeof bs->session.frame.view.inv_view_proj);
    snprintf(key, sizeof key,
             "conegraph-reference-v2|pt %d|%s|scene %016llx|view %016llx|%dx%d|spp %d|bounces %d|seed %d",
             PT_RENDER_VERSION, bs->source, (unsigned long long)scene_hash(&bs->session.scene),
             (unsigned long long)view_hash, c->width, c->height, spp, bounces, c->ref_seed);
    char path[4096];
    snprintf(path, sizeof path, "%s/ref-%016llx.exr", c->cache_dir, (unsigned long long)fnv1a(key));
    if (stat(path, &st) == 0) {
        if (!cg_image_read(path, out, err))
            return false;
        if (out->width == c->width && out->height == c->height) {
            fprintf(stderr, "bench: %s: reference (%d spp, %d bounces) from the cache %s\n", bs->source, spp,
                    bounces, path);
            return true;
        }
        cg_image_free(out);
    }
    fprintf(stderr, "bench: %s: rendering the reference, %dx%d, %d spp, %d bounces\n", bs->source, c->width,
            c->height, spp, bounces);
    if (!cg_image_alloc(out, c->width, c->height, err))
        return false;
    pt_settings s = pt_settings_default();
    s.spp = spp;
    s.bounces = bounces;
    s.seed = (uint32_t)c->ref_seed;
    s.progress = true;
    double t0 = app_now_ms(), cpu0 = app_cpu_ms();
    uint64_t rays = 0;
    if (!pt_render(bs->pts, &bs->session.frame.view, &s, out->rgba, &rays, err))
        return false;
    double ms = app_now_ms() - t0, cpu = app_cpu_ms() - cpu0;
    fprintf(stderr, "bench: reference took %.1f s, %.2f M rays/s (%.2f M per CPU second)\n", ms / 1e3,
            (double)rays / ms / 1e3, (double)rays / cpu / 1e3);
    if (!make_dirs(c->cache_dir, err) || !cg_image_write(path, out, CG_EXR_FLOAT, err))
        return false;
    /* A readable note of what the hashed file holds. */
    char note[4200];
    snprintf(note, sizeof note, "%s.txt", path);
    cg_atomic_file f;
    if (!cg_atomic_open(&f, note, err))
        return false;
    fprintf(f.fp, "%s\n", key);
    return cg_atomic_commit(&f, err);
}

/* ------------------------------------------------------------ rows */

static bench_row *
row_add(bench_rows *rows, cg_error *err)
{
    if (rows->count == rows->capacity) {
        int cap = rows->capacity ? rows->capacity * 2 : 32;
        bench_row *r = realloc(rows->rows, sizeof *r * (size_t)cap);
        if (!r) {
            cg_fail(err, CG_ERR_OUT_OF_MEMORY, "bench rows");
            return NULL;
        }
        rows->rows = r;
        rows->capacity = cap;
    }
    bench_row *r = &rows->rows[rows->count++];
    memset(r, 0, sizeof *r);
    r->pt_equal_ms = r->speedup = NAN;
    return r;
}

static bool
measure_errors(const bench_scene *bs, const cg_image *test, bench_row *row, cg_error *err)
{
    cg_image ind = { 0 };
    if (!cg_metrics_compute(test, &bs->ref, &row->full, err))
        return false;
    bool ok = cg_image_subtract(test, &bs->ref_direct, &ind, err) &&
              cg_metrics_compute(&ind, &bs->ref_indirect, &row->indirect, err);
    cg_image_free(&ind);
    return ok;
}

/* The path tracer at each --pt-spp (seed other than the reference's), timed wall-clock. */
static bool
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
        bench_row *row = row_add(rows, err);
        if (!row || !measure_errors(bs, &img, row, err)) {
            cg_image_free(&img);
            return false;
        }
        row->scene = scene_index;
        row->is_pt = true;
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

/* Path tracer time to reach relMSE `e`: log-log interpolation between the measured sample
 * counts, the 1/N law beyond them, at least 1 spp; time proportional to spp at the largest
 * count's cost per sample. */
static double
pt_time_for_error(const bench_rows *rows, int scene, double e)
{
    double spp[BENCH_MAX_SPP], err[BENCH_MAX_SPP], per_spp = NAN;
    int n = 0, best = 0;
    for (int i = 0; i < rows->count; i++) {
        const bench_row *r = &rows->rows[i];
        if (r->scene != scene || !r->is_pt || !(r->full.rel_mse > 0.0) || n == BENCH_MAX_SPP)
            continue;
        spp[n] = r->spp;
        err[n] = r->full.rel_mse;
        if (r->spp >= best) {
            best = r->spp;
            per_spp = r->ms / r->spp;
        }
        n++;
    }
    if (n == 0 || !(e > 0.0))
        return NAN;
    /* Sort by spp. */
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && spp[j] < spp[j - 1]; j--) {
            double t = spp[j]; spp[j] = spp[j - 1]; spp[j - 1] = t;
            t = err[j]; err[j] = err[j - 1]; err[j - 1] = t;
        }
    double needed;
    if (e >= err[0]) {
        needed = spp[0] * err[0] / e;
    } else if (e <= err[n - 1]) {
        needed = spp[n - 1] * err[n - 1] / e;
    } else {
        needed = spp[n - 1];
        for (int i = 0; i + 1 < n; i++)
            if (e <= err[i] && e >= err[i + 1]) {
                double t = (log(e) - log(err[i])) / (log(err[i + 1]) - log(err[i]));
                needed = exp(log(spp[i]) + t * (log(spp[i + 1]) - log(spp[i])));
                break;
            }
    }
    /* A path tracer cannot take less than one sample per pixel. */
    return (needed > 1.0 ? needed : 1.0) * per_spp;
}

/* ------------------------------------------------------------ graph settings */

static bool
run_setting(const bench_config *c, bench_scene *bs, int scene_index, const bench_setting *s, const int *choice,
            bench_rows *rows, cg_error *err)
{
    bench_row *row = row_add(rows, err);
    if (!row)
        return false;
    row->scene = scene_index;
    snprintf(row->graph, sizeof row->graph, "%s", s->graph);
    size_t len = 0;
    for (int i = 0; i < s->set_count; i++)
        len += (size_t)snprintf(row->params + len, sizeof row->params - len, "%s%s", len ? " " : "", s->sets[i]);
    for (int v = 0; v < s->vary_count && len < sizeof row->params; v++)
        len += (size_t)snprintf(row->params + len, sizeof row->params - len, "%s%s=%s", len ? " " : "",
                                s->vary[v].param, s->vary[v].values[choice[v]]);
    char assignments[BENCH_MAX_SETS + BENCH_MAX_VARY][2 * BENCH_TEXT];
    const char *sets[BENCH_MAX_SETS + BENCH_MAX_VARY];
    int set_count = 0;
    for (int i = 0; i < s->set_count; i++)
        sets[set_count++] = s->sets[i];
    for (int v = 0; v < s->vary_count; v++) {
        snprintf(assignments[v], sizeof assignments[v], "%s=%s", s->vary[v].param, s->vary[v].values[choice[v]]);
        sets[set_count++] = assignments[v];
    }
    app_graph_desc graph = { .graph = s->graph, .sets = sets, .set_count = set_count, .image = "hdr" };
    app_run_desc run = { .warmup = c->warmup, .frames = c->frames, .timing = FG_TIMING_SYNC };
    app_frame_stats stats = { 0 };
    cg_image img = { 0 };
    bool ok = app_session_load_graph(&bs->session, &graph, err) && app_session_check(&bs->session, err) &&
              app_session_compile(&bs->session, err) && app_session_run(&bs->session, &run, &stats, err);
    if (!ok)
        goto done;
    fg_graph *g = bs->session.graph;
    row->ms = stats.median_pass_sum_ms;
    const int *order;
    int order_count = fg_graph_order(g, &order);
    len = 0;
    for (int k = 0; k < order_count && len < sizeof row->pass_ms; k++)
        len += (size_t)snprintf(row->pass_ms + len, sizeof row->pass_ms - len, "%s%s %.2f", len ? ", " : "",
                                fg_pass_name(fg_graph_pass_at(g, order[k])),
                                app_frame_stats_pass_median(&stats, order[k]));
    fg_memory_report mem;
    fg_graph_memory_report(g, &mem);
    row->gi_bytes = mem.gi_bytes;
    row->peak_bytes = mem.peak_bytes;
    ok = app_session_read_image(&bs->session, bs->session.image_source, false, &img, err) &&
         measure_errors(bs, &img, row, err);
    if (ok && c->images) {
        char name[2048], path[4096], scene_slug[BENCH_TEXT], params_slug[512];
        slug(bs->source, scene_slug, sizeof scene_slug);
        snprintf(name, sizeof name, "%s%s%s", s->graph, row->params[0] ? " " : "", row->params);
        slug(name, params_slug, sizeof params_slug);
        snprintf(path, sizeof path, "%s/%s-%s.png", c->out_dir, scene_slug, params_slug);
        cg_image heat = { 0 };
        ok = cg_image_write(path, &img, CG_EXR_HALF, err);
        snprintf(path, sizeof path, "%s/%s-%s-error.png", c->out_dir, scene_slug, params_slug);
        ok = ok && cg_metrics_heatmap(&img, &bs->ref, 1.0, &heat, err) && cg_image_write(path, &heat, CG_EXR_HALF, err);
        cg_image_free(&heat);
    }
done:
    cg_image_free(&img);
    app_frame_stats_free(&stats);
    if (!ok)
        rows->count--;
    return ok;
}

/* ------------------------------------------------------------ reports */

static void
mark_pareto(bench_rows *rows, int scene)
{
    for (int i = 0; i < rows->count; i++) {
        bench_row *p = &rows->rows[i];
        if (p->scene != scene || p->is_pt)
            continue;
        bool dominated_t = false, dominated_m = false;
        for (int j = 0; j < rows->count; j++) {
            const bench_row *q = &rows->rows[j];
            if (j == i || q->scene != scene || q->is_pt)
                continue;
            double pe = p->full.rel_mse, qe = q->full.rel_mse;
            if (q->ms <= p->ms && qe <= pe && (q->ms < p->ms || qe < pe))
                dominated_t = true;
            if (q->gi_bytes <= p->gi_bytes && qe <= pe && (q->gi_bytes < p->gi_bytes || qe < pe))
                dominated_m = true;
        }
        p->pareto_time = !dominated_t;
        p->pareto_memory = !dominated_m;
    }
}

static void
csv_field(FILE *fp, const char *text)
{
    fputc('"', fp);
    for (const char *s = text; *s; s++) {
        if (*s == '"')
            fputc('"', fp);
        fputc(*s, fp);
    }
    fputc('"', fp);
}

static bool
write_csv(const bench_config *c, const bench_rows *rows, const bench_scene *scenes, cg_error *err)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/bench.csv", c->out_dir);
    cg_atomic_file f;
    if (!cg_atomic_open(&f, path, err))
        return false;
    fprintf(f.fp, "scene,width,height,method,params,ms,pass_ms,gi_bytes,peak_bytes,rmse,relmse,ssim,max_error,"
                  "lum_ratio,nonfinite,indirect_rmse,indirect_relmse,indirect_ssim,indirect_lum_ratio,"
                  "pt_equal_error_ms,speedup,pareto_time,pareto_memory\n");
    for (int i = 0; i < rows->count; i++) {
        const bench_row *r = &rows->rows[i];
        csv_field(f.fp, scenes[r->scene].source);
        fprintf(f.fp, ",%d,%d,", c->width, c->height);
        csv_field(f.fp, r->graph);
        fputc(',', f.fp);
        csv_field(f.fp, r->params);
        fprintf(f.fp, ",%.3f,", r->ms);
        csv_field(f.fp, r->pass_ms);
        fprintf(f.fp, ",%zu,%zu,%.6g,%.6g,%.6f,%.6g,%.6f,%zu,%.6g,%.6g,%.6f,%.6f,%.3f,%.3f,%d,%d\n", r->gi_bytes,
                r->peak_bytes, r->full.rmse, r->full.rel_mse, r->full.ssim, r->full.max_error,
                r->full.mean_luminance_ratio, r->full.nonfinite_pixels, r->indirect.rmse, r->indirect.rel_mse,
                r->indirect.ssim, r->indirect.mean_luminance_ratio, r->pt_equal_ms, r->speedup,
                !r->is_pt && r->pareto_time, !r->is_pt && r->pareto_memory);
    }
    return cg_atomic_commit(&f, err);
}

static void
write_markdown_table(FILE *fp, const bench_config *c, const bench_rows *rows, const bench_scene *scenes, int s)
{
    fprintf(fp, "### %s, %dx%d\n\n", scenes[s].source, c->width, c->height);
    fprintf(fp, "Reference: path_trace, %d spp, %d bounce(s), seed %d (BVH build %.0f ms). "
                "Times: median of %d frames after %d warm-up, synchronous. "
                "P: on the Pareto front of relMSE against time (t) or GI memory (m).\n\n",
            c->ref_spp, c->ref_bounces, c->ref_seed, scenes[s].bvh_ms, c->frames, c->warmup);
    fprintf(fp, "| method | parameters | ms | GI MiB | relMSE | RMSE | SSIM | lum. ratio | indirect relMSE | "
                "indirect lum. ratio | PT ms at equal relMSE | speed-up | P | per pass (ms) |\n");
    fprintf(fp, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|\n");
    for (int i = 0; i < rows->count; i++) {
        const bench_row *r = &rows->rows[i];
        if (r->scene != s)
            continue;
        char pareto[8] = "";
        if (!r->is_pt)
            snprintf(pareto, sizeof pareto, "%s%s", r->pareto_time ? "t" : "", r->pareto_memory ? "m" : "");
        char equal[32] = "", speed[32] = "";
        if (!r->is_pt && isfinite(r->pt_equal_ms)) {
            snprintf(equal, sizeof equal, "%.0f", r->pt_equal_ms);
            snprintf(speed, sizeof speed, "%.1fx", r->speedup);
        }
        fprintf(fp, "| %s | %s | %.1f | %.1f | %.5f | %.5f | %.4f | %.3f | %.5f | %.3f | %s | %s | %s | %s |\n",
                r->graph, r->params[0] ? r->params : "-", r->ms, (double)r->gi_bytes / 1048576.0, r->full.rel_mse,
                r->full.rmse, r->full.ssim, r->full.mean_luminance_ratio, r->indirect.rel_mse,
                r->indirect.mean_luminance_ratio, equal, speed, pareto, r->pass_ms);
    }
    fprintf(fp, "\n");
}

static bool
write_markdown(const bench_config *c, const bench_rows *rows, const bench_scene *scenes, int scene_count,
               cg_error *err)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/bench.md", c->out_dir);
    cg_atomic_file f;
    if (!cg_atomic_open(&f, path, err))
        return false;
    for (int s = 0; s < scene_count; s++) {
        write_markdown_table(f.fp, c, rows, scenes, s);
        write_markdown_table(stdout, c, rows, scenes, s);
    }
    return cg_atomic_commit(&f, err);
}

/* Per scene: relMSE against time (GI settings by graph, the path tracer's curve, the Pareto
 * front) and against GI memory. */
static bool
write_plots(const bench_config *c, const bench_rows *rows, const bench_scene *scenes, int s, cg_error *err)
{
    static const float palette[6][3] = { { 0.12f, 0.47f, 0.71f }, { 1.0f, 0.5f, 0.05f }, { 0.17f, 0.63f, 0.17f },
                                         { 0.58f, 0.4f, 0.74f }, { 0.55f, 0.34f, 0.29f }, { 0.89f, 0.47f, 0.76f } };
    int n = rows->count;
    double *buf = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1) * 8);
    plot_series *series = calloc((size_t)BENCH_MAX_SETTINGS + 2, sizeof *series);
    if (!buf || !series) {
        free(buf);
        free(series);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "bench plots");
    }
    bool ok = true;
    for (int kind = 0; kind < 2 && ok; kind++) {
        bool time_axis = kind == 0;
        double *x = buf, *y = buf + n, *px = buf + 2 * n, *py = buf + 3 * n, *fx = buf + 4 * n, *fy = buf + 5 * n;
        int used = 0, series_count = 0, pn = 0, fn = 0;
        /* One series per graph file, in order of first appearance. */
        const char *graphs[BENCH_MAX_SETTINGS];
        int graph_count = 0;
        for (int i = 0; i < n; i++) {
            const bench_row *r = &rows->rows[i];
            if (r->scene != s || r->is_pt)
                continue;
            bool seen = false;
            for (int g = 0; g < graph_count; g++)
                seen |= !strcmp(graphs[g], r->graph);
            if (!seen && graph_count < BENCH_MAX_SETTINGS)
                graphs[graph_count++] = r->graph;
        }
        for (int g = 0; g < graph_count; g++) {
            int start = used;
            for (int i = 0; i < n; i++) {
                const bench_row *r = &rows->rows[i];
                if (r->scene != s || r->is_pt || strcmp(r->graph, graphs[g]))
                    continue;
                x[used] = time_axis ? r->ms : (double)r->gi_bytes / 1048576.0;
                y[used++] = r->full.rel_mse;
            }
            plot_series *ser = &series[series_count++];
            ser->name = graphs[g];
            memcpy(ser->color, palette[g % 6], sizeof ser->color);
            ser->x = x + start;
            ser->y = y + start;
            ser->count = used - start;
        }
        for (int i = 0; i < n; i++) {
            const bench_row *r = &rows->rows[i];
            if (r->scene != s)
                continue;
            if (r->is_pt && time_axis) {
                px[pn] = r->ms;
                py[pn++] = r->full.rel_mse;
            }
            if (!r->is_pt && (time_axis ? r->pareto_time : r->pareto_memory)) {
                fx[fn] = time_axis ? r->ms : (double)r->gi_bytes / 1048576.0;
                fy[fn++] = r->full.rel_mse;
            }
        }
        if (pn > 0)
            series[series_count++] = (plot_series){ .name = "path tracer (spp sweep)", .color = { 0.45f, 0.45f, 0.45f },
                                                    .x = px, .y = py, .count = pn, .line = true };
        series[series_count++] = (plot_series){ .name = "Pareto front", .color = { 0.85f, 0.1f, 0.1f }, .x = fx,
                                                .y = fy, .count = fn, .line = true, .ring = true };
        char title[512], path[4096], scene_slug[BENCH_TEXT];
        snprintf(title, sizeof title, "%s %dx%d: relMSE vs %s", scenes[s].source, c->width, c->height,
                 time_axis ? "time" : "GI memory");
        slug(scenes[s].source, scene_slug, sizeof scene_slug);
        snprintf(path, sizeof path, "%s/%s-%s.png", c->out_dir, scene_slug, time_axis ? "time" : "memory");
        plot_desc plot = { .title = title, .xlabel = time_axis ? "time per frame (ms)" : "GI memory (MiB)",
                           .ylabel = "relMSE", .logx = time_axis, .logy = true, .series = series,
                           .series_count = series_count };
        ok = plot_write_png(&plot, path, err);
    }
    free(series);
    free(buf);
    return ok;
}

/* ------------------------------------------------------------ main loop */

#define TOOL "conegraph bench"

static int
fail_with(const char *what, const cg_error *err)
{
    return app_fail(TOOL, what, err);
}

static int
settings_run_count(const bench_setting *s)
{
    int n = 1;
    for (int v = 0; v < s->vary_count; v++)
        n *= s->vary[v].count;
    return n;
}

static int
bench(const bench_config *c)
{
    cg_error err = { 0 };
    int code = 1;
    double t_start = app_now_ms();
    bench_scene *scenes = calloc((size_t)c->scene_count, sizeof *scenes);
    bench_rows rows = { 0 };
    int loaded = 0;
    char renderer[256] = "";
    if (!scenes) {
        fprintf(stderr, "conegraph bench: out of memory\n");
        goto done;
    }
    if (!make_dirs(c->out_dir, &err)) {
        code = fail_with(c->out_dir, &err);
        goto done;
    }
    /* Every scene loads before anything is measured, so bad input fails fast. */
    for (int s = 0; s < c->scene_count; s++) {
        bench_scene *bs = &scenes[s];
        bs->source = c->scenes[s];
        app_session_desc desc = { .scene = bs->source, .camera = c->camera[0] ? c->camera : NULL,
                                  .width = c->width, .height = c->height };
        if (!app_session_open(&bs->session, &desc, &err)) {
            code = fail_with(bs->source, &err);
            goto done;
        }
        loaded++;
    }
    cg_context_desc cdesc = { .backend = c->backend, .width = c->width, .height = c->height, .debug = true };
    int total_runs = 0, run = 0;
    for (int k = 0; k < c->setting_count; k++)
        total_runs += settings_run_count(&c->settings[k]);
    total_runs *= c->scene_count;

    for (int s = 0; s < c->scene_count; s++) {
        bench_scene *bs = &scenes[s];
        double t0 = app_now_ms();
        if (!pt_scene_create(&bs->session.scene, &bs->pts, &err)) {
            code = fail_with(bs->source, &err);
            goto done;
        }
        bs->bvh_ms = app_now_ms() - t0;
        /* The direct part needs 1 sample: through pixel centres with 0 bounces nothing is random. */
        if (!reference_image(c, bs, c->ref_spp, c->ref_bounces, &bs->ref, &err) ||
            !reference_image(c, bs, 1, 0, &bs->ref_direct, &err) ||
            !cg_image_subtract(&bs->ref, &bs->ref_direct, &bs->ref_indirect, &err)) {
            code = fail_with(bs->source, &err);
            goto done;
        }
        if (c->images) {
            char path[4096], scene_slug[BENCH_TEXT];
            slug(bs->source, scene_slug, sizeof scene_slug);
            snprintf(path, sizeof path, "%s/%s-reference.png", c->out_dir, scene_slug);
            if (!cg_image_write(path, &bs->ref, CG_EXR_HALF, &err)) {
                code = fail_with(path, &err);
                goto done;
            }
        }
        if (!bench_path_tracer(c, bs, s, &rows, &err)) {
            code = fail_with(bs->source, &err);
            goto done;
        }
        if (!app_session_start_gl(&bs->session, &cdesc, &err)) {
            code = fail_with(bs->source, &err);
            goto done;
        }
        snprintf(renderer, sizeof renderer, "%s", cg_context_renderer(bs->session.ctx));
        for (int k = 0; k < c->setting_count; k++) {
            const bench_setting *set = &c->settings[k];
            int combos = settings_run_count(set);
            for (int combo = 0; combo < combos; combo++) {
                int choice[BENCH_MAX_VARY] = { 0 }, rest = combo;
                for (int v = set->vary_count - 1; v >= 0; v--) {
                    choice[v] = rest % set->vary[v].count;
                    rest /= set->vary[v].count;
                }
                run++;
                cg_error_clear(&err);
                if (!run_setting(c, bs, s, set, choice, &rows, &err)) {
                    code = fail_with(set->graph, &err);
                    goto done;
                }
                const bench_row *r = &rows.rows[rows.count - 1];
                fprintf(stderr, "bench: [%d/%d] %s %s %s: %.1f ms, GI %.1f MiB, relMSE %.5f, lum ratio %.3f\n",
                        run, total_runs, bs->source, r->graph, r->params, r->ms, (double)r->gi_bytes / 1048576.0,
                        r->full.rel_mse, r->full.mean_luminance_ratio);
            }
        }
        app_session_stop_gl(&bs->session);
        for (int i = 0; i < rows.count; i++) {
            bench_row *r = &rows.rows[i];
            if (r->scene != s || r->is_pt)
                continue;
            r->pt_equal_ms = pt_time_for_error(&rows, s, r->full.rel_mse);
            r->speedup = r->pt_equal_ms / r->ms;
        }
        mark_pareto(&rows, s);
        if (!write_plots(c, &rows, scenes, s, &err)) {
            code = fail_with("plots", &err);
            goto done;
        }
    }
    if (!write_csv(c, &rows, scenes, &err) || !write_markdown(c, &rows, scenes, c->scene_count, &err)) {
        code = fail_with(c->out_dir, &err);
        goto done;
    }
    fprintf(stderr, "bench: %d setting(s) on %d scene(s) in %.1f s on %s; wrote %s/bench.csv, bench.md and plots\n",
            total_runs, c->scene_count, (app_now_ms() - t_start) / 1e3, renderer, c->out_dir);
    code = 0;
done:
    for (int s = 0; s < loaded; s++) {
        pt_scene_destroy(scenes[s].pts);
        cg_image_free(&scenes[s].ref);
        cg_image_free(&scenes[s].ref_direct);
        cg_image_free(&scenes[s].ref_indirect);
        app_session_close(&scenes[s].session);
    }
    free(scenes);
    free(rows.rows);
    return code;
}

int
cmd_bench(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            bench_usage(stdout);
            return 0;
        }
    bench_config *c = malloc(sizeof *c);
    if (!c) {
        fprintf(stderr, "conegraph bench: out of memory\n");
        return 1;
    }
    int code = parse_args(argc, argv, c);
    if (!code)
        code = bench(c);
    free(c);
    return code;
}
