/* What every app shares: see app_common.h. */
#include "app_common.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include <sys/types.h>
#include <time.h>

static bool
file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

const char *
app_graph_dir(void)
{
    const char *env = getenv("CONEGRAPH_GRAPH_DIR");
    if (env && *env)
        return env;
    struct stat st;
    if (stat(CONEGRAPH_GRAPH_SOURCE_DIR, &st) == 0 && S_ISDIR(st.st_mode))
        return CONEGRAPH_GRAPH_SOURCE_DIR;
    return CONEGRAPH_GRAPH_INSTALL_DIR;
}

bool
app_resolve_graph(const char *given, char *out, size_t size, cg_error *err)
{
    if (!given) {
        snprintf(out, size, "%s/vct.json", app_graph_dir());
        if (!file_exists(out))
            snprintf(out, size, "%s/direct.json", app_graph_dir());
        return true;
    }
    snprintf(out, size, "%s", given);
    if (file_exists(given) || given[0] == '/')
        return true;
    char in_dir[4096];
    snprintf(in_dir, sizeof in_dir, "%s/%s", app_graph_dir(), given);
    if (file_exists(in_dir)) {
        snprintf(out, size, "%s", in_dir);
        return true;
    }
    char cwd[4096];
    if (!getcwd(cwd, sizeof cwd))
        snprintf(cwd, sizeof cwd, ".");
    return cg_fail(err, CG_ERR_FILE_NOT_FOUND,
                   "graph file '%s' not found: neither in the working directory (%s/%s) nor in the graph "
                   "directory (%s)", given, cwd, given, in_dir);
}

bool
app_parse_int(const char *text, long min, long max, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (errno || end == text || *end || v < min || v > max)
        return false;
    *out = v;
    return true;
}

bool
app_parse_double(const char *text, double min, double max, bool open_min, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(text, &end);
    if (errno || end == text || *end || !isfinite(v) || v < min || v > max || (open_min && v <= min))
        return false;
    *out = v;
    return true;
}

bool
app_parse_size(const char *text, int *w, int *h)
{
    char buf[64];
    if (strlen(text) >= sizeof buf)
        return false;
    strcpy(buf, text);
    char *x = strchr(buf, 'x');
    if (!x)
        return false;
    *x = '\0';
    long lw, lh;
    if (!app_parse_int(buf, 1, 65536, &lw) || !app_parse_int(x + 1, 1, 65536, &lh))
        return false;
    *w = (int)lw;
    *h = (int)lh;
    return true;
}

bool
app_parse_timing(const char *text, fg_timing_mode *out)
{
    if (!strcmp(text, "sync"))
        *out = FG_TIMING_SYNC;
    else if (!strcmp(text, "queries"))
        *out = FG_TIMING_QUERIES;
    else if (!strcmp(text, "none"))
        *out = FG_TIMING_NONE;
    else
        return false;
    return true;
}

/* The units of memory sizes, powers of 1024. KB, MB and GB are not among them: some read
 * them as powers of 1000, so they are refused rather than guessed. */
static const struct {
    const char *name;
    unsigned long long scale;
} byte_units[] = {
    { "B", 1ull },        { "K", 1ull << 10 }, { "KiB", 1ull << 10 }, { "M", 1ull << 20 },
    { "MiB", 1ull << 20 }, { "G", 1ull << 30 }, { "GiB", 1ull << 30 }, { "T", 1ull << 40 },
    { "TiB", 1ull << 40 },
};

bool
app_parse_bytes(const char *text, size_t *out)
{
    /* Digits, at most one '.', then the unit: no sign, exponent, hex, inf or nan (which
     * strtod would take). */
    const char *p = text;
    size_t digits = 0;
    while (isdigit((unsigned char)*p))
        p++, digits++;
    if (*p == '.')
        for (p++; isdigit((unsigned char)*p); p++)
            digits++;
    if (digits == 0)
        return false;
    unsigned long long scale = 0;
    for (size_t i = 0; i < sizeof byte_units / sizeof byte_units[0]; i++)
        if (!strcasecmp(p, byte_units[i].name))
            scale = byte_units[i].scale;
    if (!scale)
        return false;
    char number[64];
    if ((size_t)(p - text) >= sizeof number)
        return false;
    memcpy(number, text, (size_t)(p - text));
    number[p - text] = '\0';
    errno = 0;
    double v = strtod(number, NULL) * (double)scale;
    /* Whole bytes, at least one, below SIZE_MAX ((double)SIZE_MAX rounds up to 2^64). */
    if (errno || !(v >= 1.0) || !(v < (double)SIZE_MAX))
        return false;
    *out = (size_t)v;
    return true;
}

bool
app_has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n > e && !strcasecmp(path + n - e, ext);
}

int
app_usage_error(const char *tool, const char *fmt, const char *arg)
{
    fprintf(stderr, "%s: ", tool);
    fprintf(stderr, fmt, arg);
    fprintf(stderr, " (see %s --help)\n", tool);
    return 2;
}

int
app_fail(const char *tool, const char *what, const cg_error *err)
{
    if (what)
        fprintf(stderr, "%s: %s: %s\n", tool, what, err->message);
    else
        fprintf(stderr, "%s: %s\n", tool, err->message);
    int code = cg_status_exit_code(err->status);
    return code ? code : 1;
}

void
app_error_prefix(cg_error *err, const char *what)
{
    /* Both halves cut to fit: the buffer holds 2047 characters and a message may fill it. */
    char message[sizeof err->message];
    memcpy(message, err->message, sizeof message);
    int n = snprintf(err->message, sizeof err->message, "%s: ", what);
    if (n >= 0 && (size_t)n < sizeof err->message)
        memcpy(err->message + n, message, sizeof err->message - (size_t)n - 1);
    err->message[sizeof err->message - 1] = '\0';
}

bool
app_make_dirs(const char *path, cg_error *err)
{
    char buf[4096];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf)
        return cg_fail(err, CG_ERR_USAGE, "%s: path too long", path);
    for (char *p = buf + 1;; p++) {
        if (*p == '/' || *p == '\0') {
            char saved = *p;
            *p = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return cg_fail(err, CG_ERR_IO, "%s: cannot create directory: %s", buf, strerror(errno));
            *p = saved;
            if (!saved)
                break;
        }
    }
    return true;
}


double
app_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

double
app_cpu_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

double
app_median(double *values, int count)
{
    if (count <= 0)
        return NAN;
    qsort(values, (size_t)count, sizeof *values, app_compare_double);
    return values[count / 2];
}

int
app_compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void
app_csv_field(FILE *fp, const char *text)
{
    fputc('"', fp);
    for (const char *s = text; *s; s++) {
        if (*s == '"')
            fputc('"', fp);
        fputc(*s, fp);
    }
    fputc('"', fp);
}
