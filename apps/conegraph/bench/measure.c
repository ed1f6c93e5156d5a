/* bench: one run of a graph setting on one scene through the app session, measured against
 * the reference: see bench.h. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "bench.h"

bench_row *
bench_row_add(bench_rows *rows, cg_error *err)
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

bool
bench_measure_errors(const bench_scene *bs, const cg_image *test, const cg_image *test_direct, bench_row *row,
                     cg_error *err)
{
    cg_image ind = { 0 }, gi = { 0 };
    if (!cg_metrics_compute(test, &bs->ref, &row->full, err))
        return false;
    bool ok = cg_image_subtract(test, &bs->ref_direct, &ind, err) &&
              cg_metrics_compute(&ind, &bs->ref_indirect, &row->indirect, err);
    row->split = test_direct != NULL;
    if (ok && test_direct)
        ok = cg_image_subtract(test, test_direct, &gi, err) && cg_metrics_part(&gi, &bs->truth_gi, &row->gi, err) &&
             cg_metrics_part(test_direct, &bs->truth_direct, &row->direct, err);
    if (!row->split) {
        row->gi = row->direct = (cg_part_metrics){ .energy = NAN, .nrmse = NAN, .rmse = NAN, .rms_truth = NAN,
                                                   .mean_luminance_estimate = NAN, .mean_luminance_truth = NAN };
    }
    cg_image_free(&ind);
    cg_image_free(&gi);
    return ok;
}

/* The graph's own direct image: composite's direct + emissive, added in float as its shader
 * adds them (the GI term between them is left out), so that for a graph without GI the image
 * minus this is exactly 0. */
static bool
read_direct_image(const app_session *s, const bench_split *split, cg_image *out, cg_error *err)
{
    cg_image emissive = { 0 };
    if (!app_session_read_image(s, split->direct, false, out, err))
        return false;
    if (!split->emissive[0])
        return true;
    bool ok = app_session_read_image(s, split->emissive, false, &emissive, err);
    if (ok && (emissive.width != out->width || emissive.height != out->height))
        ok = cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s is %dx%d, %s %dx%d", split->emissive, emissive.width,
                     emissive.height, split->direct, out->width, out->height);
    size_t n = ok ? (size_t)out->width * (size_t)out->height : 0;
    for (size_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++)
            out->rgba[4 * i + c] += emissive.rgba[4 * i + c];
        out->rgba[4 * i + 3] = 1.0f;
    }
    cg_image_free(&emissive);
    return ok;
}

/* "shadow 8.06, gbuf 2.68, ...": each live pass's median, in execution order. */
static void
format_pass_times(const fg_graph *graph, const app_frame_stats *stats, char *out, size_t size)
{
    const int *order;
    int order_count = fg_graph_order(graph, &order);
    size_t len = 0;
    out[0] = '\0';
    for (int k = 0; k < order_count && len < size; k++) {
        int n = snprintf(out + len, size - len, "%s%s %.2f", len ? ", " : "",
                         fg_pass_name(fg_graph_pass_at(graph, order[k])),
                         app_frame_stats_pass_median(stats, order[k]));
        if (n < 0)
            break;
        len += (size_t)n;
    }
}

bool
bench_measure_run(const bench_config *c, bench_scene *bs, int scene_index, const bench_run *run, bench_rows *rows,
                  cg_error *err)
{
    const bench_setting *setting = &c->settings[run->setting];
    char buf[BENCH_MAX_VARY][2 * BENCH_TEXT];
    const char *sets[BENCH_MAX_SETS + BENCH_MAX_VARY];
    app_graph_desc graph = { .graph = setting->graph, .sets = sets, .image = "hdr" };
    graph.set_count = bench_run_assignments(c, run, buf, sets);
    /* Synchronous timing (glFinish and a CPU clock around each pass): right on llvmpipe. */
    app_run_desc frames = { .warmup = c->warmup, .frames = c->frames, .timing = FG_TIMING_SYNC };
    app_frame_stats stats = { 0 };
    cg_image image = { 0 }, direct = { 0 };
    app_session *s = &bs->session;
    bench_split split;
    fg_memory_report mem;
    bool added;
    /* Checked before anything ran (bench_validate). The graph's memory is reported as it compiles
     * for this frame on its own; then the composite's direct and emissive inputs are kept as
     * outputs, to be read back after the frame (outputs are never pooled, which may change the
     * peak), and the graph is compiled again and prepared. */
    if (!app_session_load_graph(s, &graph, err))
        return false;
    if (!fg_graph_compile(s->graph, &s->frame, &s->compile, err)) {
        app_error_prefix(err, "graph");
        return false;
    }
    fg_graph_memory_report(s->graph, &mem);
    bench_graph_split(s, &split);
    if (split.ok && (!app_session_mark_output(s, split.direct, &added, err) ||
                     (split.emissive[0] && !app_session_mark_output(s, split.emissive, &added, err))))
        return false;
    if (!app_session_compile(s, err) || !app_session_run(s, &frames, &stats, err))
        return false;
    bench_row *row = bench_row_add(rows, err);
    bool ok = row != NULL;
    if (ok) {
        row->scene = scene_index;
        row->run = run->index;
        row->setting = run->setting;
        row->combo = run->combo;
        snprintf(row->graph, sizeof row->graph, "%s", setting->graph);
        snprintf(row->params, sizeof row->params, "%s", run->params);
        snprintf(row->label, sizeof row->label, "%s", run->label);
        row->ms = stats.median_pass_sum_ms;
        format_pass_times(s->graph, &stats, row->pass_ms, sizeof row->pass_ms);
        fg_graph_reads_text(s->graph, row->pass_reads, sizeof row->pass_reads);
        row->gi_bytes = mem.gi_bytes;
        row->peak_bytes = mem.peak_bytes;
        ok = app_session_read_image(s, s->image_source, false, &image, err) &&
             (!split.ok || read_direct_image(s, &split, &direct, err)) &&
             bench_measure_errors(bs, &image, split.ok ? &direct : NULL, row, err) &&
             (!c->images || bench_write_run_images(c, bs, row, &image, err));
        if (!ok)
            rows->count--;
    }
    cg_image_free(&image);
    cg_image_free(&direct);
    app_frame_stats_free(&stats);
    return ok;
}
