/* bench: what the measured rows say together: the equal-error speed-up over the path tracer
 * and the Pareto fronts of error against time and against GI memory: see bench.h. */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "bench.h"

double
bench_error_value(const bench_row *row, bench_error error)
{
    if (error == BENCH_ERROR_GI_NRMSE)
        return row->split ? row->gi.nrmse * row->gi.nrmse : NAN;
    return row->full.rel_mse;
}

const char *
bench_error_name(bench_error error)
{
    return error == BENCH_ERROR_GI_NRMSE ? "GI nRMSE" : "relMSE";
}

/* Path tracer time to reach error `e`: log-log interpolation between the measured sample
 * counts, the 1/N law beyond them (both errors are MSE-like: relMSE, nrmse squared), at least
 * 1 spp; time proportional to spp at the largest count's cost per sample. */
double
bench_pt_time_for_error(const bench_rows *rows, int scene, bench_error error, double e)
{
    double spp[BENCH_MAX_SPP], err[BENCH_MAX_SPP], per_spp = NAN;
    int n = 0, best = 0;
    for (int i = 0; i < rows->count; i++) {
        const bench_row *r = &rows->rows[i];
        double v = bench_error_value(r, error);
        if (r->scene != scene || !r->is_pt || !(v > 0.0) || !isfinite(v) || n == BENCH_MAX_SPP)
            continue;
        spp[n] = r->spp;
        err[n] = v;
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

/* A setting is on its graph's front when no other setting of the same graph file is at least as
 * good in both error and cost and better in one; one without the error (a graph bench cannot
 * split) is on none. Each method has its own front: a line from direct.json's point to
 * vct.json's would join two methods as if one could slide between them. */
static void
mark_pareto(bench_rows *rows, int scene, bench_error error)
{
    for (int i = 0; i < rows->count; i++) {
        bench_row *p = &rows->rows[i];
        if (p->scene != scene || p->is_pt)
            continue;
        double pe = bench_error_value(p, error);
        bool dominated_t = !isfinite(pe), dominated_m = !isfinite(pe);
        for (int j = 0; j < rows->count; j++) {
            const bench_row *q = &rows->rows[j];
            double qe = bench_error_value(q, error);
            if (j == i || q->scene != scene || q->is_pt || !isfinite(qe) || strcmp(q->graph, p->graph))
                continue;
            if (q->ms <= p->ms && qe <= pe && (q->ms < p->ms || qe < pe))
                dominated_t = true;
            if (q->gi_bytes <= p->gi_bytes && qe <= pe && (q->gi_bytes < p->gi_bytes || qe < pe))
                dominated_m = true;
        }
        p->pareto_time = !dominated_t;
        p->pareto_memory = !dominated_m;
    }
}

void
bench_analyse(const bench_config *c, bench_rows *rows, int scene)
{
    for (int i = 0; i < rows->count; i++) {
        bench_row *r = &rows->rows[i];
        if (r->scene != scene || r->is_pt)
            continue;
        r->pt_equal_ms = bench_pt_time_for_error(rows, scene, c->error, bench_error_value(r, c->error));
        r->speedup = r->pt_equal_ms / r->ms;
    }
    mark_pareto(rows, scene, c->error);
}
