/* tests/fuzz/fuzz_input.h: the file a fuzz target writes each input to and reads it from, as
 * a user's file would be read: fuzz_input_path, in a private directory fuzz_input_dir under
 * $TMPDIR that is removed at exit. Header-only: each target is a single source file.
 *
 * Declares: fuzz_input_dir, fuzz_input_path, fuzz_input_open, fuzz_input_write.
 */
#ifndef CG_FUZZ_INPUT_H
#define CG_FUZZ_INPUT_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static char fuzz_input_dir[4096], fuzz_input_path[4200];
static void (*fuzz_input_remove_more)(void);

static void
fuzz_input_remove(void)
{
    if (fuzz_input_remove_more)
        fuzz_input_remove_more();
    unlink(fuzz_input_path);
    rmdir(fuzz_input_dir);
}

/* Makes the directory ($TMPDIR/conegraph-fuzz-TARGET-XXXXXX) and names the input file `file`
 * in it; aborts when it cannot. remove_more (may be NULL) removes, at exit, what else the
 * target put there. */
static void
fuzz_input_open(const char *target, const char *file, void (*remove_more)(void))
{
    const char *tmp = getenv("TMPDIR");
    snprintf(fuzz_input_dir, sizeof fuzz_input_dir, "%s/conegraph-fuzz-%s-XXXXXX", tmp && *tmp ? tmp : "/tmp",
             target);
    if (!mkdtemp(fuzz_input_dir)) {
        fprintf(stderr, "fuzz_%s: ", target);
        perror("mkdtemp");
        abort();
    }
    snprintf(fuzz_input_path, sizeof fuzz_input_path, "%s/%s", fuzz_input_dir, file);
    fuzz_input_remove_more = remove_more;
    atexit(fuzz_input_remove);
}

/* Writes an input to fuzz_input_path; aborts when it cannot. */
static void
fuzz_input_write(const uint8_t *data, size_t size)
{
    FILE *fp = fopen(fuzz_input_path, "wb");
    if (!fp)
        abort();
    if (size && fwrite(data, 1, size, fp) != size)
        abort();
    fclose(fp);
}

#endif
