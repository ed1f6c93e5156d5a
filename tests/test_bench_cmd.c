/* `conegraph bench` end to end at a tiny size: the sweep runs, CSV, Markdown and plots are
 * written, the reference is cached, and bad input exits with 2. Not a timing test: it
 * checks the instrument, not the figures. The executable comes from $CONEGRAPH_EXE. */
#include <dirent.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cg/image.h"
#include "test_support.h"

/* Runs conegraph with `args`; returns the exit code. */
static int
run(const char *args, char *out, size_t size)
{
    return cg_test_run_conegraph(args, true, out, size);
}

static int
count_lines(const char *path)
{
    FILE *fp = fopen(path, "r");
    assert_non_null(fp);
    int n = 0, c;
    while ((c = fgetc(fp)) != EOF)
        n += c == '\n';
    fclose(fp);
    return n;
}

static void
sweep_runs_and_caches_the_reference(void **state)
{
    (void)state;
    static char out[1 << 16];
    char args[4096], path[4200];
    const char *dir = cg_test_tmpdir();
    snprintf(args, sizeof args,
             "bench --scene builtin:cornell --graph direct.json --vary shadow.resolution=256,512 "
             "--size 32x18 --ref-spp 4 --pt-spp 1,2 --frames 2 --warmup 1 --out '%s/b' --images", dir);
    int code = run(args, out, sizeof out);
    if (code != 0)
        fail_msg("bench exited with %d:\n%s", code, out);
    /* Header, 2 path tracer rows, 2 settings. */
    snprintf(path, sizeof path, "%s/b/bench.csv", dir);
    assert_int_equal(count_lines(path), 5);
    snprintf(path, sizeof path, "%s/b/bench.md", dir);
    assert_true(count_lines(path) > 4);
    const char *plots[] = { "builtin-cornell-time.png", "builtin-cornell-memory.png", "builtin-cornell-reference.png" };
    for (int i = 0; i < 3; i++) {
        snprintf(path, sizeof path, "%s/b/%s", dir, plots[i]);
        cg_image img = { 0 };
        cg_error err = { 0 };
        assert_cg_ok(cg_image_read(path, &img, &err), &err);
        cg_image_free(&img);
    }
    assert_non_null(strstr(out, "shadow.resolution=512"));
    assert_null(strstr(out, "from the cache"));
    /* Again: the reference and its direct part come from the cache. The progress shown from
     * the start (CONEGRAPH_PROGRESS_DELAY=0, at the info log level) goes into the captured output as lines, one per
     * step (the reference with the path tracer, then each run), each with the time left but
     * the last, and never a carriage return. */
    char log_level[32] = "";
    if (getenv("CONEGRAPH_LOG"))
        snprintf(log_level, sizeof log_level, "%s", getenv("CONEGRAPH_LOG"));
    setenv("CONEGRAPH_PROGRESS_DELAY", "0", 1);
    setenv("CONEGRAPH_LOG", "info", 1); /* the suite runs with warn: progress is info */
    code = run(args, out, sizeof out);
    unsetenv("CONEGRAPH_PROGRESS_DELAY");
    if (log_level[0])
        setenv("CONEGRAPH_LOG", log_level, 1);
    else
        unsetenv("CONEGRAPH_LOG");
    assert_int_equal(code, 0);
    assert_null(strchr(out, '\r'));
    assert_non_null(strstr(out, "conegraph: bench: 33% (1/3 steps)"));
    assert_non_null(strstr(out, "conegraph: bench: 66% (2/3 steps)"));
    assert_non_null(strstr(out, "s left\n"));
    assert_non_null(strstr(out, "conegraph: bench: 100% (3/3 steps)"));
    assert_non_null(strstr(out, "reference (4 spp, 1 bounces) and its parts from the cache"));
    assert_null(strstr(out, "rendering the reference"));
    /* A sky is part of the scene: it is not the cached reference (the cache keys hash it). */
    snprintf(args, sizeof args,
             "bench --scene builtin:cornell --graph direct.json --vary shadow.resolution=256,512 "
             "--size 32x18 --ref-spp 4 --pt-spp 1,2 --frames 2 --warmup 1 --out '%s/b' --images --sky 0.5", dir);
    code = run(args, out, sizeof out);
    assert_int_equal(code, 0);
    assert_non_null(strstr(out, "rendering the reference"));
}

/* The scene's light in a sweep: the default light for a scene nothing lights, with its notice
 * (the reference and every setting see the same); graph files that ask for different skies
 * are refused before anything renders, unless --sky chooses one. */
static void
sweep_lights_each_scene_once(void **state)
{
    (void)state;
    static char out[1 << 16];
    char args[8192];
    const char *dir = cg_test_tmpdir();
    snprintf(args, sizeof args, "bench --scene 'builtin:furnace?radiance=0' --graph direct.json --size 16x16 "
             "--ref-spp 1 --pt-spp 1 --frames 1 --warmup 0 --out '%s/dark'", dir);
    int code = run(args, out, sizeof out);
    if (code != 0)
        fail_msg("bench exited with %d:\n%s", code, out);
    assert_non_null(strstr(out, "conegraph bench: scene builtin:furnace?radiance=0 has no light: added a sun"));
    snprintf(args, sizeof args, "bench --scene 'builtin:furnace?radiance=0' --graph direct.json --size 16x16 "
             "--ref-spp 1 --pt-spp 1 --frames 1 --warmup 0 --out '%s/dark2' --no-default-light", dir);
    assert_int_equal(run(args, out, sizeof out), 0);
    assert_null(strstr(out, "added a sun"));
    /* Two graph files asking for two skies. */
    const char *blue = cg_test_write_file("blue.json",
        "{ \"version\": 1, \"sky\": \"0.2,0.3,0.6\",\n"
        "  \"passes\": { \"trace\": { \"type\": \"path_trace\", \"params\": { \"spp\": 1 } },\n"
        "    \"final\": { \"type\": \"composite\", \"inputs\": { \"direct\": \"trace.radiance\" } } },\n"
        "  \"outputs\": [ \"final.hdr\", \"final.ldr\" ] }\n", 0);
    const char *grey = cg_test_write_file("grey.json",
        "{ \"version\": 1, \"sky\": 0.5,\n"
        "  \"passes\": { \"trace\": { \"type\": \"path_trace\", \"params\": { \"spp\": 1 } },\n"
        "    \"final\": { \"type\": \"composite\", \"inputs\": { \"direct\": \"trace.radiance\" } } },\n"
        "  \"outputs\": [ \"final.hdr\", \"final.ldr\" ] }\n", 0);
    snprintf(args, sizeof args, "bench --scene builtin:cornell --graph '%s' --graph '%s' --size 16x16 --ref-spp 1 "
             "--pt-spp 1 --frames 1 --warmup 0 --out '%s/skies'", blue, grey, dir);
    assert_int_equal(run(args, out, sizeof out), 2);
    assert_non_null(strstr(out, "grey.json asks for the sky 0.5, but the scene's sky is 0.2,0.3,0.6"));
    assert_null(strstr(out, "rendering the reference"));
    snprintf(args, sizeof args, "bench --scene builtin:cornell --graph '%s' --graph '%s' --size 16x16 --ref-spp 1 "
             "--pt-spp 1 --frames 1 --warmup 0 --out '%s/skies' --sky 0.1", blue, grey, dir);
    assert_int_equal(run(args, out, sizeof out), 0);
    /* The sweep file's fields. */
    const char *sweep = cg_test_write_file("sky-sweep.json",
        "{ \"scenes\": [\"builtin:furnace?radiance=0\"], \"size\": \"16x16\", \"frames\": 1, \"warmup\": 0,\n"
        "  \"sky\": \"0.5\", \"default_light\": false,\n"
        "  \"reference\": { \"spp\": 1 }, \"path_tracer_spp\": [1],\n"
        "  \"settings\": [ { \"graph\": \"direct.json\" } ] }\n", 0);
    snprintf(args, sizeof args, "bench --sweep '%s' --out '%s/sw'", sweep, dir);
    assert_int_equal(run(args, out, sizeof out), 0);
    assert_null(strstr(out, "added a sun"));
    const char *bad = cg_test_write_file("bad-sky.json", "{ \"sky\": \"purple\" }", 0);
    snprintf(args, sizeof args, "bench --sweep '%s' --out '%s/x'", bad, dir);
    assert_int_equal(run(args, out, sizeof out), 2);
    bad = cg_test_write_file("bad-light.json", "{ \"default_light\": 1 }", 0);
    snprintf(args, sizeof args, "bench --sweep '%s' --out '%s/x'", bad, dir);
    assert_int_equal(run(args, out, sizeof out), 2);
}

static void
sweep_file(void **state)
{
    (void)state;
    static char out[1 << 16];
    const char *sweep = cg_test_write_file("sweep.json",
        "{ \"scenes\": [\"builtin:cornell\"], \"size\": \"24x16\", \"frames\": 1, \"warmup\": 0,\n"
        "  \"reference\": { \"spp\": 2, \"bounces\": 1 }, \"path_tracer_spp\": [1],\n"
        "  \"settings\": [ { \"graph\": \"direct.json\", \"set\": { \"shadow.resolution\": 256 } } ] }\n", 0);
    char args[4096], path[4200];
    snprintf(args, sizeof args, "bench --sweep '%s' --out '%s/s'", sweep, cg_test_tmpdir());
    int code = run(args, out, sizeof out);
    if (code != 0)
        fail_msg("bench exited with %d:\n%s", code, out);
    snprintf(path, sizeof path, "%s/s/bench.csv", cg_test_tmpdir());
    assert_int_equal(count_lines(path), 3);
    assert_non_null(strstr(out, "shadow.resolution=256"));
}

static void
bad_input_exits_with_2(void **state)
{
    (void)state;
    static char out[1 << 16];
    char args[4096];
    const char *dir = cg_test_tmpdir();
    assert_int_equal(run("bench --vary a.b=1,2", out, sizeof out), 2);
    assert_int_equal(run("bench --size 0x10", out, sizeof out), 2);
    assert_int_equal(run("bench --pt-spp 1,x", out, sizeof out), 2);
    const char *bad = cg_test_write_file("bad.json", "{ \"scenes\": [\"builtin:cornell\"], \"nonsense\": 1 }", 0);
    snprintf(args, sizeof args, "bench --sweep '%s' --out '%s/x'", bad, dir);
    assert_int_equal(run(args, out, sizeof out), 2);
    const char *broken = cg_test_write_file("broken.json", "{ \"scenes\": [", 0);
    snprintf(args, sizeof args, "bench --sweep '%s' --out '%s/x'", broken, dir);
    assert_int_equal(run(args, out, sizeof out), 2);
    snprintf(args, sizeof args, "bench --scene builtin:nosuchscene --out '%s/x'", dir);
    assert_int_equal(run(args, out, sizeof out), 2);
    snprintf(args, sizeof args,
             "bench --scene builtin:cornell --graph direct.json --set shadow.nosuchparam=1 --size 16x16 "
             "--ref-spp 1 --pt-spp 1 --out '%s/x'", dir);
    assert_int_equal(run(args, out, sizeof out), 2);
    assert_int_equal(run("bench --help", out, sizeof out), 0);
    assert_non_null(strstr(out, "usage: conegraph bench"));
}

static bool exists(const char *path);

/* --out and --cache are checked before any work: a part of the path that is a file, or (not as
 * root, who may write anywhere) a directory that cannot take new files, exits 2 at once naming
 * the flag and the path as written; nothing renders and no directory is made. A missing
 * directory is not refused: bench makes it with its parents. */
static void
output_dirs_refused_before_work(void **state)
{
    (void)state;
    static char out[1 << 16];
    char args[8192], path[4200];
    const char *dir = cg_test_tmpdir();
    const char *file = cg_test_write_file("not-a-dir", "x", 0);
    const char *sweep = "--scene builtin:cornell --graph direct.json --size 16x16 --ref-spp 1 --pt-spp 1 "
                        "--frames 1 --warmup 0";
    struct { const char *flags, *named; } cases[] = {
        { "--out '%s'", "is not a directory" },
        { "--out '%s/sub/deeper'", "is not a directory" },
        { "--cache '%s/cache' --out '%s/ok'", "is not a directory" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char flags[4096], expected[4200];
        snprintf(flags, sizeof flags, cases[i].flags, file, dir);
        snprintf(args, sizeof args, "bench %s %s", sweep, flags);
        int code = run(args, out, sizeof out);
        /* The flag and its path as the user wrote them. */
        snprintf(expected, sizeof expected, i == 2 ? "--cache %s/cache: " : i == 1 ? "--out %s/sub/deeper: " : "--out %s: ",
                 file);
        if (code != 2 || !strstr(out, expected) || !strstr(out, cases[i].named))
            fail_msg("bench %s exited %d, expected 2 naming '%s' and '%s':\n%s", flags, code, expected,
                     cases[i].named, out);
        assert_null(strstr(out, "rendering the reference"));
        assert_null(strstr(out, "checked in"));
    }
    snprintf(path, sizeof path, "%s/ok", dir);
    assert_false(exists(path));
    if (geteuid() != 0) {
        snprintf(path, sizeof path, "%s/read-only", dir);
        assert_int_equal(mkdir(path, 0555), 0);
        snprintf(args, sizeof args, "bench %s --out '%s/b'", sweep, path);
        assert_int_equal(run(args, out, sizeof out), 2);
        assert_non_null(strstr(out, "is not writable"));
    }
    /* A directory that does not exist yet is made, parents and all. */
    snprintf(args, sizeof args, "bench %s --out '%s/new/nested'", sweep, dir);
    int code = run(args, out, sizeof out);
    if (code != 0)
        fail_msg("bench exited with %d:\n%s", code, out);
    snprintf(path, sizeof path, "%s/new/nested/bench.csv", dir);
    assert_true(exists(path));
}

static int csv_fields(const char *line, char fields[][512], int max);

/* The rows of OUT/bench.json, and the row of `graph` (the first; NULL when none). */
static json_t *
load_rows(const char *dir, json_t **root)
{
    char path[4400];
    snprintf(path, sizeof path, "%.4200s/bench.json", dir);
    json_error_t jerr;
    *root = json_load_file(path, 0, &jerr);
    if (!*root)
        fail_msg("%s: %s", path, jerr.text);
    json_t *rows = json_object_get(*root, "rows");
    assert_true(json_is_array(rows));
    return rows;
}

static json_t *
find_row(json_t *rows, const char *graph, const char *params)
{
    size_t i;
    json_t *row;
    json_array_foreach(rows, i, row)
        if (!strcmp(json_string_value(json_object_get(row, "graph")), graph) &&
            (!params || !strcmp(json_string_value(json_object_get(row, "params")), params)))
            return row;
    fail_msg("no row of %s %s", graph, params ? params : "");
    return NULL;
}

/* A figure of a row's section ("gi", "direct", "full"); NAN for null. */
static double
figure(const json_t *row, const char *section, const char *key)
{
    const json_t *v = json_object_get(json_object_get(row, section), key);
    assert_non_null(v);
    return json_is_number(v) ? json_number_value(v) : NAN;
}

/* The cached image whose note (FILE.txt) names the reference `part` ("full", "emitted", ...). */
static void
cached_part(const char *cache, const char *part, char *out, size_t size)
{
    DIR *d = opendir(cache);
    assert_non_null(d);
    struct dirent *e;
    char suffix[64];
    snprintf(suffix, sizeof suffix, "|%s\n", part);
    out[0] = '\0';
    while ((e = readdir(d))) {
        size_t len = strlen(e->d_name);
        if (len < 8 || strcmp(e->d_name + len - 8, ".exr.txt"))
            continue;
        char note[4600], key[4096] = "";
        snprintf(note, sizeof note, "%s/%s", cache, e->d_name);
        FILE *fp = fopen(note, "r");
        assert_non_null(fp);
        assert_non_null(fgets(key, sizeof key, fp));
        fclose(fp);
        size_t kl = strlen(key), sl = strlen(suffix);
        if (kl >= sl && !strcmp(key + kl - sl, suffix)) {
            snprintf(out, size, "%.*s", (int)(strlen(note) - 4), note);
            break;
        }
    }
    closedir(d);
    if (!out[0])
        fail_msg("no cached reference part '%s' in %s", part, cache);
}

/* The GI and direct columns on a tiny sweep: a graph without GI gives GI energy 0 and nRMSE 1
 * exactly; a GI graph's direct figures are those of the same direct pass without GI (its own
 * direct image, read from its frame); its GI figures are plausible; the path tracer's rows are
 * split by their own parts; the reference's cached parts against themselves give 1 and 0. */
static void
gi_and_direct_columns(void **state)
{
    (void)state;
    static char out[1 << 16];
    char args[32768], dir[4200], cache[4300];
    snprintf(dir, sizeof dir, "%s/gi", cg_test_tmpdir());
    snprintf(cache, sizeof cache, "%s/cache", dir);
    snprintf(args, sizeof args, "bench --scene builtin:cornell --graph direct.json --graph vct.json --size 32x18 "
             "--ref-spp 16 --pt-spp 1,4 --frames 1 --warmup 0 --out '%s'", dir);
    int code = run(args, out, sizeof out);
    if (code != 0)
        fail_msg("bench exited with %d:\n%s", code, out);
    json_t *root, *rows = load_rows(dir, &root);
    json_t *none = find_row(rows, "direct.json", NULL), *vct = find_row(rows, "vct.json", NULL);
    assert_true(json_is_true(json_object_get(none, "split")));
    assert_true(figure(none, "gi", "energy") == 0.0);
    assert_true(figure(none, "gi", "nrmse") == 1.0);
    /* The same direct pass with the same shadow map in both graphs: the same direct image. */
    assert_true(figure(vct, "direct", "energy") == figure(none, "direct", "energy"));
    assert_true(figure(vct, "direct", "nrmse") == figure(none, "direct", "nrmse"));
    assert_true(figure(none, "direct", "energy") > 0.9 && figure(none, "direct", "energy") < 1.1);
    assert_true(figure(none, "direct", "nrmse") > 0.0 && figure(none, "direct", "nrmse") < 0.5);
    /* vct.json gathers light: some, not wildly off (the figures are the GI's to improve). */
    double energy = figure(vct, "gi", "energy"), nrmse = figure(vct, "gi", "nrmse");
    if (!(energy > 0.5 && energy < 2.0 && nrmse > 0.05 && nrmse < 1.0))
        fail_msg("vct.json GI energy %g, nRMSE %g", energy, nrmse);
    /* The truth's rms is the reference's: the same for every row of the scene. */
    assert_true(figure(vct, "gi", "rms_truth") == figure(none, "gi", "rms_truth"));
    assert_true(figure(vct, "gi", "rms_truth") > 0.0);
    /* Path tracer rows: the spot light's direct light through pixel centres has no noise, so
     * their own direct part is the reference's; their GI part's error falls with samples. */
    json_t *pt1 = find_row(rows, "path_trace", "spp=1 bounces=1"), *pt4 = find_row(rows, "path_trace", "spp=4 bounces=1");
    assert_true(figure(pt1, "direct", "nrmse") < 1e-6);
    assert_true(figure(pt4, "gi", "nrmse") < figure(pt1, "gi", "nrmse"));
    json_t *scene = json_array_get(json_object_get(root, "scenes"), 0);
    double lum = json_number_value(json_object_get(scene, "reference_mean_luminance"));
    json_t *parts = json_object_get(scene, "reference_parts_mean_luminance");
    double sum = 0.0;
    const char *names[] = { "emitted", "direct_punctual", "direct_emitters", "direct_sky", "indirect" };
    for (int k = 0; k < 5; k++)
        sum += json_number_value(json_object_get(parts, names[k]));
    assert_float_equal(sum, lum, 1e-5 * lum);
    json_decref(root);

    /* The tables: the old columns kept, the new ones named, the reference's parts described. */
    char path[4400];
    snprintf(path, sizeof path, "%s/bench.md", dir);
    FILE *fp = fopen(path, "r");
    assert_non_null(fp);
    static char md[1 << 15];
    md[fread(md, 1, sizeof md - 1, fp)] = '\0';
    fclose(fp);
    assert_non_null(strstr(md, "| indirect relMSE | indirect lum. ratio | GI energy | GI nRMSE | direct energy | "
                               "direct nRMSE | PT ms at equal relMSE |"));
    assert_non_null(strstr(md, "emitted 0.0%, direct punctual "));
    assert_non_null(strstr(md, "| direct.json | - |"));
    assert_non_null(strstr(md, "| 0.000 | 1.0000 |"));

    /* The reference's cached parts: against itself, energy 1 and nRMSE 0 (compare). */
    char full[4400], emitted[4400], punctual[4400];
    cached_part(cache, "full", full, sizeof full);
    cached_part(cache, "emitted", emitted, sizeof emitted);
    cached_part(cache, "direct_punctual", punctual, sizeof punctual);
    snprintf(args, sizeof args, "compare '%s' '%s' --direct '%s' --direct '%s' --ref-direct '%s' --ref-direct '%s' "
             "--json", full, full, emitted, punctual, emitted, punctual);
    assert_int_equal(cg_test_run_conegraph(args, false, out, sizeof out), 0);
    assert_non_null(strstr(out, "\"energy\": 1, \"nrmse\": 0,"));

    /* --error gi-nrmse judges by the GI part: the tables and the CSV say so. */
    snprintf(args, sizeof args, "bench --scene builtin:cornell --graph direct.json --graph vct.json --size 32x18 "
             "--ref-spp 16 --pt-spp 1,4 --frames 1 --warmup 0 --out '%s/by-gi' --cache '%s' --error gi-nrmse", dir,
             cache);
    code = run(args, out, sizeof out);
    if (code != 0)
        fail_msg("bench exited with %d:\n%s", code, out);
    assert_non_null(strstr(out, "PT ms at equal GI nRMSE"));
    assert_non_null(strstr(out, "P: on its graph's own Pareto front of GI nRMSE against time"));
    assert_non_null(strstr(out, "and its parts from the cache"));
    snprintf(path, sizeof path, "%s/by-gi/bench.csv", dir);
    fp = fopen(path, "r");
    assert_non_null(fp);
    static char line[1 << 14], fields[32][512];
    assert_non_null(fgets(line, sizeof line, fp));
    assert_int_equal(csv_fields(line, fields, 32), 29);
    assert_string_equal(fields[27], "error_metric");
    assert_string_equal(fields[28], "pass_reads");
    assert_non_null(fgets(line, sizeof line, fp));
    csv_fields(line, fields, 32);
    assert_string_equal(fields[27], "gi-nrmse");
    /* The texture reads: vct.json's voxel_light and cone_gather count theirs, direct.json nothing. */
    int graph_rows = 0;
    do {
        csv_fields(line, fields, 32);
        if (!strcmp(fields[3], "vct.json")) {
            graph_rows++;
            assert_non_null(strstr(fields[28], "light 0 M, no voxel; gather "));
            assert_non_null(strstr(fields[28], " a pixel"));
        } else if (!strcmp(fields[3], "direct.json")) {
            graph_rows++;
            assert_string_equal(fields[28], "");
        }
    } while (fgets(line, sizeof line, fp));
    assert_int_equal(graph_rows, 2);
    fclose(fp);
    assert_int_equal(run("bench --error mse", out, sizeof out), 2);
    const char *bad = cg_test_write_file("bad-error.json", "{ \"error\": \"mse\" }", 0);
    snprintf(args, sizeof args, "bench --sweep '%s' --out '%s/x'", bad, dir);
    assert_int_equal(run(args, out, sizeof out), 2);
}

static bool
exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* A sweep whose last setting or last scene is bad exits 2 before it renders anything (no
 * reference, no setting) and before it makes the output or cache directory: every setting is
 * compiled on every scene first. The output names what it would have rendered first. */
static void
one_bad_setting_renders_and_writes_nothing(void **state)
{
    (void)state;
    static char out[1 << 16];
    char args[16384], out_dir[4200], cache_dir[4200];
    const char *dir = cg_test_tmpdir();
    snprintf(out_dir, sizeof out_dir, "%s/first/out", dir);
    snprintf(cache_dir, sizeof cache_dir, "%s/first/cache", dir);
    const char *cases[] = {
        /* A value the parameter table takes but the pass refuses when it declares (compile). */
        "--scene builtin:cornell --graph direct.json --graph vct.json --vary gather.cones=6,7",
        /* An unknown parameter in the last of several settings. */
        "--scene builtin:cornell --graph direct.json --graph vct.json --set gather.nosuchparam=1",
        /* A bad second scene. */
        "--scene builtin:cornell --scene builtin:nosuchscene --graph direct.json",
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(args, sizeof args, "bench %s --out '%s' --cache '%s'", cases[i], out_dir, cache_dir);
        int code = run(args, out, sizeof out);
        if (code != 2)
            fail_msg("'%s' exited with %d, expected 2:\n%s", cases[i], code, out);
        assert_null(strstr(out, "rendering the reference"));
        assert_null(strstr(out, "path_trace"));
        assert_false(exists(out_dir));
        assert_false(exists(cache_dir));
    }
}

/* The fields of one CSV line (quoted fields unquoted, "" inside them as "); returns the count. */
static int
csv_fields(const char *line, char fields[][512], int max)
{
    int n = 0;
    const char *p = line;
    while (n < max) {
        size_t len = 0;
        if (*p == '"') {
            for (p++; *p && !(*p == '"' && p[1] != '"'); p++) {
                if (*p == '"')
                    p++;
                if (len + 1 < 512)
                    fields[n][len++] = *p;
            }
            if (*p == '"')
                p++;
        } else {
            for (; *p && *p != ',' && *p != '\n'; p++)
                if (len + 1 < 512)
                    fields[n][len++] = *p;
        }
        fields[n++][len] = '\0';
        if (*p != ',')
            break;
        p++;
    }
    return n;
}

/* A sweep run as two shards and merged gives the table of one unsharded run: the same rows in
 * the same order with the same images' figures (times differ from run to run and are left out:
 * ms, pass_ms, the speed-up and the Pareto flags). Merging refuses a missing shard and shards
 * of another sweep. */
static void
shards_merge_into_the_unsharded_table(void **state)
{
    (void)state;
    static char out[1 << 16];
    char args[16384], path[4200];
    const char *dir = cg_test_tmpdir();
    const char *sweep = "--scene builtin:cornell --scene builtin:furnace --graph direct.json "
                        "--vary shadow.resolution=256,512 --size 24x16 --ref-spp 2 --pt-spp 1,2 --frames 1 --warmup 0";
    snprintf(args, sizeof args, "bench %s --out '%s/whole' --cache '%s/shared-cache'", sweep, dir, dir);
    int code = run(args, out, sizeof out);
    if (code != 0)
        fail_msg("bench exited with %d:\n%s", code, out);
    for (int k = 1; k <= 2; k++) {
        snprintf(args, sizeof args, "bench %s --shard %d/2 --out '%s/shard%d' --cache '%s/shared-cache'", sweep, k,
                 dir, k, dir);
        code = run(args, out, sizeof out);
        if (code != 0)
            fail_msg("shard %d exited with %d:\n%s", k, code, out);
        snprintf(path, sizeof path, "%s/shard%d/bench.csv", dir, k);
        assert_false(exists(path));     /* a shard's table waits for the merge */
    }
    snprintf(args, sizeof args, "bench %s --merge '%s/shard2' '%s/shard1' --out '%s/merged'", sweep, dir, dir, dir);
    code = run(args, out, sizeof out);
    if (code != 0)
        fail_msg("merge exited with %d:\n%s", code, out);

    static char whole[1 << 14], merged[1 << 14];
    snprintf(path, sizeof path, "%s/whole/bench.csv", dir);
    FILE *a = fopen(path, "r");
    snprintf(path, sizeof path, "%s/merged/bench.csv", dir);
    FILE *b = fopen(path, "r");
    assert_non_null(a);
    assert_non_null(b);
    int lines = 0;
    static char fa[32][512], fb[32][512];
    while (fgets(whole, sizeof whole, a)) {
        assert_non_null(fgets(merged, sizeof merged, b));
        int na = csv_fields(whole, fa, 32), nb = csv_fields(merged, fb, 32);
        assert_int_equal(na, 29);
        assert_int_equal(nb, 29);
        /* scene .. params, gi_bytes .. indirect_lum_ratio, gi_energy .. pass_reads: the texture
         * reads are counts, the same in a shard as in the whole run, whatever the machine's load */
        for (int f = 0; f < 29; f++)
            if (f != 5 && f != 6 && (f < 19 || f > 22))
                assert_string_equal(fa[f], fb[f]);
        lines++;
    }
    assert_null(fgets(merged, sizeof merged, b));
    fclose(a);
    fclose(b);
    assert_int_equal(lines, 1 + 2 * (2 + 2));    /* header; per scene 2 path tracer rows, 2 settings */
    snprintf(path, sizeof path, "%s/merged/builtin-furnace-time.png", dir);
    assert_true(exists(path));

    snprintf(args, sizeof args, "bench %s --merge '%s/shard1' --out '%s/half'", sweep, dir, dir);
    assert_int_equal(run(args, out, sizeof out), 2);
    assert_non_null(strstr(out, "shard 2/2 is missing"));
    snprintf(args, sizeof args, "bench %s --frames 2 --merge '%s/shard1' '%s/shard2' --out '%s/other'", sweep, dir,
             dir, dir);
    assert_int_equal(run(args, out, sizeof out), 2);
    assert_non_null(strstr(out, "of another sweep"));
    snprintf(path, sizeof path, "%s/other", dir);
    assert_false(exists(path));
    assert_int_equal(run("bench --shard 3/2", out, sizeof out), 2);
    assert_int_equal(run("bench --shard 1/2 --merge x", out, sizeof out), 2);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(sweep_runs_and_caches_the_reference),
             cmocka_unit_test(sweep_file),
             cmocka_unit_test(sweep_lights_each_scene_once),
             cmocka_unit_test(bad_input_exits_with_2),
             cmocka_unit_test(output_dirs_refused_before_work),
             cmocka_unit_test(one_bad_setting_renders_and_writes_nothing),
             cmocka_unit_test(shards_merge_into_the_unsharded_table),
             cmocka_unit_test(gi_and_direct_columns))
