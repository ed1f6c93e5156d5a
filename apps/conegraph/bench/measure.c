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
bench_measure_errors(const bench_scene *bs, const cg_image *test, bench_row *row, cg_error *err)
{
    cg_image ind = { 0 };
    if (!cg_metrics_compute(test, &bs->ref, &row->full, err))
        return false;
    bool ok = cg_image_subtract(test, &bs->ref_direct, &ind, err) &&
              cg_metrics_compute(&ind, &bs->ref_indirect, &row->indirect, err);
    cg_image_free(&ind);
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
    cg_image image = { 0 };
    app_session *s = &bs->session;
    /* Checked before anything ran (bench_validate): the compile with GL adds the context's limits. */
    if (!app_session_load_graph(s, &graph, err) || !app_session_compile(s, err) ||
        !app_session_run(s, &frames, &stats, err))
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
        fg_memory_report mem;
        fg_graph_memory_report(s->graph, &mem);
        row->gi_bytes = mem.gi_bytes;
        row->peak_bytes = mem.peak_bytes;
        ok = app_session_read_image(s, s->image_source, false, &image, err) &&
             bench_measure_errors(bs, &image, row, err) &&
             (!c->images || bench_write_run_images(c, bs, row, &image, err));
        if (!ok)
            rows->count--;
    }
    cg_image_free(&image);
    app_frame_stats_free(&stats);
    return ok;
}
