#include "test_support.h"

#include "cg/fs.h"

#include <math.h>
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

static char *
next_path_slot(void)
{
    static char paths[CG_TEST_PATH_SLOTS][4200];
    static int next;
    return paths[next++ % CG_TEST_PATH_SLOTS];
}

const char *
cg_test_tmp_path(const char *name)
{
    char *path = next_path_slot();
    snprintf(path, 4200, "%s/%s", cg_test_tmpdir(), name);
    return path;
}

static const char *
path_under(const char *variable, const char *relative)
{
    const char *dir = getenv(variable);
    if (!dir)
        fail_msg("%s is not set: run the test through meson test", variable);
    char *path = next_path_slot();
    snprintf(path, 4200, "%s/%s", dir, relative);
    return path;
}

const char *
cg_test_data_path(const char *relative)
{
    return path_under("CONEGRAPH_TEST_DATA", relative);
}

const char *
cg_test_graph_path(const char *file)
{
    return path_under("CONEGRAPH_GRAPH_DIR", file);
}

const char *
cg_test_write_file(const char *name, const void *data, size_t size)
{
    const char *path = cg_test_tmp_path(name);
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

/* Runs `'EXE' ARGS TAIL` through the shell, EXE from the environment variable exe_var; its
 * stdout to out (NULL: read and dropped). Returns the exit code. */
static int
run_shell(const char *exe_var, const char *args, const char *tail, char *out, size_t size)
{
    const char *exe = getenv(exe_var);
    if (!exe)
        fail_msg("%s is not set: run the test through meson test", exe_var);
    char cmd[16384];
    int length = snprintf(cmd, sizeof cmd, "'%s' %s %s", exe, args, tail);
    if (length < 0 || (size_t)length >= sizeof cmd)
        fail_msg("command too long: %.200s...", cmd);
    FILE *p = popen(cmd, "r");
    if (!p)
        fail_msg("could not run: %s", cmd);
    if (out) {
        size_t n = fread(out, 1, size - 1, p);
        out[n] = '\0';
    }
    int status = pclose(p);
    if (status == -1 || !WIFEXITED(status))
        fail_msg("could not run: %s", cmd);
    return WEXITSTATUS(status);
}

int
cg_test_run_program(const char *exe_var, const char *args, bool with_stderr, char *out, size_t size)
{
    const char *tail = !out ? ">/dev/null 2>&1" : with_stderr ? "2>&1" : "2>/dev/null";
    return run_shell(exe_var, args, tail, out, size);
}

int
cg_test_run_conegraph(const char *args, bool with_stderr, char *out, size_t size)
{
    return cg_test_run_program("CONEGRAPH_EXE", args, with_stderr, out, size);
}

int
cg_test_run_conegraph_split(const char *args, char *out, size_t out_size, char *err, size_t err_size)
{
    const char *err_path = cg_test_tmp_path("stderr.txt");
    char tail[4300];
    snprintf(tail, sizeof tail, "2>'%s'", err_path);
    int code = run_shell("CONEGRAPH_EXE", args, tail, out, out_size);
    char *text;
    cg_error error = { 0 };
    assert_cg_ok(cg_read_file(err_path, &text, NULL, &error), &error);
    snprintf(err, err_size, "%s", text);
    free(text);
    return code;
}

void
cg_test_material_default(cg_material *m, int index)
{
    *m = (cg_material){ 0 };
    snprintf(m->name, sizeof m->name, "material %d", index);
    for (int k = 0; k < 4; k++)
        m->base_color[k] = 1.0f;
    m->base_color_texture = -1;
    m->metallic_roughness_texture = m->normal_texture = m->occlusion_texture = m->transmission_texture = -1;
    m->double_sided = true;
    m->alpha_cutoff = 0.5f;
    m->ior = 1.5f;
    m->normal_scale = m->occlusion_strength = 1.0f;
    m->attenuation_distance = INFINITY;
    for (int k = 0; k < 3; k++)
        m->specular_color[k] = m->attenuation_color[k] = 1.0f;
    for (int t = 0; t < CG_TEX_COUNT; t++)
        m->uv[t] = (cg_uv_transform){ { 1, 0, 0, 1, 0, 0 } };
    m->emissive_texture = -1;
    m->emissive_strength = 1.0f;
    m->roughness = 1.0f;
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

void
cg_test_expect_all(const char *text, const char *what, const char *const *wanted)
{
    for (int i = 0; wanted[i]; i++)
        if (!strstr(text, wanted[i]))
            fail_msg("%s: expected '%s' in:\n%s", what, wanted[i], text);
}

cg_scene
cg_test_load_scene(const char *source)
{
    cg_scene scene;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load(source, &scene, &err), &err);
    return scene;
}
