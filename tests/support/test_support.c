#include "test_support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <sys/wait.h>
#include <unistd.h>

static char tmpdir[4096];

static void
remove_tmpdir(void)
{
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    if (system(cmd) != 0)
        fprintf(stderr, "warning: could not remove %s\n", tmpdir);
}

const char *
cg_test_tmpdir(void)
{
    if (!tmpdir[0]) {
        const char *base = getenv("TMPDIR");
        snprintf(tmpdir, sizeof tmpdir, "%s/conegraph-test-XXXXXX", base ? base : "/tmp");
        if (!mkdtemp(tmpdir)) {
            perror("mkdtemp");
            abort();
        }
        atexit(remove_tmpdir);
    }
    return tmpdir;
}

const char *
cg_test_write_file(const char *name, const void *data, size_t size)
{
    static char paths[8][4096];
    static int next;
    char *path = paths[next++ % 8];
    snprintf(path, 4096, "%s/%s", cg_test_tmpdir(), name);
    FILE *fp = fopen(path, "wb");
    if (!fp) {
        perror(path);
        abort();
    }
    if (size == 0)
        size = strlen(data);
    if (fwrite(data, 1, size, fp) != size) {
        perror(path);
        abort();
    }
    fclose(fp);
    return path;
}

int
cg_test_gl_setup(void **state)
{
    cg_context_desc desc = { .backend = CG_CONTEXT_EGL, .debug = true };
    const char *env = getenv("CONEGRAPH_CONTEXT");
    if (env && *env && !cg_context_backend_parse(env, &desc.backend)) {
        fprintf(stderr, "CONEGRAPH_CONTEXT=%s: expected egl, osmesa or glfw\n", env);
        return -1;
    }
    if (desc.backend == CG_CONTEXT_AUTO)
        desc.backend = CG_CONTEXT_EGL;
    cg_context *ctx = NULL;
    cg_error err = { 0 };
    if (!cg_context_create(&desc, &ctx, &err)) {
        fprintf(stderr, "cannot create a GL context for the tests: %s: %s\n",
                cg_status_name(err.status), err.message);
        return -1;
    }
    *state = ctx;
    return 0;
}

int
cg_test_gl_teardown(void **state)
{
    cg_context *ctx = *state;
    int errors = ctx ? cg_context_gl_error_count(ctx) : 0;
    cg_context_destroy(ctx);
    *state = NULL;
    if (errors) {
        fprintf(stderr, "%d GL error(s) counted that no test asserted on\n", errors);
        return -1;
    }
    return 0;
}

cg_context *
cg_test_gl_context(void **state)
{
    cg_context *ctx = *state;
    if (!ctx)
        fail_msg("no GL context: use cg_test_gl_setup as the group setup");
    return ctx;
}

float *
cg_test_read_texture(GLuint texture, int level, int *w, int *h, int *d)
{
    GLint width = 0, height = 0, depth = 0;
    glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_WIDTH, &width);
    glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_HEIGHT, &height);
    glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_DEPTH, &depth);
    if (width <= 0 || height <= 0 || depth <= 0)
        fail_msg("texture %u level %d has size %dx%dx%d", texture, level, width, height, depth);
    size_t count = (size_t)width * height * depth * 4;
    float *data = malloc(count * sizeof *data);
    if (!data)
        fail_msg("out of memory reading back texture %u", texture);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(texture, level, GL_RGBA, GL_FLOAT, (GLsizei)(count * sizeof *data), data);
    if (w)
        *w = width;
    if (h)
        *h = height;
    if (d)
        *d = depth;
    return data;
}

float *
cg_test_read_framebuffer(GLuint fbo, GLenum attachment, int w, int h)
{
    size_t count = (size_t)w * h * 4;
    float *data = malloc(count * sizeof *data);
    if (!data)
        fail_msg("out of memory reading back framebuffer %u", fbo);
    glNamedFramebufferReadBuffer(fbo, attachment);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadnPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, (GLsizei)(count * sizeof *data), data);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    return data;
}

int
cg_test_skip_program(const char *reason)
{
    printf("1..0 # SKIP %s\n", reason);
    fflush(stdout);
    return 0;
}

int
cg_test_run_conegraph(const char *args, bool with_stderr, char *out, size_t size)
{
    const char *exe = getenv("CONEGRAPH_EXE");
    assert_non_null(exe);
    char cmd[8192];
    snprintf(cmd, sizeof cmd, "'%s' %s %s", exe, args, with_stderr ? "2>&1" : "2>/dev/null");
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    size_t n = fread(out, 1, size - 1, p);
    out[n] = '\0';
    int status = pclose(p);
    assert_true(WIFEXITED(status));
    return WEXITSTATUS(status);
}

void
cg_test_scale_scene(cg_scene *s, double k)
{
    for (int i = 0; i < s->instance_count; i++)
        for (int c = 0; c < 4; c++)
            for (int r = 0; r < 3; r++)
                s->instances[i].world[c * 4 + r] = (float)(s->instances[i].world[c * 4 + r] * k);
    for (int i = 0; i < s->light_count; i++) {
        cg_light *l = &s->lights[i];
        for (int c = 0; c < 3; c++)
            l->position[c] = (float)(l->position[c] * k);
        l->range = (float)(l->range * k);
        if (l->type != CG_LIGHT_DIRECTIONAL)
            l->intensity = (float)(l->intensity * k * k);
    }
    for (int i = 0; i < s->camera_count; i++) {
        cg_camera *cam = &s->cameras[i];
        for (int r = 0; r < 3; r++)
            cam->world[12 + r] = (float)(cam->world[12 + r] * k);
        cam->znear = (float)(cam->znear * k);
        cam->zfar = (float)(cam->zfar * k);
        cam->xmag = (float)(cam->xmag * k);
        cam->ymag = (float)(cam->ymag * k);
    }
    cg_scene_compute_bounds(s);
}

static int
compare_names(const void *a, const void *b)
{
    return strcmp(a, b);
}

int
cg_test_list_graphs(char names[CG_TEST_MAX_GRAPHS][256])
{
    const char *dir = getenv("CONEGRAPH_GRAPH_DIR");
    if (!dir)
        fail_msg("CONEGRAPH_GRAPH_DIR is not set");
    DIR *d = opendir(dir);
    if (!d)
        fail_msg("cannot open %s", dir);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        size_t len = strlen(e->d_name);
        if (len > 5 && !strcmp(e->d_name + len - 5, ".json") && n < CG_TEST_MAX_GRAPHS && len < 256)
            snprintf(names[n++], 256, "%.*s", (int)(len - 5), e->d_name);
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof names[0], compare_names);
    return n;
}

double
cg_test_json_number(const char *json, const char *section, const char *key)
{
    const char *s = strstr(json, section);
    assert_non_null(s);
    char pattern[64];
    snprintf(pattern, sizeof pattern, "\"%s\": ", key);
    const char *k = strstr(s, pattern);
    assert_non_null(k);
    return strtod(k + strlen(pattern), NULL);
}
