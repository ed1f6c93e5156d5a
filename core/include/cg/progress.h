/* cg/progress.h: progress of long work on stderr, with the time left.
 *
 * Declares: cg_progress_desc, cg_progress, cg_progress_begin, cg_progress_update,
 *           cg_progress_end, cg_progress_delay, CG_PROGRESS_DELAY_S.
 *
 * The one progress reporter of the project (the scene loader, render's frames, the path
 * tracer, bench): work of `total` units is reported as it is done, with the time spent and
 * the time left (linear in the units done so far: elapsed x (total - done) / done).
 *  - On a terminal (isatty of the stream): one line updated in place with '\r', at most
 *    about 10 times a second, ended with a newline by cg_progress_end.
 *  - Anywhere else (a log file, a pipe): one line per 10% of the work, or per unit when there
 *    are fewer than 10, and never a '\r'.
 *  - Nothing before the work has taken the delay (CG_PROGRESS_DELAY_S, 2 s, unless
 *    $CONEGRAPH_PROGRESS_DELAY says other seconds, 0 for at once): short work stays silent.
 *  - Nothing at all when the log level (cg/log.h) is above info: --quiet.
 * Lines read "conegraph: WHAT: 40% (3/8 frames), 2.6 s, about 3.9 s left".
 * Not thread-safe: one thread updates a reporter (the path tracer's main thread does).
 *
 * Use:
 *     cg_progress p;
 *     cg_progress_begin(&p, &(cg_progress_desc){ .what = "rendering", .total = frames, .unit = "frames" });
 *     for (...) { ...; cg_progress_update(&p, k + 1); }
 *     cg_progress_end(&p);
 */
#ifndef CG_PROGRESS_H
#define CG_PROGRESS_H

#include <stdbool.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CG_PROGRESS_DELAY_S 2.0

/* Zero-initialised fields take the defaults. */
typedef struct cg_progress_desc {
    const char *what;       /* what is being done, e.g. "loading town.glb" (copied) */
    double total;           /* units of work, > 0 */
    const char *unit;       /* e.g. "frames": lines then say "3/8 frames"; NULL: percent only */
    FILE *out;              /* NULL: stderr */
    int terminal;           /* 0: isatty(out); 1: as on a terminal; -1: as into a file */
    double delay_s;         /* 0: cg_progress_delay(); < 0: report from the start */
    double (*clock)(void *user); /* seconds on a monotonic clock; NULL: CLOCK_MONOTONIC (tests
                                  * pass their own, so that no test depends on timing) */
    void *clock_user;
} cg_progress_desc;

typedef struct cg_progress {
    char what[160];
    char unit[32];
    double total, done;
    FILE *out;
    bool terminal, enabled, shown;
    double delay_s;
    double (*clock)(void *user);
    void *clock_user;
    double start, last_print;
    int last_step;          /* the last 10% step (or unit) written into a file */
} cg_progress;

/* The delay before the first line: $CONEGRAPH_PROGRESS_DELAY (seconds, >= 0) or CG_PROGRESS_DELAY_S. */
double cg_progress_delay(void);

void cg_progress_begin(cg_progress *p, const cg_progress_desc *desc);
/* `done` units of the total are done (absolute, not an increment; clamped to [0, total]). */
void cg_progress_update(cg_progress *p, double done);
/* The work is over: on a terminal the line is finished with its total time and a newline;
 * into a file, a last "100%" line when an earlier line was written. Silent when nothing was
 * shown. */
void cg_progress_end(cg_progress *p);

#ifdef __cplusplus
}
#endif

#endif
