/* bench: the flags and the sweep file into a config, the config into runs, and every run
 * validated on every scene before anything renders or any file is made: see bench.h. */
#include <jansson.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cg/image.h"

#include "app_common.h"
#include "bench.h"

#define TOOL "conegraph bench"

static int
usage_error(const char *fmt, const char *arg)
{
    return app_usage_error(TOOL, fmt, arg);
}

/* "conegraph bench: FILE: what"; returns 2. */
static int
sweep_error(const char *path, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static int
sweep_error(const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "%s: %s: ", TOOL, path);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
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

/* "K/N" into the shard fields. */
static bool
parse_shard(const char *text, bench_config *c)
{
    char buf[64];
    long k, n;
    const char *slash = strchr(text, '/');
    if (!slash || (size_t)(slash - text) >= sizeof buf)
        return false;
    memcpy(buf, text, (size_t)(slash - text));
    buf[slash - text] = '\0';
    if (!app_parse_int(buf, 1, BENCH_MAX_SHARDS, &k) || !app_parse_int(slash + 1, 1, BENCH_MAX_SHARDS, &n) || k > n)
        return false;
    c->shard = (int)k;
    c->shard_count = (int)n;
    return true;
}

/* "relmse" or "gi-nrmse" (--error, the sweep's "error"). */
static bool
parse_error(const char *text, bench_error *out)
{
    if (!strcmp(text, "relmse"))
        *out = BENCH_ERROR_RELMSE;
    else if (!strcmp(text, "gi-nrmse"))
        *out = BENCH_ERROR_GI_NRMSE;
    else
        return false;
    return true;
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
    int n;
    if (json_is_string(v))
        n = snprintf(out, size, "%s", json_string_value(v));
    else if (json_is_integer(v))
        n = snprintf(out, size, "%lld", (long long)json_integer_value(v));
    else if (json_is_real(v))
        n = snprintf(out, size, "%.17g", json_real_value(v));
    else if (json_is_boolean(v))
        n = snprintf(out, size, "%s", json_is_true(v) ? "true" : "false");
    else
        return false;
    return n >= 0 && (size_t)n < size;
}

/* root[key], when present, an integer in min..max into *out. */
static int
json_int_field(const char *path, const json_t *root, const char *where, const char *key, long min, long max,
               int *out)
{
    json_t *v = json_object_get(root, key);
    if (!v)
        return 0;
    if (!json_is_integer(v) || json_integer_value(v) < min || json_integer_value(v) > max)
        return sweep_error(path, "%s\"%s\" must be an integer from %ld to %ld", where, key, min, max);
    *out = (int)json_integer_value(v);
    return 0;
}

/* root[key], when present, must be an array of 1..max entries. */
static int
json_array_field(const char *path, const json_t *root, const char *key, size_t max, const char *entries,
                 json_t **out)
{
    *out = json_object_get(root, key);
    if (*out && (!json_is_array(*out) || json_array_size(*out) == 0 || json_array_size(*out) > max))
        return sweep_error(path, "\"%s\" must be a non-empty array of at most %zu %s", key, max, entries);
    return 0;
}

static int
check_known_fields(const char *path, const char *where, const json_t *object, const char *const *known)
{
    const char *key;
    json_t *value;
    json_object_foreach((json_t *)object, key, value) {
        bool ok = false;
        for (int i = 0; known[i]; i++)
            ok |= !strcmp(key, known[i]);
        if (!ok)
            return sweep_error(path, "%sunknown field \"%s\"", where, key);
    }
    return 0;
}

static int
load_setting(const char *path, size_t index, const json_t *value, bench_setting *s)
{
    static const char *const known[] = { "graph", "set", "vary", NULL };
    char where[64], text[BENCH_TEXT];
    snprintf(where, sizeof where, "setting %zu: ", index);
    memset(s, 0, sizeof *s);
    json_t *graph = json_object_get(value, "graph");
    if (!json_is_object(value) || !json_is_string(graph) || !copy_text(s->graph, json_string_value(graph)))
        return sweep_error(path, "each setting must be an object with a string \"graph\"");
    int code = check_known_fields(path, where, value, known);
    if (code)
        return code;
    for (int i = 1; i < 3; i++) {
        json_t *field = json_object_get(value, known[i]);
        if (field && !json_is_object(field))
            return sweep_error(path, "%s\"%s\" must be an object of PASS.PARAM names", where, known[i]);
    }
    const char *key;
    json_t *item;
    json_object_foreach(json_object_get(value, "set"), key, item) {
        if (s->set_count == BENCH_MAX_SETS || !json_scalar_text(item, text, sizeof text) ||
            snprintf(s->sets[s->set_count], BENCH_TEXT, "%s=%s", key, text) >= BENCH_TEXT)
            return sweep_error(path, "%s\"set\" must map at most 16 PASS.PARAM names to scalars", where);
        s->set_count++;
    }
    json_object_foreach(json_object_get(value, "vary"), key, item) {
        if (s->vary_count == BENCH_MAX_VARY || !json_is_array(item) || json_array_size(item) == 0 ||
            json_array_size(item) > BENCH_MAX_VALUES || strlen(key) >= BENCH_TEXT)
            return sweep_error(path, "%s\"vary\" must map at most 4 PASS.PARAM names to arrays of 1 to 16 values",
                               where);
        bench_vary *v = &s->vary[s->vary_count++];
        strcpy(v->param, key);
        size_t k;
        json_t *scalar;
        json_array_foreach(item, k, scalar) {
            if (!json_scalar_text(scalar, v->values[v->count], sizeof v->values[0]))
                return sweep_error(path, "%s\"vary\" values must be strings, numbers or booleans", where);
            v->count++;
        }
    }
    return 0;
}

static int
load_sweep_object(const char *path, const json_t *root, bench_config *c)
{
    static const char *const known[] = { "scenes", "size", "camera", "sky", "default_light", "frames", "warmup",
                                          "reference", "path_tracer_spp", "settings", "error", NULL };
    char text[BENCH_TEXT];
    if (!json_is_object(root))
        return sweep_error(path, "expected a JSON object at the top");
    int code = check_known_fields(path, "", root, known);
    json_t *scenes, *spp, *settings, *value;
    size_t i;
    if (code || (code = json_array_field(path, root, "scenes", BENCH_MAX_SCENES, "strings", &scenes)))
        return code;
    if (scenes) {
        c->scene_count = 0;
        json_array_foreach(scenes, i, value)
            if (!json_is_string(value) || !copy_text(c->scenes[c->scene_count++], json_string_value(value)))
                return sweep_error(path, "\"scenes\" entries must be strings (shorter than 256 bytes)");
    }
    json_t *size = json_object_get(root, "size");
    if (size && (!json_is_string(size) || !app_parse_size(json_string_value(size), &c->width, &c->height)))
        return sweep_error(path, "\"size\" must be a string \"WxH\"");
    json_t *camera = json_object_get(root, "camera");
    if (camera && !(json_scalar_text(camera, text, sizeof text) && copy_text(c->camera, text)))
        return sweep_error(path, "\"camera\" must be a name or an index");
    json_t *sky = json_object_get(root, "sky");
    if (sky) {
        cg_error why = { 0 };
        if (!json_scalar_text(sky, text, sizeof text) || json_is_boolean(sky))
            return sweep_error(path, "\"sky\" must be a string as --sky takes it (or a number)");
        if (!cg_sky_parse(text, &c->sky, &why))
            return sweep_error(path, "\"sky\": %s", why.message);
        c->sky_given = true;
    }
    json_t *error = json_object_get(root, "error");
    if (error && !(json_is_string(error) && parse_error(json_string_value(error), &c->error)))
        return sweep_error(path, "\"error\" must be \"relmse\" or \"gi-nrmse\"");
    json_t *default_light = json_object_get(root, "default_light");
    if (default_light && !json_is_boolean(default_light))
        return sweep_error(path, "\"default_light\" must be true or false");
    if (default_light)
        c->no_default_light = !json_is_true(default_light);
    json_t *ref = json_object_get(root, "reference");
    if (ref && !json_is_object(ref))
        return sweep_error(path, "\"reference\" must be an object { spp, bounces, glossy_bounces, "
                                 "transmission_bounces, caustics, seed }");
    json_t *caustics = ref ? json_object_get(ref, "caustics") : NULL;
    if (caustics && !json_is_boolean(caustics))
        return sweep_error(path, "\"reference\": \"caustics\" must be true or false");
    if (caustics)
        c->ref_caustics = json_is_true(caustics);
    if ((code = json_int_field(path, root, "", "frames", 1, 10000, &c->frames)) ||
        (code = json_int_field(path, root, "", "warmup", 0, 10000, &c->warmup)) ||
        (code = json_int_field(path, ref, "\"reference\": ", "spp", 1, 65536, &c->ref_spp)) ||
        (code = json_int_field(path, ref, "\"reference\": ", "bounces", 0, 16, &c->ref_bounces)) ||
        (code = json_int_field(path, ref, "\"reference\": ", "glossy_bounces", 0, 16, &c->ref_glossy_bounces)) ||
        (code = json_int_field(path, ref, "\"reference\": ", "transmission_bounces", 0, 16,
                               &c->ref_transmission_bounces)) ||
        (code = json_int_field(path, ref, "\"reference\": ", "seed", 0, 2147483647L, &c->ref_seed)) ||
        (code = json_array_field(path, root, "path_tracer_spp", BENCH_MAX_SPP, "counts", &spp)))
        return code;
    if (spp) {
        c->pt_count = 0;
        json_array_foreach(spp, i, value) {
            if (!json_is_integer(value) || json_integer_value(value) < 1 || json_integer_value(value) > 65536)
                return sweep_error(path, "\"path_tracer_spp\" entries must be integers from 1 to 65536");
            c->pt_spp[c->pt_count++] = (int)json_integer_value(value);
        }
    }
    settings = json_object_get(root, "settings");
    if (settings && (!json_is_array(settings) || json_array_size(settings) > BENCH_MAX_SETTINGS))
        return sweep_error(path, "\"settings\" must be an array of at most 64 objects");
    json_array_foreach(settings, i, value)
        if ((code = load_setting(path, i, value, &c->settings[c->setting_count++])))
            return code;
    return 0;
}

static int
load_sweep(const char *path, bench_config *c)
{
    json_error_t jerr;
    json_t *root = json_load_file(path, 0, &jerr);
    if (!root) {
        fprintf(stderr, "%s: %s:%d:%d: %s\n", TOOL, path, jerr.line, jerr.column, jerr.text);
        return 2;
    }
    int code = load_sweep_object(path, root, c);
    json_decref(root);
    return code;
}

/* The integer flags, with their ranges (those of the sweep file's fields). */
typedef struct int_flag {
    const char *name;
    long min, max;
    int *field;
} int_flag;

static const int_flag *
find_int_flag(const int_flag *flags, int count, const char *name)
{
    for (int i = 0; i < count; i++)
        if (!strcmp(name, flags[i].name))
            return &flags[i];
    return NULL;
}

int
bench_parse_args(int argc, char **argv, bench_config *c)
{
    memset(c, 0, sizeof *c);
    c->width = 320;
    c->height = 180;
    c->frames = 5;
    c->warmup = 2;
    c->ref_spp = 1024;
    c->ref_bounces = 1;
    c->ref_glossy_bounces = 1;      /* the path_trace pass's defaults */
    c->ref_transmission_bounces = 4;
    c->ref_caustics = false;
    c->ref_seed = 1;
    c->pt_spp[0] = 1, c->pt_spp[1] = 4, c->pt_spp[2] = 16, c->pt_spp[3] = 64;
    c->pt_count = 4;
    c->shard = c->shard_count = 1;
    strcpy(c->out_dir, "bench-out");
    /* The sweep file first, so that flags override it wherever they appear. */
    for (int i = 1; i + 1 < argc; i++)
        if (!strcmp(argv[i], "--sweep")) {
            int code = load_sweep(argv[i + 1], c);
            if (code)
                return code;
        }
    const int_flag int_flags[] = { { "--frames", 1, 10000, &c->frames }, { "--warmup", 0, 10000, &c->warmup },
                                   { "--ref-spp", 1, 65536, &c->ref_spp }, { "--ref-bounces", 0, 16, &c->ref_bounces },
                                   { "--ref-glossy-bounces", 0, 16, &c->ref_glossy_bounces },
                                   { "--ref-transmission-bounces", 0, 16, &c->ref_transmission_bounces } };
    bool scenes_from_flags = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--images")) {
            c->images = true;
            continue;
        }
        if (!strcmp(a, "--no-default-light")) {
            c->no_default_light = true;
            continue;
        }
        if (!strcmp(a, "--ref-caustics")) {
            c->ref_caustics = true;
            continue;
        }
        if (!strcmp(a, "--merge")) {
            /* The directories up to the next option. */
            int before = c->merge_count;
            while (i + 1 < argc && argv[i + 1][0] != '-') {
                if (c->merge_count == BENCH_MAX_SHARDS)
                    return usage_error("--merge: more than %s directories", "4096");
                c->merge[c->merge_count++] = argv[++i];
            }
            if (c->merge_count == before)
                return usage_error("%s wants one or more directories (the shards' --out)", a);
            continue;
        }
        if (a[0] != '-')
            return usage_error("unexpected argument '%s'", a);
        const char *v = i + 1 < argc ? argv[++i] : NULL;
        if (!v)
            return usage_error("%s needs a value", a);
        const int_flag *option;
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
        } else if (!strcmp(a, "--sky")) {
            cg_error why = { 0 };
            if (!cg_sky_parse(v, &c->sky, &why))
                return usage_error("--sky: %s", why.message);
            c->sky_given = true;
        } else if ((option = find_int_flag(int_flags, (int)(sizeof int_flags / sizeof *int_flags), a))) {
            long n;
            if (!app_parse_int(v, option->min, option->max, &n)) {
                char fmt[128];
                snprintf(fmt, sizeof fmt, "%s wants %ld to %ld, not '%%s'", a, option->min, option->max);
                return usage_error(fmt, v);
            }
            *option->field = (int)n;
        } else if (!strcmp(a, "--error")) {
            if (!parse_error(v, &c->error))
                return usage_error("--error wants relmse or gi-nrmse, not '%s'", v);
        } else if (!strcmp(a, "--shard")) {
            if (!parse_shard(v, c))
                return usage_error("--shard wants K/N with 1 <= K <= N <= 4096, not '%s'", v);
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
    if (c->merge_count && c->shard_count > 1)
        return usage_error("%s", "--merge joins shards; it is not one itself (no --shard with it)");
    if (!c->cache_dir[0] && snprintf(c->cache_dir, BENCH_TEXT, "%s/cache", c->out_dir) >= BENCH_TEXT)
        return usage_error("--out '%s' is too long", c->out_dir);
    return 0;
}

/* The runs of one setting: the product of its vary counts (1 without any). */
static long
combinations(const bench_setting *s)
{
    long n = 1;
    for (int v = 0; v < s->vary_count; v++)
        n *= s->vary[v].count;
    return n;
}

/* Appends "a=b" (a space first unless at the start) to text; false when it does not fit. */
static bool
append_assignment(char *text, size_t size, const char *param, const char *value)
{
    size_t len = strlen(text);
    int n = value ? snprintf(text + len, size - len, "%s%s=%s", len ? " " : "", param, value)
                  : snprintf(text + len, size - len, "%s%s", len ? " " : "", param);
    return n >= 0 && (size_t)n < size - len;
}

int
bench_expand_runs(const bench_config *c, bench_run **runs, int *run_count)
{
    long total = 0;
    for (int k = 0; k < c->setting_count; k++)
        total += combinations(&c->settings[k]);
    *runs = NULL;
    *run_count = 0;
    if (total > BENCH_MAX_RUNS) {
        fprintf(stderr, "%s: the sweep has %ld runs per scene; at most %d\n", TOOL, total, BENCH_MAX_RUNS);
        return 2;
    }
    *runs = calloc((size_t)(total > 0 ? total : 1), sizeof **runs);
    if (!*runs) {
        fprintf(stderr, "%s: out of memory\n", TOOL);
        return 1;
    }
    for (int k = 0; k < c->setting_count; k++) {
        const bench_setting *s = &c->settings[k];
        long combos = combinations(s);
        for (long combo = 0; combo < combos; combo++) {
            bench_run *r = &(*runs)[*run_count];
            r->index = (*run_count)++;
            r->setting = k;
            r->combo = (int)combo;
            long rest = combo;
            for (int v = s->vary_count - 1; v >= 0; v--) {
                r->choice[v] = (int)(rest % s->vary[v].count);
                rest /= s->vary[v].count;
            }
            bool fits = true;
            for (int i = 0; i < s->set_count; i++)
                fits &= append_assignment(r->params, sizeof r->params, s->sets[i], NULL);
            for (int v = 0; v < s->vary_count; v++) {
                const char *value = s->vary[v].values[r->choice[v]];
                fits &= append_assignment(r->params, sizeof r->params, s->vary[v].param, value);
                /* The label drops the pass name: the plot's legend names the graph. */
                const char *dot = strrchr(s->vary[v].param, '.');
                fits &= append_assignment(r->label, sizeof r->label, dot ? dot + 1 : s->vary[v].param, value);
            }
            if (!fits) {
                fprintf(stderr, "%s: %s: its parameters are too long to report\n", TOOL, s->graph);
                return 2;
            }
        }
    }
    return 0;
}

int
bench_run_assignments(const bench_config *c, const bench_run *run, char buf[BENCH_MAX_VARY][2 * BENCH_TEXT],
                      const char *sets[BENCH_MAX_SETS + BENCH_MAX_VARY])
{
    const bench_setting *s = &c->settings[run->setting];
    int n = 0;
    for (int i = 0; i < s->set_count; i++)
        sets[n++] = s->sets[i];
    for (int v = 0; v < s->vary_count; v++) {
        snprintf(buf[v], 2 * BENCH_TEXT, "%s=%s", s->vary[v].param, s->vary[v].values[run->choice[v]]);
        sets[n++] = buf[v];
    }
    return n;
}

/* The pass named by the part of `source` ("final.hdr") before its dot. */
static const fg_pass *
writer_of(const fg_graph *graph, const char *source)
{
    char name[BENCH_TEXT];
    snprintf(name, sizeof name, "%.*s", (int)strcspn(source, "."), source);
    return fg_graph_find_pass(graph, name);
}

void
bench_graph_split(const app_session *s, bench_split *out)
{
    memset(out, 0, sizeof *out);
    const char *image = s->image_source;
    const fg_pass *final = image ? writer_of(s->graph, image) : NULL;
    const char *dot = image ? strrchr(image, '.') : NULL;
    if (!final || strcmp(fg_pass_type_of(final)->name, "composite") || !dot || strcmp(dot + 1, "hdr")) {
        snprintf(out->why, sizeof out->why, "its image %s is not the hdr output of a composite pass",
                 image ? image : "(none)");
        return;
    }
    const char *direct = fg_pass_input_source(final, "direct");
    const char *emissive = fg_pass_input_source(final, "emissive");
    if (!direct) {
        snprintf(out->why, sizeof out->why, "its composite '%s' has no direct input", fg_pass_name(final));
        return;
    }
    out->ok = true;
    snprintf(out->direct, sizeof out->direct, "%s", direct);
    snprintf(out->emissive, sizeof out->emissive, "%s", emissive ? emissive : "");
}

int
bench_validate(const bench_config *c, const bench_run *runs, int run_count, bench_scene *scenes)
{
    cg_error err = { 0 };
    /* Images are read and written throughout: an installation without them fails first. */
    if (!cg_image_io_check(&err))
        return app_fail(TOOL, NULL, &err);
    /* Every scene, then every run on each: a bad one exits 2 before anything renders. */
    for (int s = 0; s < c->scene_count; s++) {
        bench_scene *bs = &scenes[s];
        bs->source = c->scenes[s];
        app_session_desc desc = { .tool = TOOL, .scene = bs->source, .camera = c->camera[0] ? c->camera : NULL,
                                  .width = c->width, .height = c->height, .sky = c->sky_given ? &c->sky : NULL,
                                  .no_default_light = c->no_default_light };
        if (!app_session_open(&bs->session, &desc, &err))
            return app_fail(TOOL, bs->source, &err);
    }
    for (int s = 0; s < c->scene_count; s++)
        for (int i = 0; i < run_count; i++) {
            char buf[BENCH_MAX_VARY][2 * BENCH_TEXT];
            const char *sets[BENCH_MAX_SETS + BENCH_MAX_VARY];
            const bench_setting *setting = &c->settings[runs[i].setting];
            app_graph_desc graph = { .graph = setting->graph, .sets = sets, .image = "hdr" };
            graph.set_count = bench_run_assignments(c, &runs[i], buf, sets);
            if (!app_session_load_graph(&scenes[s].session, &graph, &err) ||
                !app_session_check(&scenes[s].session, &err)) {
                char what[2048];
                snprintf(what, sizeof what, "%s: %s%s%s", scenes[s].source, setting->graph,
                         runs[i].params[0] ? " " : "", runs[i].params);
                return app_fail(TOOL, what, &err);
            }
            /* Once per setting: a graph whose direct image cannot be found has no GI columns. */
            bench_split split;
            bench_graph_split(&scenes[s].session, &split);
            if (s == 0 && runs[i].combo == 0 && !split.ok)
                fprintf(stderr, "%s: %s: %s, so its own direct image cannot be read: its GI and direct "
                        "columns are left empty\n", TOOL, setting->graph, split.why);
        }
    return 0;
}
