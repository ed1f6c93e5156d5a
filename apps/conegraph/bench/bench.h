/* apps/conegraph/bench/bench.h: `conegraph bench`, split by job; cmd_bench.c runs them in order.
 *
 * Declares: the limits BENCH_MAX_*; bench_vary, bench_setting, bench_config (what to measure);
 *           bench_run (one combination of a setting); bench_scene (a scene with its session and
 *           reference); bench_row, bench_rows (one measured line of the table);
 *   sweep.c      bench_parse_args, bench_expand_runs, bench_run_assignments, bench_validate,
 *                bench_graph_split: flags and sweep file into a config, its runs, and every run
 *                compiled (without GL) on every scene before anything renders or any file is
 *                made, with where each graph's own direct image is;
 *   reference.c  bench_reference, bench_path_tracer, bench_hash_text: the path-traced reference
 *                and its parts (cached), the truths made of them, and the path tracer timed at
 *                each sample count (cg/pt_render.h);
 *   measure.c    bench_measure_run: one run on one scene through the app session: timings, GI
 *                memory, errors against the reference (full image, GI part, direct part);
 *   analysis.c   bench_analyse, bench_error_value: the equal-error speed-up over the path tracer
 *                and the Pareto fronts, by the error --error chooses;
 *   write.c      bench_write_tables, bench_write_plots, bench_write_run_images,
 *                bench_write_reference_image, bench_slug: CSV, Markdown, PNG plots and images;
 *   shard.c      bench_in_shard, bench_scene_in_shard, bench_shard_run_count, bench_fingerprint,
 *                bench_write_json, bench_merge: --shard K/N (a job array's share of the work),
 *                bench.json (every row at full precision) and --merge of shards' bench.json.
 *
 * The parts of an image (docs/metrics.md, "The benchmark"): a graph's own direct image is what
 * its final composite outputs without its `indirect` input (`direct` + `emissive`), read back
 * from the same frame; its GI part is its image minus that. The reference's parts come from
 * the same trace (pt_render_parts): the truth of the direct image is the emitted and
 * direct-punctual parts (what the raster direct pass and the G-buffer's emission stand for),
 * the truth of the GI part is the reference minus them (the bounces, and the once-reflected
 * light of emitters and the sky, which reach a raster graph through its cones).
 *
 * Units of work, for sharding: per scene, the path tracer's timings, then each run, numbered
 * scene by scene; shard K of N takes the units whose number is K-1 modulo N (so consecutive
 * runs, which tend to cost alike, spread over the shards).
 */
#ifndef CONEGRAPH_BENCH_H
#define CONEGRAPH_BENCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "app_session.h"
#include "cg/error.h"
#include "cg/gl.h"
#include "cg/image.h"
#include "cg/metrics.h"
#include "cg/pt_render.h"

#define BENCH_MAX_SCENES 16
#define BENCH_MAX_SETTINGS 64
#define BENCH_MAX_SETS 16
#define BENCH_MAX_VARY 4
#define BENCH_MAX_VALUES 16
#define BENCH_MAX_SPP 16
#define BENCH_MAX_RUNS 4096     /* runs per scene, over all settings and their combinations */
#define BENCH_MAX_SHARDS 4096
#define BENCH_TEXT 256

typedef struct bench_vary {
    char param[BENCH_TEXT];                 /* pass.param */
    char values[BENCH_MAX_VALUES][64];
    int count;
} bench_vary;

/* The error the plots, the Pareto fronts and the equal-error speed-up judge by (--error). */
typedef enum bench_error {
    BENCH_ERROR_RELMSE,                     /* full image relMSE */
    BENCH_ERROR_GI_NRMSE,                   /* nrmse of the GI part */
} bench_error;

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
    bool sky_given;                         /* --sky or the sweep's "sky": the scenes' sky */
    cg_sky sky;
    bool no_default_light;                  /* --no-default-light, or "default_light": false */
    int frames, warmup;
    int ref_spp, ref_bounces, ref_seed;
    int ref_glossy_bounces, ref_transmission_bounces; /* the reference's other bounce limits (pt_settings) */
    bool ref_caustics;
    int pt_spp[BENCH_MAX_SPP];
    int pt_count;
    bench_setting settings[BENCH_MAX_SETTINGS];
    int setting_count;
    char out_dir[BENCH_TEXT];
    char cache_dir[BENCH_TEXT];
    cg_context_backend backend;
    bool images;
    bench_error error;                      /* --error; analysis only, not in the fingerprint */
    int shard, shard_count;                 /* --shard K/N, K from 1; 1/1 without */
    const char *merge[BENCH_MAX_SHARDS];    /* --merge DIR...: shards' output directories */
    int merge_count;
} bench_config;

/* One combination of one setting's varied values: a line of the table per scene. */
typedef struct bench_run {
    int index;                              /* in the list of runs, from 0 */
    int setting;                            /* index into bench_config.settings */
    int choice[BENCH_MAX_VARY];             /* the value of each vary */
    int combo;                              /* which combination of its setting, from 0: its plot marker */
    char params[1024];                      /* fixed, then varied assignments: the table's "parameters" */
    char label[256];                        /* the varied values only ("cones=6"): the plot label */
} bench_run;

typedef struct bench_scene {
    const char *source;
    app_session session;                    /* scene, camera and view at the bench size, registry,
                                             * graph, context */
    pt_scene *pts;
    double bvh_ms;                          /* NAN until measured (a shard may skip the scene) */
    cg_image ref;
    cg_image ref_parts[PT_PART_COUNT];      /* pt_render_parts of the same trace */
    /* The reference's light reflected at most once (emitted + the three direct parts) and the
     * rest: the old indirect columns, which take ref_direct from the setting's image too. */
    cg_image ref_direct, ref_indirect;
    /* The truths of a graph's parts: emitted + direct_punctual, and ref minus that. */
    cg_image truth_direct, truth_gi;
    /* Mean luminance of the reference and of each part (NAN until known): the table's line on
     * what the truths hold; carried by bench.json for --merge. */
    double ref_luminance, part_luminance[PT_PART_COUNT];
} bench_scene;

/* Where a graph's own direct image is read from: the composite that writes its image, its
 * `direct` and `emissive` inputs. */
typedef struct bench_split {
    bool ok;                                /* false: the image is not a composite's hdr */
    char direct[BENCH_TEXT];                /* "pass.output" */
    char emissive[BENCH_TEXT];              /* "" when the composite has none */
    char why[512];                          /* when !ok: what the image is */
} bench_split;

typedef struct bench_row {
    int scene;
    bool is_pt;
    int spp;                                /* path tracer rows */
    int run;                                /* graph rows: which run (-1: a path tracer row) */
    int setting;                            /* graph rows: which setting */
    int combo;                              /* graph rows: which combination of the setting;
                                             * path tracer rows: which --pt-spp */
    char graph[BENCH_TEXT];
    char params[1024];
    char label[256];
    char pass_ms[1024];
    char pass_reads[512];   /* the passes that count texture reads (fg_pass_reads): "gather 1.75 M, 1082 a
                             * pixel", of the last frame measured */
    double ms;              /* median over frames of the sum of the passes' times, or path tracer wall time */
    size_t gi_bytes, peak_bytes;
    cg_metrics full, indirect;      /* indirect: TEST - REF_DIRECT against REF - REF_DIRECT */
    bool split;                     /* gi and direct measured (false: NAN) */
    cg_part_metrics gi;             /* TEST - its own direct image against truth_gi */
    cg_part_metrics direct;         /* its own direct image against truth_direct */
    double pt_equal_ms;     /* path tracer time at the same error (estimated; --error) */
    double speedup;
    bool pareto_time, pareto_memory;
} bench_row;

typedef struct bench_rows {
    bench_row *rows;
    int count, capacity;
} bench_rows;

/* sweep.c ------------------------------------------------------------------------------------ */

/* Flags and the --sweep file into *c. Returns 0, or 2 after printing what is wrong. */
int bench_parse_args(int argc, char **argv, bench_config *c);
/* Every combination of every setting, in order (settings, then the last vary fastest). *runs
 * is allocated here. Returns 0, 1 (out of memory) or 2 (more than BENCH_MAX_RUNS). */
int bench_expand_runs(const bench_config *c, bench_run **runs, int *run_count);
/* The run's "pass.param=value" assignments, fixed then varied, as --set would carry them:
 * sets[i] points into buf or into the config. Returns the count. */
int bench_run_assignments(const bench_config *c, const bench_run *run,
                          char buf[BENCH_MAX_VARY][2 * BENCH_TEXT], const char *sets[BENCH_MAX_SETS + BENCH_MAX_VARY]);
/* Opens every scene's session (scenes[i].session, to be closed by the caller) and compiles
 * every run on every scene without GL: bad scenes, graphs, parameters and outputs found
 * before anything renders. Returns 0, or the exit code after printing the error. */
int bench_validate(const bench_config *c, const bench_run *runs, int run_count, bench_scene *scenes);

/* reference.c -------------------------------------------------------------------------------- */

/* The BVH, the reference and its parts (from the cache, else one trace written to it), and
 * what bench_scene derives from them. */
bool bench_reference(const bench_config *c, bench_scene *bs, cg_error *err);
/* The path tracer at each --pt-spp, timed, compared with the reference (its own direct image:
 * its emitted and direct-punctual parts, from the same trace): one row each. */
bool bench_path_tracer(const bench_config *c, bench_scene *bs, int scene_index, bench_rows *rows, cg_error *err);

/* FNV-1a of a text: cache keys, the sweep's fingerprint. */
uint64_t bench_hash_text(const char *text);

/* measure.c ---------------------------------------------------------------------------------- */

/* A new row at the end of rows (zeroed; speed-up fields NAN), or NULL when out of memory. */
bench_row *bench_row_add(bench_rows *rows, cg_error *err);
/* Metrics of `test` against the reference: full image, the indirect part (the reference's
 * direct part taken from both), and, when `test_direct` (its own direct image) is not NULL,
 * its GI part and its direct part against their truths (else row->split is false). */
bool bench_measure_errors(const bench_scene *bs, const cg_image *test, const cg_image *test_direct, bench_row *row,
                          cg_error *err);
/* Where the loaded graph's own direct image is, from its last compile (check or compile). */
void bench_graph_split(const app_session *s, bench_split *out);
/* Runs `run` on the scene's session (its GL started): one row; with --images, its image and
 * error map are written. */
bool bench_measure_run(const bench_config *c, bench_scene *bs, int scene_index, const bench_run *run,
                       bench_rows *rows, cg_error *err);

/* analysis.c --------------------------------------------------------------------------------- */

/* The row's error by `error`, as a quantity that falls as 1/N with a path tracer's samples:
 * relMSE, or the GI part's nrmse squared. NAN when the row has none. */
double bench_error_value(const bench_row *row, bench_error error);
/* "relMSE", "GI nRMSE": for titles and tables. */
const char *bench_error_name(bench_error error);
/* Fills pt_equal_ms, speedup and the Pareto flags of the scene's graph rows, by c->error. */
void bench_analyse(const bench_config *c, bench_rows *rows, int scene);
/* Path tracer time to reach error `e` (a bench_error_value) on the scene: log-log interpolation
 * between the measured sample counts, the 1/N law beyond them, at least 1 spp. NAN without
 * path tracer rows. */
double bench_pt_time_for_error(const bench_rows *rows, int scene, bench_error error, double e);

/* write.c ------------------------------------------------------------------------------------ */

/* "builtin:openworld?triangles=10000" -> "builtin-openworld-triangles-10000". */
void bench_slug(const char *text, char *out, size_t size);
/* OUT/bench.csv and OUT/bench.md (atomically); the Markdown tables also to stdout. */
bool bench_write_tables(const bench_config *c, const bench_rows *rows, const bench_scene *scenes,
                        int scene_count, cg_error *err);
/* OUT/SCENE-time.png and OUT/SCENE-memory.png: the error --error chooses against time and memory. */
bool bench_write_plots(const bench_config *c, const bench_rows *rows, const bench_scene *scenes, int scene,
                       cg_error *err);
/* OUT/SCENE-reference.png. */
bool bench_write_reference_image(const bench_config *c, const bench_scene *bs, cg_error *err);
/* OUT/SCENE-GRAPH-PARAMS.png and its error heat map OUT/SCENE-GRAPH-PARAMS-error.png. */
bool bench_write_run_images(const bench_config *c, const bench_scene *bs, const bench_row *row,
                            const cg_image *image, cg_error *err);

/* shard.c ------------------------------------------------------------------------------------ */

/* Whether this shard measures run `run` (-1: the path tracer's timings) of scene `scene`. */
bool bench_in_shard(const bench_config *c, int run_count, int scene, int run);
/* Whether it measures anything of the scene (then it needs the scene's reference). */
bool bench_scene_in_shard(const bench_config *c, int run_count, int scene);
/* How many runs (path tracer timings left out) this shard measures over all scenes. */
int bench_shard_run_count(const bench_config *c, int run_count);
/* 16 hex digits naming what a sweep measures (scenes, size, camera, frames, reference, path
 * tracer counts, settings), not where it writes: shards of one sweep share it. */
void bench_fingerprint(const bench_config *c, char out[17]);
/* OUT/bench.json: the sweep's fingerprint, the shard, the scenes, the renderer and every row at
 * full precision (non-finite figures as null), written atomically. */
bool bench_write_json(const bench_config *c, const bench_rows *rows, const bench_scene *scenes,
                      const char *renderer, cg_error *err);
/* Reads DIR/bench.json of each --merge directory: they must be shards 1..N of this sweep, each
 * once, together holding every unit. Fills rows (in the order one unsharded run gives), each
 * scene's bvh_ms and the renderer. Returns 0, or 2 after printing what is wrong. */
int bench_merge(const bench_config *c, int run_count, bench_rows *rows, bench_scene *scenes, char *renderer,
                size_t renderer_size);

#endif
