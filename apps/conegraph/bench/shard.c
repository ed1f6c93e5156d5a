/* bench: a shard's share of a sweep, bench.json (the rows at full precision), and merging the
 * bench.json of a job array's shards into one table: see bench.h. */
#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "bench.h"
#include "cg/fs.h"

#define TOOL "conegraph bench"
/* 2: rows carry the GI and direct parts, scenes the reference's parts. */
#define SHARD_FORMAT "conegraph-bench-3"

bool
bench_in_shard(const bench_config *c, int run_count, int scene, int run)
{
    long unit = (long)scene * (run_count + 1) + (run + 1);
    return unit % c->shard_count == c->shard - 1;
}

bool
bench_scene_in_shard(const bench_config *c, int run_count, int scene)
{
    for (int run = -1; run < run_count; run++)
        if (bench_in_shard(c, run_count, scene, run))
            return true;
    return false;
}

int
bench_shard_run_count(const bench_config *c, int run_count)
{
    int n = 0;
    for (int s = 0; s < c->scene_count; s++)
        for (int run = 0; run < run_count; run++)
            n += bench_in_shard(c, run_count, s, run);
    return n;
}

/* Appends to a growing text; false when it is full. */
static bool
add(char *text, size_t size, size_t *len, const char *fmt, ...) __attribute__((format(printf, 4, 5)));

static bool
add(char *text, size_t size, size_t *len, const char *fmt, ...)
{
    if (*len >= size)
        return false;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(text + *len, size - *len, fmt, ap);
    va_end(ap);
    if (n < 0)
        return false;
    *len += (size_t)n;
    return *len < size;
}

void
bench_fingerprint(const bench_config *c, char out[17])
{
    /* Everything that changes what is measured, each field tagged so that no two configs give
     * the same text; where it writes (--out, --cache, --images) and the GL backend are left out. */
    static char text[1 << 20];
    size_t len = 0;
    char sky[128];
    cg_sky_format(&c->sky, sky, sizeof sky);
    add(text, sizeof text, &len,
        "size %dx%d|camera %s|sky %s %s|default light %d|frames %d|warmup %d|ref %d %d %d|ref bounces %d %d %d|pt",
        c->width, c->height, c->camera, c->sky_given ? "given" : "not given", sky, !c->no_default_light, c->frames,
        c->warmup, c->ref_spp, c->ref_bounces, c->ref_seed, c->ref_glossy_bounces, c->ref_transmission_bounces,
        (int)c->ref_caustics);
    for (int i = 0; i < c->pt_count; i++)
        add(text, sizeof text, &len, " %d", c->pt_spp[i]);
    for (int i = 0; i < c->scene_count; i++)
        add(text, sizeof text, &len, "|scene %s", c->scenes[i]);
    for (int k = 0; k < c->setting_count; k++) {
        const bench_setting *s = &c->settings[k];
        add(text, sizeof text, &len, "|setting %s", s->graph);
        for (int i = 0; i < s->set_count; i++)
            add(text, sizeof text, &len, "|set %s", s->sets[i]);
        for (int v = 0; v < s->vary_count; v++) {
            add(text, sizeof text, &len, "|vary %s", s->vary[v].param);
            for (int i = 0; i < s->vary[v].count; i++)
                add(text, sizeof text, &len, " %s", s->vary[v].values[i]);
        }
    }
    snprintf(out, 17, "%016llx", (unsigned long long)bench_hash_text(text));
}

/* ------------------------------------------------------------ writing */

/* A figure, or null when it is not finite (JSON has no NaN). */
static json_t *
number(double v)
{
    return isfinite(v) ? json_real(v) : json_null();
}

static json_t *
metrics_json(const cg_metrics *m)
{
    return json_pack("{s:i, s:i, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:I, s:I}", "width", m->width, "height",
                     m->height, "rmse", number(m->rmse), "rel_mse", number(m->rel_mse), "ssim", number(m->ssim),
                     "max_error", number(m->max_error), "mean_luminance_test", number(m->mean_luminance_test),
                     "mean_luminance_ref", number(m->mean_luminance_ref), "mean_luminance_ratio",
                     number(m->mean_luminance_ratio), "nonfinite_pixels", (json_int_t)m->nonfinite_pixels,
                     "nonfinite_test", (json_int_t)m->nonfinite_test);
}

static json_t *
part_json(const cg_part_metrics *m)
{
    return json_pack("{s:i, s:i, s:o, s:o, s:o, s:o, s:o, s:o, s:I}", "width", m->width, "height", m->height, "energy",
                     number(m->energy), "nrmse", number(m->nrmse), "rmse", number(m->rmse), "rms_truth",
                     number(m->rms_truth), "mean_luminance_estimate", number(m->mean_luminance_estimate),
                     "mean_luminance_truth", number(m->mean_luminance_truth), "nonfinite_pixels",
                     (json_int_t)m->nonfinite_pixels);
}

static json_t *
row_json(const bench_row *r)
{
    return json_pack("{s:i, s:b, s:i, s:i, s:i, s:i, s:s, s:s, s:s, s:s, s:s, s:o, s:I, s:I, s:o, s:o, s:b, s:o, s:o}",
                     "scene", r->scene, "is_pt", r->is_pt, "spp", r->spp, "run", r->run, "setting", r->setting,
                     "combo", r->combo, "graph", r->graph, "params", r->params, "label", r->label, "pass_ms",
                     r->pass_ms, "pass_reads", r->pass_reads, "ms", number(r->ms), "gi_bytes", (json_int_t)r->gi_bytes, "peak_bytes",
                     (json_int_t)r->peak_bytes, "full", metrics_json(&r->full), "indirect", metrics_json(&r->indirect),
                     "split", r->split, "gi", part_json(&r->gi), "direct", part_json(&r->direct));
}

/* A scene's entry: its BVH time and what its reference holds, part by part. */
static json_t *
scene_json(const bench_scene *bs)
{
    json_t *parts = json_object();
    for (int k = 0; k < PT_PART_COUNT; k++)
        json_object_set_new(parts, pt_part_name((pt_part)k), number(bs->part_luminance[k]));
    return json_pack("{s:s, s:o, s:o, s:o}", "source", bs->source, "bvh_ms", number(bs->bvh_ms),
                     "reference_mean_luminance", number(bs->ref_luminance), "reference_parts_mean_luminance", parts);
}

bool
bench_write_json(const bench_config *c, const bench_rows *rows, const bench_scene *scenes, const char *renderer,
                 cg_error *err)
{
    char fingerprint[17], path[4096];
    bench_fingerprint(c, fingerprint);
    json_t *scene_list = json_array(), *row_list = json_array();
    for (int s = 0; s < c->scene_count; s++)
        json_array_append_new(scene_list, scene_json(&scenes[s]));
    for (int i = 0; i < rows->count; i++)
        json_array_append_new(row_list, row_json(&rows->rows[i]));
    json_t *root = json_pack("{s:s, s:s, s:[i,i], s:s, s:o, s:o}", "format", SHARD_FORMAT, "sweep", fingerprint,
                             "shard", c->shard, c->shard_count, "renderer", renderer, "scenes", scene_list,
                             "rows", row_list);
    if (!root)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "bench.json");
    snprintf(path, sizeof path, "%s/bench.json", c->out_dir);
    cg_atomic_file f;
    bool ok = cg_atomic_open(&f, path, err);
    if (ok && json_dumpf(root, f.fp, JSON_INDENT(1) | JSON_REAL_PRECISION(17)) != 0) {
        cg_atomic_abort(&f);
        ok = cg_fail(err, CG_ERR_IO, "%s: cannot write", path);
    } else if (ok) {
        fputc('\n', f.fp);
        ok = cg_atomic_commit(&f, err);
    }
    json_decref(root);
    return ok;
}

/* ------------------------------------------------------------ merging */

static double
figure(const json_t *v)
{
    return json_is_number(v) ? json_number_value(v) : NAN;
}

static bool
read_metrics(const json_t *j, cg_metrics *m)
{
    json_t *rmse, *rel, *ssim, *max, *lt, *lr, *ratio;
    json_int_t nonfinite, nonfinite_test;
    if (json_unpack((json_t *)j, "{s:i, s:i, s:o, s:o, s:o, s:o, s:o, s:o, s:o, s:I, s:I}", "width", &m->width,
                    "height", &m->height, "rmse", &rmse, "rel_mse", &rel, "ssim", &ssim, "max_error", &max,
                    "mean_luminance_test", &lt, "mean_luminance_ref", &lr, "mean_luminance_ratio", &ratio,
                    "nonfinite_pixels", &nonfinite, "nonfinite_test", &nonfinite_test) != 0)
        return false;
    m->rmse = figure(rmse);
    m->rel_mse = figure(rel);
    m->ssim = figure(ssim);
    m->max_error = figure(max);
    m->mean_luminance_test = figure(lt);
    m->mean_luminance_ref = figure(lr);
    m->mean_luminance_ratio = figure(ratio);
    m->nonfinite_pixels = (size_t)nonfinite;
    m->nonfinite_test = (size_t)nonfinite_test;
    return true;
}

static bool
read_part(const json_t *j, cg_part_metrics *m)
{
    json_t *energy, *nrmse, *rmse, *rms, *le, *lt;
    json_int_t nonfinite;
    if (json_unpack((json_t *)j, "{s:i, s:i, s:o, s:o, s:o, s:o, s:o, s:o, s:I}", "width", &m->width, "height",
                    &m->height, "energy", &energy, "nrmse", &nrmse, "rmse", &rmse, "rms_truth", &rms,
                    "mean_luminance_estimate", &le, "mean_luminance_truth", &lt, "nonfinite_pixels", &nonfinite) != 0)
        return false;
    m->energy = figure(energy);
    m->nrmse = figure(nrmse);
    m->rmse = figure(rmse);
    m->rms_truth = figure(rms);
    m->mean_luminance_estimate = figure(le);
    m->mean_luminance_truth = figure(lt);
    m->nonfinite_pixels = (size_t)nonfinite;
    return true;
}

static bool
copy_field(char *dst, size_t size, const char *src)
{
    int n = snprintf(dst, size, "%s", src);
    return n >= 0 && (size_t)n < size;
}

/* One row of a shard file; false when it is not one of this sweep's. */
static bool
read_row(const json_t *j, const bench_config *c, int run_count, bench_row *r)
{
    const char *graph, *params, *label, *pass_ms, *pass_reads;
    json_t *ms, *full, *indirect, *gi_part, *direct_part;
    json_int_t gi, peak;
    int is_pt, split;
    memset(r, 0, sizeof *r);
    if (json_unpack((json_t *)j, "{s:i, s:b, s:i, s:i, s:i, s:i, s:s, s:s, s:s, s:s, s:s, s:o, s:I, s:I, s:o, s:o, s:b, s:o, s:o}",
                    "scene", &r->scene, "is_pt", &is_pt, "spp", &r->spp, "run", &r->run, "setting", &r->setting,
                    "combo", &r->combo, "graph", &graph, "params", &params, "label", &label, "pass_ms", &pass_ms,
                    "pass_reads", &pass_reads, "ms",
                    &ms, "gi_bytes", &gi, "peak_bytes", &peak, "full", &full, "indirect", &indirect, "split", &split,
                    "gi", &gi_part, "direct", &direct_part) != 0)
        return false;
    r->is_pt = is_pt;
    r->split = split;
    r->ms = figure(ms);
    r->gi_bytes = (size_t)gi;
    r->peak_bytes = (size_t)peak;
    r->pt_equal_ms = r->speedup = NAN;
    return r->scene >= 0 && r->scene < c->scene_count && r->run >= (r->is_pt ? -1 : 0) && r->run < run_count &&
           (r->is_pt || (r->setting >= 0 && r->setting < c->setting_count)) &&
           copy_field(r->graph, sizeof r->graph, graph) && copy_field(r->params, sizeof r->params, params) &&
           copy_field(r->label, sizeof r->label, label) && copy_field(r->pass_ms, sizeof r->pass_ms, pass_ms) &&
           copy_field(r->pass_reads, sizeof r->pass_reads, pass_reads) &&
           read_metrics(full, &r->full) && read_metrics(indirect, &r->indirect) && read_part(gi_part, &r->gi) &&
           read_part(direct_part, &r->direct);
}

/* Reads one shard file into rows; *shard receives its K, N. Returns 0 or 2 (printed). */
static int
read_shard(const char *dir, const bench_config *c, int run_count, const char *fingerprint, bench_rows *rows,
           bench_scene *scenes, int *shard, int *shard_count, char *renderer, size_t renderer_size)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/bench.json", dir);
    json_error_t jerr;
    json_t *root = json_load_file(path, 0, &jerr);
    if (!root) {
        fprintf(stderr, "%s: --merge: %s:%d:%d: %s\n", TOOL, path, jerr.line, jerr.column, jerr.text);
        return 2;
    }
    const char *format, *sweep, *shard_renderer;
    json_t *scene_list, *row_list, *value;
    int code = 0;
    if (json_unpack(root, "{s:s, s:s, s:[i,i], s:s, s:o, s:o}", "format", &format, "sweep", &sweep, "shard", shard,
                    shard_count, "renderer", &shard_renderer, "scenes", &scene_list, "rows", &row_list) != 0 ||
        strcmp(format, SHARD_FORMAT) || !json_is_array(scene_list) || !json_is_array(row_list)) {
        fprintf(stderr, "%s: --merge: %s: not a bench.json of this version (%s)\n", TOOL, path, SHARD_FORMAT);
        code = 2;
    } else if (strcmp(sweep, fingerprint)) {
        fprintf(stderr, "%s: --merge: %s is of another sweep (%s, this one is %s): merge with the sweep flags "
                "the shards ran with\n", TOOL, path, sweep, fingerprint);
        code = 2;
    }
    size_t i;
    /* A scene's figures from the first shard that rendered its reference. */
    json_array_foreach(code ? NULL : scene_list, i, value) {
        double bvh = figure(json_object_get(value, "bvh_ms"));
        if (i < (size_t)c->scene_count && isfinite(bvh) && !isfinite(scenes[i].bvh_ms)) {
            scenes[i].bvh_ms = bvh;
            scenes[i].ref_luminance = figure(json_object_get(value, "reference_mean_luminance"));
            json_t *parts = json_object_get(value, "reference_parts_mean_luminance");
            for (int k = 0; k < PT_PART_COUNT; k++)
                scenes[i].part_luminance[k] = figure(json_object_get(parts, pt_part_name((pt_part)k)));
        }
    }
    json_array_foreach(code ? NULL : row_list, i, value) {
        bench_row *r = bench_row_add(rows, NULL);
        if (!r || !read_row(value, c, run_count, r)) {
            fprintf(stderr, "%s: --merge: %s: row %zu is not a row of this sweep\n", TOOL, path, i);
            code = 2;
            break;
        }
    }
    if (!code && !renderer[0])
        snprintf(renderer, renderer_size, "%s", shard_renderer);
    else if (!code && strcmp(renderer, shard_renderer))
        fprintf(stderr, "bench: warning: %s ran on %s, another shard on %s: times of different machines are not "
                "comparable\n", path, shard_renderer, renderer);
    json_decref(root);
    return code;
}

/* The order of one unsharded run: scene by scene, the path tracer's rows in --pt-spp order
 * (their combo), then the runs in order. */
static int
row_order(const void *a, const void *b)
{
    const bench_row *x = a, *y = b;
    if (x->scene != y->scene)
        return x->scene < y->scene ? -1 : 1;
    if (x->run != y->run)
        return x->run < y->run ? -1 : 1;
    return (x->combo > y->combo) - (x->combo < y->combo);
}

int
bench_merge(const bench_config *c, int run_count, bench_rows *rows, bench_scene *scenes, char *renderer,
            size_t renderer_size)
{
    char fingerprint[17];
    bench_fingerprint(c, fingerprint);
    int shard_count = 0;
    bool seen[BENCH_MAX_SHARDS] = { false };
    for (int s = 0; s < c->scene_count; s++) {
        scenes[s].bvh_ms = scenes[s].ref_luminance = NAN;
        for (int k = 0; k < PT_PART_COUNT; k++)
            scenes[s].part_luminance[k] = NAN;
    }
    renderer[0] = '\0';
    for (int i = 0; i < c->merge_count; i++) {
        int k, n;
        int code = read_shard(c->merge[i], c, run_count, fingerprint, rows, scenes, &k, &n, renderer, renderer_size);
        if (code)
            return code;
        if (i == 0)
            shard_count = n;
        if (n != shard_count || k < 1 || k > n || n > BENCH_MAX_SHARDS || seen[k - 1]) {
            fprintf(stderr, "%s: --merge: %s holds shard %d/%d; the shards must be 1/%d to %d/%d, each once\n", TOOL,
                    c->merge[i], k, n, shard_count, shard_count, shard_count);
            return 2;
        }
        seen[k - 1] = true;
    }
    for (int k = 0; k < shard_count; k++)
        if (!seen[k]) {
            fprintf(stderr, "%s: --merge: shard %d/%d is missing\n", TOOL, k + 1, shard_count);
            return 2;
        }
    long expected = (long)c->scene_count * (c->pt_count + run_count);
    if (rows->count != expected) {
        fprintf(stderr, "%s: --merge: the shards hold %d rows; the sweep has %ld\n", TOOL, rows->count, expected);
        return 2;
    }
    qsort(rows->rows, (size_t)rows->count, sizeof *rows->rows, row_order);
    return 0;
}
