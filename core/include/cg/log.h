/* cg/log.h: leveled logging to stderr.
 *
 * Declares: cg_log_level, cg_log_set_level, cg_log_get_level, cg_log, cg_log_debug,
 *           cg_log_info, cg_log_warn, cg_log_error.
 *
 * The level is process-wide configuration set once by the app (or the
 * CONEGRAPH_LOG environment variable: debug, info, warn, error), not per-frame state.
 */
#ifndef CG_LOG_H
#define CG_LOG_H

typedef enum cg_log_level {
    CG_LOG_DEBUG,
    CG_LOG_INFO,
    CG_LOG_WARN,
    CG_LOG_ERROR,
    CG_LOG_SILENT
} cg_log_level;

void cg_log_set_level(cg_log_level level);
cg_log_level cg_log_get_level(void);

void cg_log(cg_log_level level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#define cg_log_debug(...) cg_log(CG_LOG_DEBUG, __VA_ARGS__)
#define cg_log_info(...)  cg_log(CG_LOG_INFO, __VA_ARGS__)
#define cg_log_warn(...)  cg_log(CG_LOG_WARN, __VA_ARGS__)
#define cg_log_error(...) cg_log(CG_LOG_ERROR, __VA_ARGS__)

#endif
