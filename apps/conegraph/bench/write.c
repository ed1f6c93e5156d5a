/* bench: the writers: tables (CSV, Markdown), plots (PNG, apps/conegraph/bench/plot.c) and
 * images (each run's image and error heat map, the reference): see bench.h. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "bench.h"
#include "cg/fs.h"
#include "plot.h"

void
bench_slug(const char *text, char *out, size_t size)
{
    size_t n = 0;
    for (const char *s = text; *s && n + 1 < size; s++)
        out[n++] = isalnum((unsigned char)*s) || *s == '.' ? *s : '-';
    out[n] = '\0';
}

static bool
write_csv(const bench_config *c, const bench_rows *rows, const bench_scene *scenes, cg_error *err)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/bench.csv", c->out_dir);
    cg_atomic_file f;
    if (!cg_atomic_open(&f, path, err))
        return false;
    /* The columns after pareto_memory came later: appended, so that the old ones keep their places. */
    fprintf(f.fp, "scene,width,height,method,params,ms,pass_ms,gi_bytes,peak_bytes,rmse,relmse,ssim,max_error,"
                  "lum_ratio,nonfinite,indirect_rmse,indirect_relmse,indirect_ssim,indirect_lum_ratio,"
                  "pt_equal_error_ms,speedup,pareto_time,pareto_memory,gi_energy,gi_nrmse,direct_energy,"
                  "direct_nrmse,error_metric,pass_reads\n");
    for (int i = 0; i < rows->count; i++) {
        const bench_row *r = &rows->rows[i];
        app_csv_field(f.fp, scenes[r->scene].source);
        fprintf(f.fp, ",%d,%d,", c->width, c->height);
        app_csv_field(f.fp, r->graph);
        fputc(',', f.fp);
        app_csv_field(f.fp, r->params);
        fprintf(f.fp, ",%.3f,", r->ms);
        app_csv_field(f.fp, r->pass_ms);
        fprintf(f.fp, ",%zu,%zu,%.6g,%.6g,%.6f,%.6g,%.6f,%zu,%.6g,%.6g,%.6f,%.6f,%.3f,%.3f,%d,%d,%.6g,%.6g,%.6g,%.6g,%s,",
                r->gi_bytes, r->peak_bytes, r->full.rmse, r->full.rel_mse, r->full.ssim, r->full.max_error,
                r->full.mean_luminance_ratio, r->full.nonfinite_pixels, r->indirect.rmse, r->indirect.rel_mse,
                r->indirect.ssim, r->indirect.mean_luminance_ratio, r->pt_equal_ms, r->speedup,
                !r->is_pt && r->pareto_time, !r->is_pt && r->pareto_memory, r->gi.energy, r->gi.nrmse,
                r->direct.energy, r->direct.nrmse, c->error == BENCH_ERROR_GI_NRMSE ? "gi-nrmse" : "relmse");
        app_csv_field(f.fp, r->pass_reads);
        fputc('\n', f.fp);
    }
    return cg_atomic_commit(&f, err);
}

/* A figure for the Markdown table: "-" when there is none (NaN), "inf" for an infinite one
 * (an energy or nRMSE against a truth of 0). */
static const char *
cell(char *buf, size_t size, const char *fmt, double v)
{
    if (isnan(v))
        snprintf(buf, size, "-");
    else if (isinf(v))
        snprintf(buf, size, "%sinf", v < 0 ? "-" : "");
    else
        snprintf(buf, size, fmt, v);
    return buf;
}

/* What the reference holds, part by part: the truths of the GI and direct columns. */
static void
write_reference_parts(FILE *fp, const bench_scene *bs)
{
    if (!isfinite(bs->ref_luminance) || !(bs->ref_luminance > 0.0))
        return;
    fprintf(fp, "Reference mean luminance %.4g: emitted %.1f%%, direct punctual %.1f%%, direct emitters %.1f%%, "
                "direct sky %.1f%%, indirect %.1f%%. A graph's direct image (its final composite's direct + emissive) "
                "is judged against emitted + direct punctual; its GI part (its image minus that) against the rest.\n\n",
            bs->ref_luminance, 100.0 * bs->part_luminance[PT_PART_EMITTED] / bs->ref_luminance,
            100.0 * bs->part_luminance[PT_PART_DIRECT_PUNCTUAL] / bs->ref_luminance,
            100.0 * bs->part_luminance[PT_PART_DIRECT_EMITTERS] / bs->ref_luminance,
            100.0 * bs->part_luminance[PT_PART_DIRECT_SKY] / bs->ref_luminance,
            100.0 * bs->part_luminance[PT_PART_INDIRECT] / bs->ref_luminance);
}

static void
write_markdown_table(FILE *fp, const bench_config *c, const bench_rows *rows, const bench_scene *scenes, int s)
{
    const char *error = bench_error_name(c->error);
    fprintf(fp, "### %s, %dx%d\n\n", scenes[s].source, c->width, c->height);
    fprintf(fp, "Reference: path_trace, %d spp, %d bounce(s) (glossy %d, transmission %d, caustics %s), seed %d "
                "(BVH build %.0f ms). Times: median of %d frames after %d warm-up, synchronous. "
                "P: on its graph's own Pareto front of %s against time (t) or GI memory (m).\n\n",
            c->ref_spp, c->ref_bounces, c->ref_glossy_bounces, c->ref_transmission_bounces,
            c->ref_caustics ? "on" : "off", c->ref_seed, scenes[s].bvh_ms, c->frames, c->warmup, error);
    write_reference_parts(fp, &scenes[s]);
    fprintf(fp, "| method | parameters | ms | GI MiB | relMSE | RMSE | SSIM | lum. ratio | indirect relMSE | "
                "indirect lum. ratio | GI energy | GI nRMSE | direct energy | direct nRMSE | PT ms at equal %s | "
                "speed-up | P | per pass (ms) | texture reads |\n", error);
    fprintf(fp, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|\n");
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
        char ge[32], gn[32], de[32], dn[32];
        fprintf(fp, "| %s | %s | %.1f | %.1f | %.5f | %.5f | %.4f | %.3f | %.5f | %.3f | %s | %s | %s | %s | %s | %s | "
                    "%s | %s | %s |\n",
                r->graph, r->params[0] ? r->params : "-", r->ms, (double)r->gi_bytes / 1048576.0, r->full.rel_mse,
                r->full.rmse, r->full.ssim, r->full.mean_luminance_ratio, r->indirect.rel_mse,
                r->indirect.mean_luminance_ratio, cell(ge, sizeof ge, "%.3f", r->gi.energy),
                cell(gn, sizeof gn, "%.4f", r->gi.nrmse), cell(de, sizeof de, "%.3f", r->direct.energy),
                cell(dn, sizeof dn, "%.4f", r->direct.nrmse), equal, speed, pareto, r->pass_ms,
                r->pass_reads[0] ? r->pass_reads : "-");
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

bool
bench_write_tables(const bench_config *c, const bench_rows *rows, const bench_scene *scenes, int scene_count,
                   cg_error *err)
{
    return write_csv(c, rows, scenes, err) && write_markdown(c, rows, scenes, scene_count, err);
}

/* The legend of a setting: its graph, its fixed assignments and what it varies
 * ("vct.json, cones varied"); the points carry the varied values. */
static void
setting_legend(const bench_setting *s, char *out, size_t size)
{
    size_t len = (size_t)snprintf(out, size, "%s", s->graph);
    for (int i = 0; i < s->set_count && len < size; i++)
        len += (size_t)snprintf(out + len, size - len, "%s%s", i ? " " : ", ", s->sets[i]);
    for (int v = 0; v < s->vary_count && len < size; v++) {
        const char *dot = strrchr(s->vary[v].param, '.');
        len += (size_t)snprintf(out + len, size - len, "%s%s", v ? " and " : ", ", dot ? dot + 1 : s->vary[v].param);
    }
    if (s->vary_count && len < size)
        snprintf(out + len, size - len, " varied");
}

/* Eight colours that stay apart (Tableau 10 without its red, which rings the Pareto fronts, and
 * its grey, the path tracer's), sRGB. */
static const float palette[8][3] = {
    { 0.12f, 0.47f, 0.71f }, { 1.0f, 0.5f, 0.05f }, { 0.17f, 0.63f, 0.17f }, { 0.58f, 0.4f, 0.74f },
    { 0.55f, 0.34f, 0.29f }, { 0.89f, 0.47f, 0.76f }, { 0.74f, 0.74f, 0.13f }, { 0.09f, 0.75f, 0.81f },
};

/* The markers of the methods (graph files, in the order the sweep first names them); the
 * path tracer's is PLOT_CROSS, which no graph gets. */
static const plot_marker method_markers[] = { PLOT_SQUARE, PLOT_CIRCLE, PLOT_TRIANGLE, PLOT_DIAMOND, PLOT_PLUS };

/* Whether setting k is the first of its graph file in the sweep. */
static bool
first_of_method(const bench_config *c, int k)
{
    for (int j = 0; j < k; j++)
        if (!strcmp(c->settings[j].graph, c->settings[k].graph))
            return false;
    return true;
}

/* Which method (graph file) setting k is, counted in the order the sweep first names them. */
static int
method_of(const bench_config *c, int k)
{
    int m = 0;
    for (int j = 0; j < c->setting_count; j++) {
        if (!strcmp(c->settings[j].graph, c->settings[k].graph))
            return m;
        m += first_of_method(c, j);
    }
    return m;
}

/* The error a plot shows: relMSE, or the GI part's nrmse (not squared: the table's figure). */
static double
plot_error(const bench_row *r, bench_error error)
{
    return error == BENCH_ERROR_GI_NRMSE ? (r->split ? r->gi.nrmse : NAN) : r->full.rel_mse;
}

/* Per scene: the error --error chooses against time and against GI memory. A series per
 * setting: its colour, its method's marker (a graph file's settings share it), a legend entry
 * each, and every point labelled with its varied values (a setting without: its graph); the
 * path tracer's curve with each point labelled by its samples per pixel (on the time plot);
 * each method's own Pareto front, ringed in red and joined in x order. */
bool
bench_write_plots(const bench_config *c, const bench_rows *rows, const bench_scene *scenes, int s, cg_error *err)
{
    int n = rows->count;
    size_t points = (size_t)(n > 0 ? n : 1);
    double *buf = malloc(sizeof(double) * points * 6);
    plot_marker *markers = malloc(sizeof *markers * points);
    const char **labels = malloc(sizeof *labels * points);
    char (*spp_labels)[32] = malloc(sizeof *spp_labels * points);
    plot_series *series = calloc((size_t)2 * BENCH_MAX_SETTINGS + 2, sizeof *series);
    char (*legends)[512] = calloc((size_t)BENCH_MAX_SETTINGS, sizeof *legends);
    bool ok = buf && markers && labels && spp_labels && series && legends;
    if (!ok)
        cg_fail(err, CG_ERR_OUT_OF_MEMORY, "bench plots");
    for (int kind = 0; kind < 2 && ok; kind++) {
        bool time_axis = kind == 0;
        double *x = buf, *y = buf + n, *px = buf + 2 * n, *py = buf + 3 * n, *fx = buf + 4 * n, *fy = buf + 5 * n;
        int used = 0, series_count = 0, pn = 0, fn = 0;
        for (int k = 0; k < c->setting_count; k++) {
            int start = used;
            plot_marker shape = method_markers[method_of(c, k) % (int)(sizeof method_markers / sizeof method_markers[0])];
            for (int i = 0; i < n; i++) {
                const bench_row *r = &rows->rows[i];
                if (r->scene != s || r->is_pt || r->setting != k)
                    continue;
                x[used] = time_axis ? r->ms : (double)r->gi_bytes / 1048576.0;
                y[used] = plot_error(r, c->error);
                markers[used] = shape;
                labels[used++] = r->label[0] ? r->label : r->graph;
            }
            if (used == start)
                continue;
            setting_legend(&c->settings[k], legends[k], sizeof legends[k]);
            series[series_count++] = (plot_series){ .name = legends[k], .x = x + start, .y = y + start,
                                                    .count = used - start, .markers = markers + start,
                                                    .labels = labels + start };
            memcpy(series[series_count - 1].color, palette[k % 8], sizeof palette[0]);
        }
        int pt_start = used;
        for (int i = 0; i < n; i++) {
            const bench_row *r = &rows->rows[i];
            if (r->scene != s || !r->is_pt || !time_axis)
                continue;
            px[pn] = r->ms;
            py[pn] = plot_error(r, c->error);
            snprintf(spp_labels[pn], sizeof spp_labels[pn], "%d spp", r->spp);
            labels[used] = spp_labels[pn++];
            markers[used++] = PLOT_CROSS;
        }
        if (pn > 0)
            series[series_count++] = (plot_series){ .name = "Path tracer (spp)",
                                                    .color = { 0.45f, 0.45f, 0.45f }, .x = px, .y = py, .count = pn,
                                                    .line = true, .markers = markers + pt_start,
                                                    .labels = labels + pt_start };
        /* Each method's front apart: a line joins only the settings of one graph file. */
        bool front_named = false;
        for (int k = 0; k < c->setting_count; k++) {
            if (!first_of_method(c, k))
                continue;
            int start = fn;
            for (int i = 0; i < n; i++) {
                const bench_row *r = &rows->rows[i];
                if (r->scene != s || r->is_pt || strcmp(r->graph, c->settings[k].graph) ||
                    !(time_axis ? r->pareto_time : r->pareto_memory))
                    continue;
                fx[fn] = time_axis ? r->ms : (double)r->gi_bytes / 1048576.0;
                fy[fn++] = plot_error(r, c->error);
            }
            if (fn == start)
                continue;
            series[series_count++] = (plot_series){ .name = front_named ? NULL : "Pareto front of each graph",
                                                    .color = { 0.85f, 0.1f, 0.1f }, .x = fx + start, .y = fy + start,
                                                    .count = fn - start, .line = true, .ring = true };
            front_named = true;
        }
        char title[512], xlabel[128], ylabel[128], path[4096], scene_slug[BENCH_TEXT];
        snprintf(title, sizeof title, "%s at %dx%d: %s against %s", scenes[s].source, c->width, c->height,
                 bench_error_name(c->error), time_axis ? "time per frame" : "GI memory");
        snprintf(xlabel, sizeof xlabel, "%s", time_axis ? "Time per frame (ms, median)" : "GI memory (MiB)");
        snprintf(ylabel, sizeof ylabel, "%s (lower is better)",
                 c->error == BENCH_ERROR_GI_NRMSE ? "GI nRMSE" : "Full-image relMSE");
        bench_slug(scenes[s].source, scene_slug, sizeof scene_slug);
        snprintf(path, sizeof path, "%s/%s-%s.png", c->out_dir, scene_slug, time_axis ? "time" : "memory");
        plot_desc plot = { .title = title, .xlabel = xlabel, .ylabel = ylabel, .logx = time_axis, .logy = true,
                           .series = series, .series_count = series_count };
        ok = plot_write_png(&plot, path, err);
    }
    free(legends);
    free(series);
    free(spp_labels);
    free(labels);
    free(markers);
    free(buf);
    return ok;
}

bool
bench_write_reference_image(const bench_config *c, const bench_scene *bs, cg_error *err)
{
    char path[4096], scene_slug[BENCH_TEXT];
    bench_slug(bs->source, scene_slug, sizeof scene_slug);
    snprintf(path, sizeof path, "%s/%s-reference.png", c->out_dir, scene_slug);
    return cg_image_write(path, &bs->ref, CG_EXR_HALF, err);
}

bool
bench_write_run_images(const bench_config *c, const bench_scene *bs, const bench_row *row, const cg_image *image,
                       cg_error *err)
{
    char name[2048], path[4096], scene_slug[BENCH_TEXT], params_slug[512];
    bench_slug(bs->source, scene_slug, sizeof scene_slug);
    snprintf(name, sizeof name, "%s%s%s", row->graph, row->params[0] ? " " : "", row->params);
    bench_slug(name, params_slug, sizeof params_slug);
    snprintf(path, sizeof path, "%s/%s-%s.png", c->out_dir, scene_slug, params_slug);
    cg_image heat = { 0 };
    bool ok = cg_image_write(path, image, CG_EXR_HALF, err);
    snprintf(path, sizeof path, "%s/%s-%s-error.png", c->out_dir, scene_slug, params_slug);
    ok = ok && plot_error_heatmap(image, &bs->ref, 1.0, &heat, err) && cg_image_write(path, &heat, CG_EXR_HALF, err);
    cg_image_free(&heat);
    return ok;
}
