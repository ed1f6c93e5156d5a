/* cg/fs.h: file helpers: whole-file reads and atomic writes.
 *
 * Declares: cg_read_file, cg_atomic_file, cg_atomic_open, cg_atomic_commit, cg_atomic_abort,
 *           cg_temp_path_for, cg_output_path_check.
 *
 * Outputs are written to a temporary file beside the target and renamed into place,
 * so that a failure never leaves a partial or clobbered file; the next write of the same
 * target removes temporaries a killed run left.
 */
#ifndef CG_FS_H
#define CG_FS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "cg/error.h"

/* Reads a whole file, NUL-terminated; the caller frees *data. */
bool cg_read_file(const char *path, char **data, size_t *size, cg_error *err);

/* "DIR/.NAME.tmp-PID-N.EXT" beside `path`, for libraries that write by path (OIIO). It also
 * removes the temporaries of `path` that a killed run left behind (their PID no longer runs),
 * so that a `kill -9` during a write leaves litter only until the next write of that output. */
bool cg_temp_path_for(const char *path, char *out, size_t out_size);

/* Whether `path` can be written, checked before any work so that a run that would end unable to
 * write its result refuses at once: its directory exists, is a directory and can take new files
 * (the atomic write creates a temporary beside the target), the path itself is not a directory
 * and, where `extensions` is not NULL, ends with one of them (a '|'-separated list such as
 * ".exr|.png", compared without case). Fails with CG_ERR_OUTPUT_PATH naming the path as written
 * and why; writes nothing. */
bool cg_output_path_check(const char *path, const char *extensions, cg_error *err);

typedef struct cg_atomic_file {
    FILE *fp;
    char path[4096];
    char temp_path[4096];
} cg_atomic_file;

bool cg_atomic_open(cg_atomic_file *f, const char *path, cg_error *err);
/* Flushes, closes and renames into place. */
bool cg_atomic_commit(cg_atomic_file *f, cg_error *err);
/* Closes and removes the temporary file. */
void cg_atomic_abort(cg_atomic_file *f);

#endif
