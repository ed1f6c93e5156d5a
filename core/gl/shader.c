/* GLSL programs from shaders/ with #include.
 *
 * Include semantics (chosen so that shaders/common/ files need no guards of their own):
 * - `#include "path"` is resolved against cg_shader_dir() (or taken as is when absolute),
 *   never against the including file, so a path reads the same in every file.
 * - Every file is included at most once per program: a second #include of a file that
 *   is already in (same realpath) expands to nothing, as if each file began with
 *   `#pragma once`; a literal `#pragma once` line is accepted and dropped.
 * - A file that includes itself through a chain (a file still being expanded) is an error
 *   naming the chain, rather than silently skipped as a repeat.
 * - Includes are expanded before the GLSL preprocessor runs, so an #include inside
 *   #if 0 is still expanded; inside a comment it is left alone.
 * - Every file gets a GLSL source-string number (the top file 0, then in order of first
 *   inclusion) and `#line N FILE` directives keep the driver's line numbers true; logs
 *   are rewritten from "FILE:LINE(COL)" to "path:LINE(COL)".
 * - Mesa 22.3 does not carry the source-string number into every message: semantic
 *   errors (an undeclared identifier, say) in an included file come out as "0:LINE".
 *   So the line numbers carry the file as well: file i > 0 counts its lines from
 *   i * CG_SHADER_LINE_BASE (`#line 200004 2` is line 4 of file 2), and the log
 *   rewriter takes the file from the line number, whatever source number the driver
 *   printed. Files longer than CG_SHADER_LINE_BASE lines are refused.
 */
#include "cg/shader.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cg/fs.h"
#include "cg/log.h"

#define MAX_INCLUDE_DEPTH 32
#define CG_SHADER_LINE_BASE 100000

static bool
is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

const char *
cg_shader_dir(void)
{
    const char *env = getenv("CONEGRAPH_SHADER_DIR");
    if (env && *env)
        return env;
    if (is_dir(CG_SHADER_SOURCE_DIR))
        return CG_SHADER_SOURCE_DIR;
    return CG_SHADER_INSTALL_DIR;
}

/* ---- growable string ---------------------------------------------------------------- */

typedef struct strbuf {
    char *data;
    size_t len, cap;
    bool oom;
} strbuf;

static void
sb_append(strbuf *sb, const char *s, size_t n)
{
    if (sb->oom)
        return;
    if (sb->len + n + 1 > sb->cap) {
        size_t cap = sb->cap ? sb->cap : 4096;
        while (sb->len + n + 1 > cap)
            cap *= 2;
        char *bigger = realloc(sb->data, cap);
        if (!bigger) {
            sb->oom = true;
            return;
        }
        sb->data = bigger;
        sb->cap = cap;
    }
    memcpy(sb->data + sb->len, s, n);
    sb->len += n;
    sb->data[sb->len] = '\0';
}

static void
sb_printf(strbuf *sb, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static void
sb_printf(strbuf *sb, const char *fmt, ...)
{
    char tmp[1024];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n > 0)
        sb_append(sb, tmp, (size_t)n < sizeof tmp ? (size_t)n : sizeof tmp - 1);
}

/* ---- include expansion --------------------------------------------------------------- */

typedef struct shader_file {
    char *name;     /* as the user wrote it: relative to the shader dir, or absolute */
    char *realpath; /* identity for once-only inclusion and cycle detection */
} shader_file;

typedef struct expansion {
    const char *dir;
    shader_file *files; /* index = GLSL source-string number */
    int file_count, file_cap;
    int stack[MAX_INCLUDE_DEPTH]; /* indices of files being expanded, outermost first */
    int stack_line[MAX_INCLUDE_DEPTH]; /* line of each one's #include being expanded now */
    int depth;
    strbuf out;
} expansion;

static void
expansion_free(expansion *ex)
{
    for (int i = 0; i < ex->file_count; i++) {
        free(ex->files[i].name);
        free(ex->files[i].realpath);
    }
    free(ex->files);
    free(ex->out.data);
    memset(ex, 0, sizeof *ex);
}

static bool
resolve(const expansion *ex, const char *name, char *path, size_t size)
{
    int n = name[0] == '/' ? snprintf(path, size, "%s", name)
                           : snprintf(path, size, "%s/%s", ex->dir, name);
    return n > 0 && (size_t)n < size;
}

/* Finds a file in the table or adds it (*added tells which); -1 with *err filled on failure. */
static int
file_index(expansion *ex, const char *name, const char *real, bool *added, cg_error *err)
{
    *added = false;
    for (int i = 0; i < ex->file_count; i++)
        if (!strcmp(ex->files[i].realpath, real))
            return i;
    if (ex->file_count == ex->file_cap) {
        int cap = ex->file_cap ? 2 * ex->file_cap : 8;
        shader_file *bigger = realloc(ex->files, (size_t)cap * sizeof *bigger);
        if (!bigger) {
            cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory expanding shader includes");
            return -1;
        }
        ex->files = bigger;
        ex->file_cap = cap;
    }
    shader_file *f = &ex->files[ex->file_count];
    f->name = strdup(name);
    f->realpath = strdup(real);
    if (!f->name || !f->realpath) {
        free(f->name);
        free(f->realpath);
        cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory expanding shader includes");
        return -1;
    }
    *added = true;
    return ex->file_count++;
}

/* The directive on a line, if the line is `# word rest`: returns a pointer past `word`. */
static const char *
directive(const char *line, const char *end, const char *word)
{
    const char *p = line;
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    if (p == end || *p != '#')
        return NULL;
    p++;
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    size_t n = strlen(word);
    if ((size_t)(end - p) < n || strncmp(p, word, n) != 0)
        return NULL;
    p += n;
    if (p < end && !(*p == ' ' || *p == '\t' || *p == '\r' || *p == '"' || *p == '<'))
        return NULL; /* #includes, #versionX, ... */
    return p;
}

static bool
only_space(const char *p, const char *end)
{
    for (; p < end; p++)
        if (!isspace((unsigned char)*p))
            return false;
    return true;
}

/* Tracks block comments so that directives inside them are left alone. Returns whether
 * the line *starts* inside a comment, and updates *in_comment for the next line. */
static bool
scan_comments(const char *line, const char *end, bool *in_comment)
{
    bool starts_inside = *in_comment;
    for (const char *p = line; p + 1 < end; p++) {
        if (*in_comment) {
            if (p[0] == '*' && p[1] == '/') {
                *in_comment = false;
                p++;
            }
        } else if (p[0] == '/' && p[1] == '/') {
            break;
        } else if (p[0] == '/' && p[1] == '*') {
            *in_comment = true;
            p++;
        }
    }
    return starts_inside;
}

/* "A -> B -> C": the files being expanded, outermost first. */
static void
describe_chain(const expansion *ex, char *out, size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    for (int i = 0; i < ex->depth && used < size; i++) {
        int n = snprintf(out + used, size - used, "%s%s", i ? " -> " : "", ex->files[ex->stack[i]].name);
        if (n < 0)
            break;
        used += (size_t)n;
    }
}

/* " (included from B:3, from A:2)" for the files below the innermost one; "" at the top. */
static void
describe_includers(const expansion *ex, char *out, size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    for (int i = ex->depth - 2; i >= 0 && used < size; i--) {
        int n = snprintf(out + used, size - used, "%s%s:%d%s", i == ex->depth - 2 ? " (included from " : ", from ",
                         ex->files[ex->stack[i]].name, ex->stack_line[i], i == 0 ? ")" : "");
        if (n < 0)
            break;
        used += (size_t)n;
    }
}

static bool expand_file(expansion *ex, int index, const char *defines, cg_error *err);

/* Handles `#include "name"` at `line_no` of file `from`. */
static bool
expand_include(expansion *ex, int from, int line_no, const char *args, const char *end, cg_error *err)
{
    const char *from_name = ex->files[from].name;
    char includers[1024];
    describe_includers(ex, includers, sizeof includers);
    const char *p = args;
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    const char *close = (p < end && *p == '"') ? memchr(p + 1, '"', (size_t)(end - p - 1)) : NULL;
    if (!close || close == p + 1 || !only_space(close + 1, end) || (size_t)(close - p - 1) >= PATH_MAX)
        return cg_fail(err, CG_ERR_SHADER_COMPILE, "%s:%d: expected #include \"path\"%s", from_name, line_no,
                       includers);
    char name[PATH_MAX];
    memcpy(name, p + 1, (size_t)(close - p - 1));
    name[close - p - 1] = '\0';

    char path[PATH_MAX], real[PATH_MAX];
    if (!resolve(ex, name, path, sizeof path))
        return cg_fail(err, CG_ERR_SHADER_NOT_FOUND, "%s:%d: #include \"%s\": path too long", from_name,
                       line_no, name);
    if (!realpath(path, real))
        return cg_fail(err, CG_ERR_SHADER_NOT_FOUND, "%s:%d: #include \"%s\": %s: %s%s", from_name, line_no,
                       name, path, strerror(errno), includers);
    bool added;
    int index = file_index(ex, name, real, &added, err);
    if (index < 0)
        return false;
    for (int i = 0; i < ex->depth; i++) {
        if (ex->stack[i] == index) {
            char chain[1024];
            describe_chain(ex, chain, sizeof chain);
            return cg_fail(err, CG_ERR_SHADER_COMPILE, "%s:%d: #include \"%s\" is a cycle: %s -> %s",
                           from_name, line_no, name, chain, name);
        }
    }
    if (!added) { /* included before and finished: every file is included once only */
        sb_append(&ex->out, "\n", 1); /* stands for the #include line: line numbers stay true */
        return true;
    }
    if (ex->depth == MAX_INCLUDE_DEPTH)
        return cg_fail(err, CG_ERR_SHADER_COMPILE, "%s:%d: #include \"%s\": includes nested deeper than %d%s",
                       from_name, line_no, name, MAX_INCLUDE_DEPTH, includers);
    ex->stack_line[ex->depth - 1] = line_no;
    sb_printf(&ex->out, "#line %d %d\n", index * CG_SHADER_LINE_BASE + 1, index);
    if (!expand_file(ex, index, NULL, err))
        return false;
    /* GLSL >= 3.30: the line after `#line N S` is line N of source string S. */
    sb_printf(&ex->out, "#line %d %d\n", from * CG_SHADER_LINE_BASE + line_no + 1, from);
    return true;
}

/* Appends file `index`, expanded. `defines` is non-NULL only for the top file. */
static bool
expand_file(expansion *ex, int index, const char *defines, cg_error *err)
{
    const shader_file *f = &ex->files[index];
    char path[PATH_MAX];
    char *text = NULL;
    if (!resolve(ex, f->name, path, sizeof path))
        return cg_fail(err, CG_ERR_SHADER_NOT_FOUND, "%s: path too long", f->name);
    cg_error read_err = { 0 };
    if (!cg_read_file(path, &text, NULL, &read_err))
        return cg_fail(err, read_err.status == CG_ERR_OUT_OF_MEMORY ? CG_ERR_OUT_OF_MEMORY
                                                                      : CG_ERR_SHADER_NOT_FOUND,
                       "%s", read_err.message);
    ex->stack[ex->depth++] = index;

    bool top = index == 0;
    bool saw_version = false;
    bool in_comment = false;
    bool ok = true;
    int line_no = 1;
    const char *defines_text = defines ? defines : "";
    size_t defines_len = strlen(defines_text);
    bool defines_need_newline = defines_len && defines_text[defines_len - 1] != '\n';

    /* The top file without its own #version gets one first (cg/shader.h). */
    bool has_version = false;
    if (top) {
        bool c = false;
        for (const char *l = text; *l;) {
            const char *e = strchr(l, '\n');
            if (!e)
                e = l + strlen(l);
            if (!scan_comments(l, e, &c) && directive(l, e, "version")) {
                has_version = true;
                break;
            }
            l = *e ? e + 1 : e;
        }
        if (!has_version) {
            sb_printf(&ex->out, "#version 450 core\n");
            sb_append(&ex->out, defines_text, defines_len);
            if (defines_need_newline)
                sb_append(&ex->out, "\n", 1);
            sb_printf(&ex->out, "#line 1 0\n");
        }
    }

    for (const char *line = text; ok && *line; line_no++) {
        if (line_no >= CG_SHADER_LINE_BASE) {
            ok = cg_fail(err, CG_ERR_SHADER_COMPILE, "%s: longer than %d lines", f->name, CG_SHADER_LINE_BASE - 1);
            break;
        }
        const char *end = strchr(line, '\n');
        const char *next = end ? end + 1 : line + strlen(line);
        if (!end)
            end = next;
        bool commented = scan_comments(line, end, &in_comment);
        const char *args = NULL;
        if (!commented && (args = directive(line, end, "include"))) {
            ok = expand_include(ex, index, line_no, args, end, err);
        } else if (!commented && (args = directive(line, end, "pragma")) && !strncmp(args, " once", 5) &&
                   only_space(args + 5, end)) {
            sb_append(&ex->out, "\n", 1); /* every file is once-only already; keep line numbers */
        } else if (!commented && directive(line, end, "version")) {
            if (!top || saw_version) {
                ok = cg_fail(err, CG_ERR_SHADER_COMPILE,
                             "%s:%d: #version belongs in the top file only, once", f->name, line_no);
            } else {
                saw_version = true;
                sb_append(&ex->out, line, (size_t)(end - line));
                sb_append(&ex->out, "\n", 1);
                if (defines_len) {
                    sb_append(&ex->out, defines_text, defines_len);
                    if (defines_need_newline)
                        sb_append(&ex->out, "\n", 1);
                    sb_printf(&ex->out, "#line %d 0\n", line_no + 1);
                }
            }
        } else {
            sb_append(&ex->out, line, (size_t)(next - line));
            if (next == end) /* last line without newline */
                sb_append(&ex->out, "\n", 1);
        }
        line = next;
    }
    free(text);
    ex->depth--;
    if (ok && ex->out.oom)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory expanding %s", f->name);
    return ok;
}

/* Expands `path` (and its includes) into ex->out; ex->files names each source string. */
static bool
expand(expansion *ex, const char *path, const char *defines, cg_error *err)
{
    memset(ex, 0, sizeof *ex);
    ex->dir = cg_shader_dir();
    char full[PATH_MAX], real[PATH_MAX];
    if (!resolve(ex, path, full, sizeof full))
        return cg_fail(err, CG_ERR_SHADER_NOT_FOUND, "%s: path too long", path);
    if (!realpath(full, real))
        return cg_fail(err, CG_ERR_SHADER_NOT_FOUND, "%s: %s (shader directory %s)", path, strerror(errno),
                       ex->dir);
    bool added;
    if (file_index(ex, path, real, &added, err) != 0)
        return false;
    return expand_file(ex, 0, defines, err);
}

bool
cg_shader_source_load(const char *path, const char *defines, char **out, cg_error *err)
{
    *out = NULL;
    expansion ex;
    if (!expand(&ex, path, defines, err)) {
        expansion_free(&ex);
        return false;
    }
    *out = ex.out.data;
    ex.out.data = NULL;
    expansion_free(&ex);
    return true;
}

/* ---- compile and link --------------------------------------------------------------- */

/* Rewrites Mesa's "S:L(C)" (and the "S(L)" form other drivers use) at the start of each
 * log line into "file:line(C)". The file comes from L, not S (see the top of this file). */
static void
rewrite_log(const char *log, const expansion *ex, strbuf *out)
{
    for (const char *line = log; *line;) {
        const char *end = strchr(line, '\n');
        const char *next = end ? end + 1 : line + strlen(line);
        const char *p = line;
        while (*p == ' ')
            p++;
        char *after = NULL, *after_line = NULL;
        long s = isdigit((unsigned char)*p) ? strtol(p, &after, 10) : -1;
        long l = -1;
        if (s >= 0 && after && (*after == ':' || *after == '(') && isdigit((unsigned char)after[1]))
            l = strtol(after + 1, &after_line, 10);
        long file = l >= 0 ? l / CG_SHADER_LINE_BASE : -1;
        bool paren = after && *after == '(';
        if (file >= 0 && file < ex->file_count && (!paren || *after_line == ')')) {
            sb_append(out, line, (size_t)(p - line));
            sb_printf(out, "%s:%ld", ex->files[file].name, l % CG_SHADER_LINE_BASE);
            p = paren ? after_line + 1 : after_line; /* "S(L) : msg" -> "file:L : msg" */
        }
        sb_append(out, p, (size_t)(next - p));
        line = next;
    }
}

static const char *
stage_name(GLenum stage)
{
    switch (stage) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_GEOMETRY_SHADER: return "geometry";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_COMPUTE_SHADER: return "compute";
    default: return "unknown";
    }
}

/* Fetches an info log into a malloc'd string (NULL when empty). */
static char *
info_log(GLuint object, bool program)
{
    GLint len = 0;
    if (program)
        glGetProgramiv(object, GL_INFO_LOG_LENGTH, &len);
    else
        glGetShaderiv(object, GL_INFO_LOG_LENGTH, &len);
    if (len <= 1)
        return NULL;
    char *log = malloc((size_t)len);
    if (!log)
        return NULL;
    if (program)
        glGetProgramInfoLog(object, len, NULL, log);
    else
        glGetShaderInfoLog(object, len, NULL, log);
    return log;
}

static bool
compile_stage(GLenum stage, const char *path, const char *defines, GLuint *out, cg_error *err)
{
    *out = 0;
    expansion ex;
    if (!expand(&ex, path, defines, err)) {
        expansion_free(&ex);
        return false;
    }
    GLuint shader = glCreateShader(stage);
    const GLchar *src = ex.out.data;
    glShaderSource(shader, 1, &src, NULL);
    glCompileShader(shader);
    glObjectLabel(GL_SHADER, shader, -1, path);
    GLint status = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &status);
    char *log = info_log(shader, false);
    strbuf rewritten = { 0 };
    if (log)
        rewrite_log(log, &ex, &rewritten);
    bool ok = status == GL_TRUE;
    if (!ok) {
        cg_fail(err, CG_ERR_SHADER_COMPILE, "%s shader %s failed to compile:\n%s", stage_name(stage), path,
                rewritten.data ? rewritten.data : "(the driver gave no log)");
        glDeleteShader(shader);
    } else {
        if (rewritten.data && !only_space(rewritten.data, rewritten.data + rewritten.len))
            cg_log_warn("%s shader %s:\n%s", stage_name(stage), path, rewritten.data);
        *out = shader;
    }
    free(log);
    free(rewritten.data);
    expansion_free(&ex);
    return ok;
}

/* Links the given shaders (0 entries skipped) and deletes them. `what` names the program. */
static bool
link_program(const GLuint *shaders, int count, const char *what, GLuint *out, cg_error *err)
{
    GLuint program = glCreateProgram();
    for (int i = 0; i < count; i++)
        if (shaders[i])
            glAttachShader(program, shaders[i]);
    glLinkProgram(program);
    for (int i = 0; i < count; i++) {
        if (shaders[i]) {
            glDetachShader(program, shaders[i]);
            glDeleteShader(shaders[i]);
        }
    }
    glObjectLabel(GL_PROGRAM, program, -1, what);
    GLint status = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &status);
    char *log = info_log(program, true);
    bool ok = status == GL_TRUE;
    if (!ok) {
        cg_fail(err, CG_ERR_SHADER_COMPILE, "program %s failed to link:\n%s", what,
                log ? log : "(the driver gave no log)");
        glDeleteProgram(program);
    } else {
        if (log && !only_space(log, log + strlen(log)))
            cg_log_warn("program %s:\n%s", what, log);
        *out = program;
    }
    free(log);
    return ok;
}

bool
cg_program_compute(const char *path, const char *defines, GLuint *out, cg_error *err)
{
    *out = 0;
    GLuint cs;
    if (!compile_stage(GL_COMPUTE_SHADER, path, defines, &cs, err))
        return false;
    return link_program(&cs, 1, path, out, err);
}

bool
cg_program_graphics(const char *vs, const char *gs, const char *fs, const char *defines, GLuint *out,
                    cg_error *err)
{
    *out = 0;
    GLuint shaders[3] = { 0, 0, 0 };
    const char *paths[3] = { vs, gs, fs };
    const GLenum stages[3] = { GL_VERTEX_SHADER, GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER };
    if (!vs)
        return cg_fail(err, CG_ERR_SHADER_NOT_FOUND, "a graphics program needs a vertex shader");
    for (int i = 0; i < 3; i++) {
        if (paths[i] && !compile_stage(stages[i], paths[i], defines, &shaders[i], err)) {
            for (int j = 0; j < i; j++)
                if (shaders[j])
                    glDeleteShader(shaders[j]);
            return false;
        }
    }
    char what[1024];
    snprintf(what, sizeof what, "%s%s%s%s%s", vs, gs ? " + " : "", gs ? gs : "", fs ? " + " : "",
             fs ? fs : "");
    return link_program(shaders, 3, what, out, err);
}
