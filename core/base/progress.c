/* core/base/progress.c: progress lines with the time left (cg/progress.h says what they look
 * like and when they appear). */
#include "cg/progress.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cg/log.h"

/* A terminal line is redrawn at most this often: more is flicker, and costs the work time. */
#define TERMINAL_INTERVAL_S 0.1

static double
monotonic_seconds(void *user)
{
    (void)user;
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double
cg_progress_delay(void)
{
    const char *v = getenv("CONEGRAPH_PROGRESS_DELAY");
    if (v && *v) {
        char *end;
        double d = strtod(v, &end);
        if (*end == '\0' && isfinite(d) && d >= 0)
            return d;
    }
    return CG_PROGRESS_DELAY_S;
}

void
cg_progress_begin(cg_progress *p, const cg_progress_desc *desc)
{
    memset(p, 0, sizeof *p);
    snprintf(p->what, sizeof p->what, "%s", desc->what ? desc->what : "working");
    snprintf(p->unit, sizeof p->unit, "%s", desc->unit ? desc->unit : "");
    p->total = desc->total > 0 ? desc->total : 1;
    p->out = desc->out ? desc->out : stderr;
    p->terminal = desc->terminal > 0 || (desc->terminal == 0 && isatty(fileno(p->out)));
    p->delay_s = desc->delay_s > 0 ? desc->delay_s : desc->delay_s < 0 ? 0 : cg_progress_delay();
    p->clock = desc->clock ? desc->clock : monotonic_seconds;
    p->clock_user = desc->clock_user;
    p->enabled = cg_log_get_level() <= CG_LOG_INFO;
    p->start = p->last_print = p->clock(p->clock_user);
}

static void
format_seconds(double s, char *out, size_t size)
{
    if (s < 100)
        snprintf(out, size, "%.1f s", s);
    else if (s < 3600)
        snprintf(out, size, "%d min %02d s", (int)(s / 60), (int)fmod(s, 60));
    else
        snprintf(out, size, "%d h %02d min", (int)(s / 3600), (int)fmod(s / 60, 60));
}

/* "WHAT: 40% (3/8 frames), 2.6 s, about 3.9 s left", or the total time when over. */
static void
format_line(const cg_progress *p, double elapsed, char *out, size_t size)
{
    double share = p->done / p->total;
    int n = snprintf(out, size, "conegraph: %s: %d%%", p->what, (int)floor(100 * share + 1e-9));
    if (p->unit[0] && n >= 0 && (size_t)n < size)
        n += snprintf(out + n, size - (size_t)n, " (%.0f/%.0f %s)", floor(p->done), p->total, p->unit);
    char spent[32], left[32];
    format_seconds(elapsed, spent, sizeof spent);
    if (n >= 0 && (size_t)n < size) {
        if (p->done > 0 && p->done < p->total) {
            format_seconds(elapsed * (p->total - p->done) / p->done, left, sizeof left);
            snprintf(out + n, size - (size_t)n, ", %s, about %s left", spent, left);
        } else {
            snprintf(out + n, size - (size_t)n, ", %s", spent);
        }
    }
}

/* The step of a line into a file: tenths of the work, or units when there are fewer than 10. */
static int
file_step(const cg_progress *p)
{
    if (p->unit[0] && p->total < 10)
        return (int)floor(p->done + 1e-9);
    return (int)floor(10 * p->done / p->total + 1e-9);
}

static int
last_file_step(const cg_progress *p)
{
    return p->unit[0] && p->total < 10 ? (int)floor(p->total + 1e-9) : 10;
}

static void
write_line(cg_progress *p, double now)
{
    char line[320];
    format_line(p, now - p->start, line, sizeof line);
    if (p->terminal)
        fprintf(p->out, "\r%s\033[K", line);
    else
        fprintf(p->out, "%s\n", line);
    fflush(p->out);
    p->shown = true;
    p->last_print = now;
}

void
cg_progress_update(cg_progress *p, double done)
{
    if (!p->enabled)
        return;
    p->done = done < 0 ? 0 : done > p->total ? p->total : done;
    double now = p->clock(p->clock_user);
    if (now - p->start < p->delay_s)
        return;
    if (p->terminal) {
        if (p->shown && now - p->last_print < TERMINAL_INTERVAL_S)
            return;
        write_line(p, now);
        return;
    }
    int step = file_step(p);
    if (step <= p->last_step)
        return;
    p->last_step = step;
    write_line(p, now);
}

void
cg_progress_end(cg_progress *p)
{
    if (!p->enabled || !p->shown)
        return;
    p->done = p->total;
    double now = p->clock(p->clock_user);
    if (p->terminal) {
        write_line(p, now);
        fputc('\n', p->out);
        fflush(p->out);
    } else if (p->last_step < last_file_step(p)) {
        p->last_step = last_file_step(p);
        write_line(p, now);
    }
}
