/* libFuzzer target: the sweep reader of `conegraph bench` (apps/conegraph/bench/sweep.c):
 * bench_parse_args with --sweep FILE, then bench_expand_runs and bench_run_assignments over
 * every run, as cmd_bench.c calls them before it validates the graphs (which needs scenes and
 * is left out: the graph reader has its own target).
 *
 * Each input is written to a file and read from there, as a user's sweep file would be. Besides
 * crashes and sanitizer reports, an exit code other than 0, 1 and 2, or more runs than the
 * limit, aborts. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench.h"
#include "fuzz_input.h"

static bench_config *config; /* large (the settings' tables): allocated once */

int
LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    fuzz_input_open("sweep", "sweep.json", NULL);
    config = malloc(sizeof *config);
    if (!config)
        abort();
    return 0;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input_write(data, size);
    char *argv[] = { "bench", "--sweep", fuzz_input_path, NULL };
    int code = bench_parse_args(3, argv, config);
    if (code != 0 && code != 2) {
        fprintf(stderr, "fuzz_sweep: bench_parse_args returned %d\n", code);
        abort();
    }
    if (code != 0)
        return 0;
    bench_run *runs = NULL;
    int count = 0;
    code = bench_expand_runs(config, &runs, &count);
    if (code != 0 && code != 1 && code != 2) {
        fprintf(stderr, "fuzz_sweep: bench_expand_runs returned %d\n", code);
        abort();
    }
    if (code == 0) {
        if (count < 0 || count > BENCH_MAX_RUNS * BENCH_MAX_SETTINGS)
            abort();
        char buf[BENCH_MAX_VARY][2 * BENCH_TEXT];
        const char *sets[BENCH_MAX_SETS + BENCH_MAX_VARY];
        for (int i = 0; i < count; i++) {
            int n = bench_run_assignments(config, &runs[i], buf, sets);
            if (n < 0 || n > BENCH_MAX_SETS + BENCH_MAX_VARY)
                abort();
            for (int k = 0; k < n; k++)
                if (!strchr(sets[k], '='))
                    abort();
        }
    }
    free(runs);
    return 0;
}
