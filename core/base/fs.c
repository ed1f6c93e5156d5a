#include "cg/fs.h"

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

bool
cg_read_file(const char *path, char **data, size_t *size, cg_error *err)
{
    *data = NULL;
    if (size)
        *size = 0;
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return cg_fail(err, CG_ERR_FILE_NOT_FOUND, "%s: cannot open: %s", path, strerror(errno));
    size_t cap = 1 << 16, len = 0;
    char *buf = malloc(cap + 1);
    while (buf) {
        size_t got = fread(buf + len, 1, cap - len, fp);
        len += got;
        if (len < cap)
            break;
        cap *= 2;
        char *bigger = realloc(buf, cap + 1);
        if (!bigger) {
            free(buf);
            buf = NULL;
        }
        buf = bigger;
    }
    bool read_error = ferror(fp);
    fclose(fp);
    if (!buf)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory reading the file", path);
    if (read_error) {
        free(buf);
        return cg_fail(err, CG_ERR_FILE_NOT_FOUND, "%s: read error", path);
    }
    buf[len] = '\0';
    *data = buf;
    if (size)
        *size = len;
    return true;
}

/* Removes the temporaries of `path` that a killed run left behind: ".NAME.tmp-PID-N.EXT"
 * beside it whose PID names no running process. A live process's temporary (a concurrent
 * run writing the same output) is left alone; a PID reused since by another process only
 * keeps a stale file until a later run. */
static void
remove_stale_temporaries(const char *path)
{
    const char *slash = strrchr(path, '/');
    char dir[4096];
    if (slash && snprintf(dir, sizeof dir, "%.*s", slash == path ? 1 : (int)(slash - path), path) >= (int)sizeof dir)
        return;
    if (!slash)
        strcpy(dir, ".");
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    const char *ext = dot ? dot : "";
    char prefix[1024];
    if (snprintf(prefix, sizeof prefix, ".%.*s.tmp-", dot ? (int)(dot - base) : (int)strlen(base), base) >=
        (int)sizeof prefix)
        return;
    DIR *d = opendir(dir);
    if (!d)
        return;
    size_t plen = strlen(prefix), elen = strlen(ext);
    struct dirent *e;
    while ((e = readdir(d))) {
        const char *name = e->d_name;
        size_t len = strlen(name);
        if (len <= plen + elen || strncmp(name, prefix, plen) || strcmp(name + len - elen, ext))
            continue;
        char *end;
        long pid = strtol(name + plen, &end, 10);
        if (end == name + plen || *end != '-' || pid <= 0 || pid == (long)getpid())
            continue;
        char *end2;
        strtoul(end + 1, &end2, 10);
        if (end2 == end + 1 || end2 != name + len - elen)
            continue;
        if (kill((pid_t)pid, 0) == 0 || errno != ESRCH)
            continue; /* running (or not ours to signal): maybe still writing */
        char stale[4096 + 256];
        snprintf(stale, sizeof stale, "%s/%s", dir, name);
        unlink(stale);
    }
    closedir(d);
}

bool
cg_temp_path_for(const char *path, char *out, size_t out_size)
{
    static atomic_uint counter;
    const char *slash = strrchr(path, '/');
    int dir_len = slash ? (int)(slash - path + 1) : 0;
    const char *base = slash ? slash + 1 : path;
    /* Keep the extension last: OIIO and tinygltf choose the format from it. */
    const char *dot = strrchr(base, '.');
    int n = snprintf(out, out_size, "%.*s.%.*s.tmp-%ld-%u%s", dir_len, path,
                     dot ? (int)(dot - base) : (int)strlen(base), base,
                     (long)getpid(), atomic_fetch_add(&counter, 1u), dot ? dot : "");
    if (n <= 0 || (size_t)n >= out_size)
        return false;
    remove_stale_temporaries(path);
    return true;
}

/* Whether `path` ends with one of the '|'-separated extensions (no case). */
static bool
has_one_of(const char *path, const char *extensions)
{
    size_t len = strlen(path);
    for (const char *e = extensions; *e;) {
        const char *bar = strchr(e, '|');
        size_t n = bar ? (size_t)(bar - e) : strlen(e);
        if (n > 0 && n <= len && !strncasecmp(path + len - n, e, n))
            return true;
        e += bar ? n + 1 : n;
    }
    return false;
}

bool
cg_output_path_check(const char *path, const char *extensions, cg_error *err)
{
    if (!path[0])
        return cg_fail(err, CG_ERR_OUTPUT_PATH, "an empty output path");
    if (extensions && !has_one_of(path, extensions))
        return cg_fail(err, CG_ERR_OUTPUT_PATH, "%s: expected a file name ending in %s", path, extensions);
    const char *slash = strrchr(path, '/');
    char dir[4096];
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else if (slash == path)
        snprintf(dir, sizeof dir, "/");
    else if ((size_t)(slash - path) < sizeof dir)
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
    else
        return cg_fail(err, CG_ERR_OUTPUT_PATH, "%s: path too long", path);
    if (slash && !slash[1])
        return cg_fail(err, CG_ERR_OUTPUT_PATH, "%s: names a directory, expected a file", path);
    struct stat st;
    if (stat(dir, &st) != 0)
        return cg_fail(err, CG_ERR_OUTPUT_PATH, "%s: directory '%s' %s", path, dir,
                       errno == ENOENT ? "does not exist" : strerror(errno));
    if (!S_ISDIR(st.st_mode))
        return cg_fail(err, CG_ERR_OUTPUT_PATH, "%s: '%s' is not a directory", path, dir);
    if (access(dir, W_OK | X_OK) != 0)
        return cg_fail(err, CG_ERR_OUTPUT_PATH, "%s: directory '%s' is not writable (%s)", path, dir,
                       strerror(errno));
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        return cg_fail(err, CG_ERR_OUTPUT_PATH, "%s: is a directory, expected a file", path);
    return true;
}

bool
cg_atomic_open(cg_atomic_file *f, const char *path, cg_error *err)
{
    memset(f, 0, sizeof *f);
    if (strlen(path) >= sizeof f->path || !cg_temp_path_for(path, f->temp_path, sizeof f->temp_path))
        return cg_fail(err, CG_ERR_IO, "%s: path too long", path);
    strcpy(f->path, path);
    f->fp = fopen(f->temp_path, "wb");
    if (!f->fp)
        return cg_fail(err, CG_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
    return true;
}

bool
cg_atomic_commit(cg_atomic_file *f, cg_error *err)
{
    bool ok = f->fp && fflush(f->fp) == 0 && !ferror(f->fp);
    if (f->fp && fclose(f->fp) != 0)
        ok = false;
    f->fp = NULL;
    if (!ok) {
        unlink(f->temp_path);
        return cg_fail(err, CG_ERR_IO, "%s: write failed: %s", f->path, strerror(errno));
    }
    if (rename(f->temp_path, f->path) != 0) {
        int e = errno;
        unlink(f->temp_path);
        return cg_fail(err, CG_ERR_IO, "%s: cannot rename into place: %s", f->path, strerror(e));
    }
    return true;
}

void
cg_atomic_abort(cg_atomic_file *f)
{
    if (f->fp)
        fclose(f->fp);
    f->fp = NULL;
    if (f->temp_path[0])
        unlink(f->temp_path);
}
