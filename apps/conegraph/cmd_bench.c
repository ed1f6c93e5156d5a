/* conegraph bench: the speed/accuracy/memory trade of GI settings against the path-traced
 * reference. For each scene: the reference and its parts (cached on disk), the path tracer's
 * own error against its sample count, then every graph setting of the sweep: per-pass
 * milliseconds (median over frames after warm-up), GI memory, error (full image, indirect
 * part, the GI part and the direct part each against its own truth) and the equal-error
 * speed-up over the path tracer. Writes CSV, Markdown and PNG plots.
 *
 * The jobs live in bench/ (bench.h): reading and validating the sweep, the reference and the
 * path tracer, measuring each setting, the analysis, the writers. This file runs them in order. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cg/fs.h"
#include "cg/progress.h"

#include "app_common.h"
#include "bench/bench.h"
#include "commands.h"

#define TOOL "conegraph bench"

void
cmd_bench_usage(FILE *out)
{
    fprintf(out,
        "usage: conegraph bench [--sweep FILE.json] [--scene SCENE]... [--graph FILE\n"
        "                       [--set PASS.PARAM=V]... [--vary PASS.PARAM=V1,V2,...]...]...\n"
        "                       [--shard K/N | --merge DIR...] [options]\n"
        "\n"
        "Measures every setting of a sweep against the path-traced reference and writes\n"
        "OUT/bench.csv, OUT/bench.md, OUT/bench.json (every row at full precision) and, per\n"
        "scene, OUT/SCENE-time.png and OUT/SCENE-memory.png (the --error against time per frame\n"
        "and against GI memory: a colour and a legend entry per setting, a marker per method\n"
        "(graph file), every point labelled with its varied values, the path tracer's with its\n"
        "samples per pixel; each graph's own Pareto front ringed in red and joined). With\n"
        "--images, each error heat map has its colour scale beneath it.\n"
        "\n"
        "Every setting is first compiled (without GL) on every scene: one bad scene, graph,\n"
        "parameter or value exits 2 before anything renders and before OUT is made.\n"
        "\n"
        "Per scene: the reference (path_trace at --ref-spp, --ref-bounces; pixel centres like the\n"
        "raster camera) and its parts from the same trace (emitted, direct_punctual,\n"
        "direct_emitters, direct_sky, indirect) are rendered once and cached in the cache\n"
        "directory; the path tracer is timed at each --pt-spp against the reference; then each\n"
        "setting runs --warmup frames and --frames timed frames (synchronous timing: glFinish and\n"
        "a CPU clock around each pass) and is compared with the reference:\n"
        "  full      the image (relMSE, RMSE, SSIM, lum. ratio)\n"
        "  indirect  TEST - REF_DIRECT against REF - REF_DIRECT, REF_DIRECT the light reflected at\n"
        "            most once: the reference's direct light taken from both (shadow-map edges count)\n"
        "  GI        the setting's GI alone, each side's own direct light taken away: its image minus\n"
        "            its own direct image (its final composite's direct + emissive inputs, read back\n"
        "            from the same frame) against the reference minus its emitted and direct_punctual\n"
        "            parts (the bounces, and the once-reflected light of emitters and the sky, which\n"
        "            reach a raster graph through its cones)\n"
        "  direct    the setting's own direct image against emitted + direct_punctual: the raster\n"
        "            direct pass's error (shadow map), apart from the GI's\n"
        "  GI and direct give energy (mean luminance / the truth's: 1 is right, 0 none) and nRMSE\n"
        "  (rmse(estimate - truth) / rms(truth): 0 is the truth, 1 no better than leaving the part\n"
        "  out, as direct.json's GI does exactly). Path tracer rows are split by their own parts.\n"
        "  A graph whose image is not a composite's hdr has no GI and direct figures (a notice).\n"
        "The equal-error speed-up is the path tracer's time to reach the setting's error\n"
        "(--error; interpolated log-log between the measured sample counts, extrapolated with the\n"
        "1/N law of relMSE and of nRMSE squared) over the setting's frame time.\n"
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
        "  --camera NAME|INDEX|auto  scene camera (default the first; auto: framed from the bounds)\n"
        "  --sky SKY             the scenes' sky, as render --sky takes it; without it, the sky the\n"
        "                        settings' graph files ask for (they must agree: every setting is\n"
        "                        compared with one reference per scene), else none\n"
        "  --no-default-light    no sun and sky for a scene that nothing lights (by default it gets\n"
        "                        them, with a notice, in the reference and in every setting alike)\n"
        "  --frames N            timed frames per setting (default 5; the median is reported)\n"
        "  --warmup N            untimed frames first (default 2: shader JIT, caches)\n"
        "  --ref-spp N           reference samples per pixel (default 1024)\n"
        "  --ref-bounces N       diffuse bounces of the reference (default 1, as the GI graphs)\n"
        "  --ref-glossy-bounces N  glossy bounces of the reference (default 1, as path_trace)\n"
        "  --ref-transmission-bounces N  transmission bounces of the reference (default 4)\n"
        "  --ref-caustics        the reference with caustics (default: none, as path_trace)\n"
        "  --pt-spp LIST         path tracer sample counts to time, e.g. 1,4,16,64 (default)\n"
        "  --error relmse|gi-nrmse  the error of the plots, the Pareto fronts (P) and the\n"
        "                        equal-error speed-up: the full image's relMSE (default) or the GI\n"
        "                        part's nRMSE; the tables carry both either way\n"
        "  --out DIR             output directory (default bench-out), made with its parents;\n"
        "                        checked before any work: a part of it that is a file or a\n"
        "                        directory that cannot take new files exits 2 at once\n"
        "  --cache DIR           reference cache (default OUT/cache); entries are keyed by the\n"
        "                        scene's contents, view, size, spp, bounce limits, caustics, seed\n"
        "                        and tracer version\n"
        "  --images              also write each setting's image, error heat map and the\n"
        "                        reference as PNG (linear radiance, clamped, sRGB-encoded)\n"
        "  --context egl|osmesa|glfw  GL context (default: $CONEGRAPH_CONTEXT, else EGL, then OSMesa)\n"
        "  --shard K/N           measure only the K-th of N shares (a job array's task K, e.g.\n"
        "                        $SLURM_ARRAY_TASK_ID); writes OUT/bench.json (and --images) only.\n"
        "                        A share: per scene, the path tracer's timings and each run, taken\n"
        "                        in turn. Give the shards a shared --cache to render each\n"
        "                        reference once, and one kind of machine (times are compared)\n"
        "  --merge DIR...        read DIR/bench.json of shards 1/N..N/N of the same sweep (the\n"
        "                        same flags and sweep file, --shard left out) and write the\n"
        "                        tables, plots and bench.json of the whole sweep to OUT\n"
        "Pass plugins in the directories of $CONEGRAPH_PLUGIN_PATH are loaded.\n"
        "\n"
        "Sweep file:\n"
        "  { \"scenes\": [\"builtin:cornell\"], \"size\": \"320x180\", \"frames\": 5, \"warmup\": 2,\n"
        "    \"camera\": \"0\", \"sky\": \"0.5,0.6,0.8\", \"default_light\": true, \"error\": \"relmse\",\n"
        "    \"reference\": { \"spp\": 1024, \"bounces\": 1, \"glossy_bounces\": 1,\n"
        "                   \"transmission_bounces\": 4, \"caustics\": false, \"seed\": 1 },\n"
        "    \"path_tracer_spp\": [1, 4, 16, 64],\n"
        "    \"settings\": [ { \"graph\": \"direct.json\" },\n"
        "                  { \"graph\": \"vct.json\", \"set\": { \"gather.cones\": 6 },\n"
        "                    \"vary\": { \"vox.resolution\": [64, 128] } } ] }\n"
        "\n"
        "Exit codes: 0 done, 1 failed while running, 2 bad usage, sweep file, scene, graph or\n"
        "shard files. Each run's figures go to stderr, and so does the progress once the sweep\n"
        "has taken 2 s: its steps are the runs and, per scene, the reference with the path\n"
        "tracer's timings; the time left is the time so far over the steps done times those\n"
        "left. On a terminal it is one line updated in place, into a file one line per step (or\n"
        "per tenth of them) and never a carriage return; none with CONEGRAPH_LOG=warn. The\n"
        "Markdown table goes to stdout as well.\n");
}

/* The sweep's progress (cg/progress.h): its units are every run and, per scene, its reference
 * with the path tracer's timings, so that the time left counts the scenes still to be prepared
 * (a reference renders for seconds, where runs take a fraction of one). The reporter's estimate
 * is linear in units: the time so far over the units done, times those left. */
typedef struct bench_progress {
    cg_progress reporter;
    int units, runs_done, runs_total;
} bench_progress;

/* The units of work of this shard: its runs, and one per scene it measures anything of. */
static int
progress_units(const bench_config *c, int run_count)
{
    int units = bench_shard_run_count(c, run_count);
    for (int s = 0; s < c->scene_count; s++)
        units += bench_scene_in_shard(c, run_count, s);
    return units;
}

/* A line of its own (a run's figures) under a terminal's progress line: that line is wiped
 * first and drawn again by the next update. */
static void
progress_note(const bench_progress *p)
{
    if (p->reporter.terminal && p->reporter.shown)
        fputs("\r\033[K", p->reporter.out);
}

static void
progress_step(bench_progress *p)
{
    p->units++;
    cg_progress_update(&p->reporter, p->units);
}

/* What this shard measures of one scene: its reference, the path tracer's timings and its runs;
 * without shards also the analysis and the plots. */
static bool
measure_scene(const bench_config *c, const bench_run *runs, int run_count, bench_scene *scenes, int s,
              bench_rows *rows, bench_progress *progress, char *renderer, size_t renderer_size, cg_error *err)
{
    bench_scene *bs = &scenes[s];
    if (!bench_scene_in_shard(c, run_count, s))
        return true;
    progress_note(progress); /* the reference's and the path tracer's lines below it */
    if (!bench_reference(c, bs, err) || (c->images && !bench_write_reference_image(c, bs, err)) ||
        (bench_in_shard(c, run_count, s, -1) && !bench_path_tracer(c, bs, s, rows, err)))
        return false;
    progress_step(progress);
    cg_context_desc context = { .backend = c->backend, .width = c->width, .height = c->height, .debug = true };
    for (int i = 0; i < run_count; i++) {
        if (!bench_in_shard(c, run_count, s, i))
            continue;
        if (!bs->session.ctx) {
            if (!app_session_start_gl(&bs->session, &context, err))
                return false;
            snprintf(renderer, renderer_size, "%s", cg_context_renderer(bs->session.ctx));
        }
        if (!bench_measure_run(c, bs, s, &runs[i], rows, err)) {
            char what[2048];
            snprintf(what, sizeof what, "%s %s%s%s", bs->source, c->settings[runs[i].setting].graph,
                     runs[i].params[0] ? " " : "", runs[i].params);
            app_error_prefix(err, what);
            return false;
        }
        progress->runs_done++;
        const bench_row *r = &rows->rows[rows->count - 1];
        progress_note(progress);
        fprintf(stderr, "bench: [%d/%d] %s %s %s: %.1f ms, GI %.1f MiB, relMSE %.5f, lum ratio %.3f, "
                "GI energy %.3f, nRMSE %.3f\n", progress->runs_done, progress->runs_total, bs->source, r->graph,
                r->params, r->ms, (double)r->gi_bytes / 1048576.0, r->full.rel_mse, r->full.mean_luminance_ratio,
                r->gi.energy, r->gi.nrmse);
        progress_step(progress);
    }
    app_session_stop_gl(&bs->session);
    if (c->shard_count > 1)
        return true;
    bench_analyse(c, rows, s);
    return bench_write_plots(c, rows, scenes, s, err);
}

static void
free_scenes(bench_scene *scenes, int count)
{
    for (int s = 0; scenes && s < count; s++) {
        pt_scene_destroy(scenes[s].pts);
        cg_image_free(&scenes[s].ref);
        cg_image_free(&scenes[s].ref_direct);
        cg_image_free(&scenes[s].ref_indirect);
        cg_image_free(&scenes[s].truth_direct);
        cg_image_free(&scenes[s].truth_gi);
        for (int k = 0; k < PT_PART_COUNT; k++)
            cg_image_free(&scenes[s].ref_parts[k]);
        app_session_close(&scenes[s].session);
    }
    free(scenes);
}

/* A sweep, or this shard's share of it. */
static int
bench(const bench_config *c)
{
    cg_error err = { 0 };
    double t_start = app_now_ms();
    bench_run *runs = NULL;
    int run_count = 0;
    bench_rows rows = { 0 };
    bench_scene *scenes = calloc((size_t)c->scene_count, sizeof *scenes);
    int code = scenes ? bench_expand_runs(c, &runs, &run_count) : 1;
    if (!scenes)
        fprintf(stderr, "%s: out of memory\n", TOOL);
    for (int s = 0; !code && s < c->scene_count; s++) {
        scenes[s].bvh_ms = scenes[s].ref_luminance = NAN;
        for (int k = 0; k < PT_PART_COUNT; k++)
            scenes[s].part_luminance[k] = NAN;
    }
    /* Every setting on every scene checked before anything renders or any file is made (all of
     * the sweep in every shard, so that a bad setting stops them all). */
    if (!code)
        code = bench_validate(c, runs, run_count, scenes);
    if (!code) {
        fprintf(stderr, "bench: %d setting(s) on %d scene(s) checked in %.1f s\n", run_count, c->scene_count,
                (app_now_ms() - t_start) / 1e3);
        if (c->shard_count > 1)
            fprintf(stderr, "bench: shard %d/%d: %d of the %d runs\n", c->shard, c->shard_count,
                    bench_shard_run_count(c, run_count), run_count * c->scene_count);
        code = app_make_dirs(c->out_dir, &err) ? 0 : app_fail(TOOL, c->out_dir, &err);
    }
    bench_progress progress = { .runs_total = bench_shard_run_count(c, run_count) };
    char renderer[256] = "";
    if (!code)
        cg_progress_begin(&progress.reporter,
                          &(cg_progress_desc){ .what = "bench", .total = progress_units(c, run_count), .unit = "steps" });
    for (int s = 0; !code && s < c->scene_count; s++)
        if (!measure_scene(c, runs, run_count, scenes, s, &rows, &progress, renderer, sizeof renderer, &err)) {
            progress_note(&progress);
            code = app_fail(TOOL, NULL, &err);
        }
    if (!code)
        cg_progress_end(&progress.reporter);
    /* A shard's rows lack the others' (the path tracer's among them): its tables wait for --merge. */
    if (!code && ((c->shard_count == 1 && !bench_write_tables(c, &rows, scenes, c->scene_count, &err)) ||
                  !bench_write_json(c, &rows, scenes, renderer, &err)))
        code = app_fail(TOOL, c->out_dir, &err);
    if (!code)
        fprintf(stderr, "bench: %d run(s) in %.1f s on %s; wrote %s/%s\n", progress.runs_total,
                (app_now_ms() - t_start) / 1e3, renderer, c->out_dir,
                c->shard_count == 1 ? "bench.csv, bench.md, bench.json and plots" : "bench.json");
    free_scenes(scenes, c->scene_count);
    free(runs);
    free(rows.rows);
    return code;
}

/* --merge: the shards' bench.json into one set of tables, plots and bench.json. */
static int
merge(const bench_config *c)
{
    cg_error err = { 0 };
    bench_run *runs = NULL;
    int run_count = 0;
    bench_rows rows = { 0 };
    char renderer[256];
    bench_scene *scenes = calloc((size_t)c->scene_count, sizeof *scenes);
    int code = scenes ? bench_expand_runs(c, &runs, &run_count) : 1;
    if (!scenes)
        fprintf(stderr, "%s: out of memory\n", TOOL);
    for (int s = 0; !code && s < c->scene_count; s++)
        scenes[s].source = c->scenes[s];
    if (!code)
        code = bench_merge(c, run_count, &rows, scenes, renderer, sizeof renderer);
    if (!code && !app_make_dirs(c->out_dir, &err))
        code = app_fail(TOOL, c->out_dir, &err);
    for (int s = 0; !code && s < c->scene_count; s++) {
        bench_analyse(c, &rows, s);
        if (!bench_write_plots(c, &rows, scenes, s, &err))
            code = app_fail(TOOL, "plots", &err);
    }
    if (!code && (!bench_write_tables(c, &rows, scenes, c->scene_count, &err) ||
                  !bench_write_json(c, &rows, scenes, renderer, &err)))
        code = app_fail(TOOL, c->out_dir, &err);
    if (!code)
        fprintf(stderr, "bench: merged %d shard(s), %d row(s); wrote %s/bench.csv, bench.md, bench.json and plots\n",
                c->merge_count, rows.count, c->out_dir);
    free_scenes(scenes, c->scene_count);
    free(runs);
    free(rows.rows);
    return code;
}

/* Whether the directory `dir` (--out, --cache) can be made where it is asked and take files,
 * checked before any work. The directory is made with its missing parents (mkdir -p), so the
 * question goes to the deepest part of the path that exists: through core's output path check
 * of the first missing part under it (that part's directory exists, is a directory and can take
 * new entries), or of a file inside `dir` itself where it exists. Fails with CG_ERR_OUTPUT_PATH
 * naming the flag and the path as written. */
static bool
output_dir_check(const char *flag, const char *dir, cg_error *err)
{
    char path[4096], probe[4200];
    size_t len = strlen(dir);
    while (len > 1 && dir[len - 1] == '/')
        len--;
    if (len == 0 || len >= sizeof path)
        return cg_fail(err, CG_ERR_OUTPUT_PATH, "%s '%s': %s", flag, dir, len ? "path too long" : "an empty path");
    snprintf(path, sizeof path, "%.*s", (int)len, dir);
    struct stat st;
    if (stat(path, &st) == 0) {
        if (!S_ISDIR(st.st_mode))
            return cg_fail(err, CG_ERR_OUTPUT_PATH, "%s %s: is not a directory", flag, dir);
        snprintf(probe, sizeof probe, "%s/bench.json", path);
    } else {
        /* Up to the deepest existing part; probe is the first missing part below it. */
        snprintf(probe, sizeof probe, "%s", path);
        for (;;) {
            char *slash = strrchr(path, '/');
            if (!slash)
                break;
            if (slash == path) {
                path[1] = '\0';
                break;
            }
            *slash = '\0';
            if (stat(path, &st) == 0)
                break;
            snprintf(probe, sizeof probe, "%s", path);
        }
    }
    cg_error why = { 0 };
    if (cg_output_path_check(probe, NULL, &why))
        return true;
    /* core's message begins with the probed path: give the user's path instead. */
    const char *reason = why.message;
    size_t n = strlen(probe);
    if (!strncmp(reason, probe, n) && !strncmp(reason + n, ": ", 2))
        reason += n + 2;
    return cg_fail(err, CG_ERR_OUTPUT_PATH, "%s %s: %s", flag, dir, reason);
}

int
cmd_bench(int argc, char **argv)
{
    /* Static, not on the stack: the config holds every setting (0.6 MB); one bench a process. */
    static bench_config config;
    int code = bench_parse_args(argc, argv, &config);
    if (code)
        return code;
    /* Where it writes, before the scenes are read and anything renders (exit 2). */
    cg_error err = { 0 };
    if (!output_dir_check("--out", config.out_dir, &err) ||
        (!config.merge_count && !output_dir_check("--cache", config.cache_dir, &err)))
        return app_fail(TOOL, NULL, &err);
    return config.merge_count ? merge(&config) : bench(&config);
}
