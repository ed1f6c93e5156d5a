#include "cg/log.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Process-wide configuration, set once by the app; -1 = not yet read from the environment. */
static int log_level = -1;

static cg_log_level
level_from_env(void)
{
    const char *v = getenv("CONEGRAPH_LOG");
    if (!v)
        return CG_LOG_INFO;
    if (!strcmp(v, "debug")) return CG_LOG_DEBUG;
    if (!strcmp(v, "warn")) return CG_LOG_WARN;
    if (!strcmp(v, "error")) return CG_LOG_ERROR;
    if (!strcmp(v, "silent")) return CG_LOG_SILENT;
    return CG_LOG_INFO;
}

void
cg_log_set_level(cg_log_level level)
{
    log_level = (int)level;
}

cg_log_level
cg_log_get_level(void)
{
    if (log_level < 0)
        log_level = (int)level_from_env();
    return (cg_log_level)log_level;
}

void
cg_log(cg_log_level level, const char *fmt, ...)
{
    if (level < cg_log_get_level())
        return;
    static const char *const prefix[] = { "debug: ", "", "warning: ", "error: ", "" };
    char line[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    /* One fprintf per message so that lines from two threads do not interleave. */
    size_t n = strlen(line);
    fprintf(stderr, "conegraph: %s%s%s", prefix[level], line, (n && line[n - 1] == '\n') ? "" : "\n");
}
