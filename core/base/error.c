#include "cg/error.h"

#include <stdarg.h>
#include <stdio.h>

static const struct {
    const char *name;
    int exit_code;
    const char *summary;
} status_table[] = {
#define CG_X_ROW(name, code, summary) { #name, code, summary },
    CG_STATUS_TABLE(CG_X_ROW)
#undef CG_X_ROW
};

bool
cg_fail(cg_error *err, cg_status status, const char *fmt, ...)
{
    /* The first failure is the cause; later ones are consequences and must not hide it. */
    if (!err || err->status != CG_OK)
        return false;
    err->status = status;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
    return false;
}

void
cg_error_clear(cg_error *err)
{
    if (!err)
        return;
    err->status = CG_OK;
    err->message[0] = '\0';
}

const char *
cg_status_name(cg_status status)
{
    return (unsigned)status < CG_STATUS_COUNT ? status_table[status].name : "CG_ERR_UNKNOWN";
}

const char *
cg_status_summary(cg_status status)
{
    return (unsigned)status < CG_STATUS_COUNT ? status_table[status].summary : "unknown error";
}

int
cg_status_exit_code(cg_status status)
{
    return (unsigned)status < CG_STATUS_COUNT ? status_table[status].exit_code : 1;
}
