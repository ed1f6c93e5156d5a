/* apps/common/app_common.h: the small things every app (`conegraph` and its commands,
 * conegraph-demo, vct-bench) shares: finding graph files, parsing command-line values,
 * reporting errors with the exit code they stand for, a clock and a median.
 *
 * Declares: app_graph_dir, app_resolve_graph, app_parse_int, app_parse_double, app_parse_size, app_parse_timing,
 *           app_parse_bytes, app_has_extension, app_usage_error, app_fail, app_error_prefix,
 *           app_make_dirs, app_now_ms, app_cpu_ms, app_median, app_compare_double, app_csv_field.
 *
 * Exit codes, as everywhere in conegraph: 0 done, 1 failed while running, 2 bad input or usage.
 */
#ifndef CONEGRAPH_APP_COMMON_H
#define CONEGRAPH_APP_COMMON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "cg/error.h"
#include "cg/fg.h"

/* $CONEGRAPH_GRAPH_DIR, else the source tree's graphs/ when it exists, else the installed one. */
const char *app_graph_dir(void);
/* The graph file to read: `given` relative to the working directory when it is there, else
 * relative to the graph directory (an absolute path only as it is); NULL = vct.json from the
 * graph directory if it exists, else direct.json. Fails with CG_ERR_FILE_NOT_FOUND naming both
 * places it looked. */
bool app_resolve_graph(const char *given, char *out, size_t size, cg_error *err);

/* Decimal integer in min..max, nothing after it. */
bool app_parse_int(const char *text, long min, long max, long *out);
/* A finite decimal number in [min, max] ((min, max] when open_min), nothing after it. */
bool app_parse_double(const char *text, double min, double max, bool open_min, double *out);
/* "WxH", each 1..65536. */
bool app_parse_size(const char *text, int *w, int *h);
/* "sync", "queries" or "none"; false for anything else. */
bool app_parse_timing(const char *text, fg_timing_mode *out);
/* A memory size, the one syntax of every memory option: a number (decimals allowed) and a
 * unit, B (bytes), K or KiB, M or MiB, G or GiB, T or TiB (powers of 1024, any case):
 * "512M", "1.5G", "4096B". Rounded down to whole bytes, at least 1. A number without a unit
 * is refused (older versions read it as MiB in one command and as bytes in another), and so
 * are KB, MB and GB (1000 or 1024?). */
bool app_parse_bytes(const char *text, size_t *out);
/* The syntax app_parse_bytes accepts, for usage errors. */
#define APP_BYTES_SYNTAX "a size with its unit, e.g. 512M, 1.5G or 4096B (B bytes; K, M, G, T: KiB, MiB, GiB, TiB)"
/* Whether `path` ends in `ext` (".png"), ignoring case, with something before it. */
bool app_has_extension(const char *path, const char *ext);

/* Prints "TOOL: <fmt with arg> (see TOOL --help)" to stderr; returns 2. */
int app_usage_error(const char *tool, const char *fmt, const char *arg);
/* Prints "TOOL: WHAT: message" (WHAT may be NULL) to stderr; returns the exit code of the
 * error's status, 1 for a failure without one. */
int app_fail(const char *tool, const char *what, const cg_error *err);
/* Puts "WHAT: " in front of err's message (where the session failed: "scene", "graph", ...). */
void app_error_prefix(cg_error *err, const char *what);

/* mkdir -p: creates `path` and the directories above it that do not exist yet. */
bool app_make_dirs(const char *path, cg_error *err);

/* Wall clock (monotonic) and the CPU time of the whole process (all threads), in ms. */
double app_now_ms(void);
double app_cpu_ms(void);
/* The median (the upper one of an even count) of values[0..count-1], which it sorts; NAN for none. */
double app_median(double *values, int count);
/* qsort comparator for doubles. */
int app_compare_double(const void *a, const void *b);

/* Writes `text` as one CSV field (RFC 4180): quoted, its quotes doubled. */
void app_csv_field(FILE *fp, const char *text);

#endif
