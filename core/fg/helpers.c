/* Small helpers of the frame graph's files (fg_internal.h, "helpers"): strings, growing arrays,
 * source locations, byte counts, "pass.output" references. They lean on no other fg file, so
 * that registry, graph, compile, execute and report can each use them without using each other. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fg_internal.h"

const char *
fg_loc_prefix(const fg_source_loc *loc, char *buf, size_t size)
{
    if (!loc || !loc->file) {
        buf[0] = '\0';
        return buf;
    }
    if (loc->line <= 0)
        snprintf(buf, size, "%s: ", loc->file);
    else
        snprintf(buf, size, "%s:%d:%d: ", loc->file, loc->line, loc->column);
    return buf;
}

char *
fg_strdup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *copy = malloc(n);
    if (copy)
        memcpy(copy, s, n);
    return copy;
}

bool
fg_grow(void **items, int *cap, int need, size_t size)
{
    if (need <= *cap)
        return true;
    int new_cap = *cap ? *cap * 2 : 8;
    while (new_cap < need)
        new_cap *= 2;
    void *bigger = realloc(*items, (size_t)new_cap * size);
    if (!bigger)
        return false;
    memset((char *)bigger + (size_t)*cap * size, 0, (size_t)(new_cap - *cap) * size);
    *items = bigger;
    *cap = new_cap;
    return true;
}

const char *
fg_bytes_text(size_t bytes, char *buf, size_t size)
{
    if (bytes >= 1024 * 1024)
        snprintf(buf, size, "%.2f MiB", bytes / 1048576.0);
    else if (bytes >= 1024)
        snprintf(buf, size, "%.1f KiB", bytes / 1024.0);
    else
        snprintf(buf, size, "%zu B", bytes);
    return buf;
}

const char *
fg_split_source(const char *source, char *pass, size_t size)
{
    const char *dot = strchr(source, '.');
    size_t length = dot ? (size_t)(dot - source) : strlen(source);
    snprintf(pass, size, "%.*s", (int)length, source);
    return dot ? dot + 1 : NULL;
}
