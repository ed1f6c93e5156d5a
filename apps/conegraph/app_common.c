/* What `render` and `bench` share: see app_common.h. */
#include "app_common.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cg/graphfile.h"

static bool
file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

const char *
app_graph_dir(void)
{
    const char *env = getenv("CONEGRAPH_GRAPH_DIR");
    if (env && *env)
        return env;
    struct stat st;
    if (stat(CONEGRAPH_GRAPH_SOURCE_DIR, &st) == 0 && S_ISDIR(st.st_mode))
        return CONEGRAPH_GRAPH_SOURCE_DIR;
    return CONEGRAPH_GRAPH_INSTALL_DIR;
}

void
app_resolve_graph(const char *given, char *out, size_t size)
{
    if (given && (file_exists(given) || strchr(given, '/'))) {
        snprintf(out, size, "%s", given);
        return;
    }
    if (given) {
        snprintf(out, size, "%s/%s", app_graph_dir(), given);
        if (!file_exists(out))
            snprintf(out, size, "%s", given);
        return;
    }
    snprintf(out, size, "%s/vct.json", app_graph_dir());
    if (file_exists(out))
        return;
    snprintf(out, size, "%s/direct.json", app_graph_dir());
}

bool
app_load_graph(fg_graph *graph, const char *path, const char *const *sets, int set_count, cg_error *err)
{
    if (!fg_graph_load_file(graph, path, err))
        return false;
    for (int i = 0; i < set_count; i++)
        if (!fg_graph_apply_override(graph, sets[i], err))
            return false;
    return true;
}

const char *
app_find_output(const fg_graph *graph, const char *suffix)
{
    for (int i = 0; i < fg_graph_output_count(graph); i++) {
        const char *name = fg_graph_output_at(graph, i);
        const char *dot = strrchr(name, '.');
        if (dot && !strcmp(dot + 1, suffix))
            return name;
    }
    return NULL;
}

bool
app_read_resource(const fg_graph *graph, const char *source, bool srgb_encoded, cg_image *out, cg_error *err)
{
    const fg_resource_info *info = fg_graph_find_resource(graph, source);
    GLuint texture = fg_graph_texture(graph, source);
    if (!info || info->absent || !texture)
        return cg_fail(err, CG_ERR_PASS, "%s: resource absent (its pass was culled or had nothing to do)", source);
    if (info->desc.kind == FG_BUFFER)
        return cg_fail(err, CG_ERR_USAGE, "%s: a buffer, not a texture; only textures can be written as images", source);
    int w = info->desc.width, h = info->desc.height;
    int layers = info->desc.kind == FG_TEXTURE_2D ? 1 : info->desc.depth;
    size_t texels = (size_t)w * (size_t)h * (size_t)layers;
    bool depth = info->desc.format == GL_DEPTH_COMPONENT32F || info->desc.format == GL_DEPTH_COMPONENT24 ||
                 info->desc.format == GL_DEPTH_COMPONENT16 || info->desc.format == GL_DEPTH_COMPONENT32;
    float *data = malloc(texels * 4 * sizeof(float));
    if (!data)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: %zu texels", source, texels);
    /* The last writer may have used image stores. */
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (depth) {
        float *d = malloc(texels * sizeof(float));
        if (!d) {
            free(data);
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: %zu texels", source, texels);
        }
        glGetTextureImage(texture, 0, GL_DEPTH_COMPONENT, GL_FLOAT, (GLsizei)(texels * sizeof(float)), d);
        for (size_t i = 0; i < texels; i++) {
            data[4 * i + 0] = data[4 * i + 1] = data[4 * i + 2] = d[i];
            data[4 * i + 3] = 1.0f;
        }
        free(d);
    } else {
        glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, (GLsizei)(texels * 4 * sizeof(float)), data);
    }
    if (!cg_image_alloc(out, w, h * layers, err)) {
        free(data);
        return false;
    }
    /* GL rows go bottom to top; image files top to bottom. */
    for (int layer = 0; layer < layers; layer++)
        for (int y = 0; y < h; y++) {
            const float *src = data + ((size_t)layer * (size_t)h + (size_t)y) * (size_t)w * 4;
            float *dst = out->rgba + ((size_t)layer * (size_t)h + (size_t)(h - 1 - y)) * (size_t)w * 4;
            memcpy(dst, src, (size_t)w * 4 * sizeof(float));
        }
    free(data);
    if (srgb_encoded) {
        /* The ldr texture holds sRGB-encoded values; cg_image is linear and the PNG writer encodes. */
        for (size_t i = 0; i < (size_t)w * (size_t)h * (size_t)layers; i++)
            for (int c = 0; c < 3; c++)
                out->rgba[4 * i + c] = cg_srgb_decode(out->rgba[4 * i + c]);
    }
    return true;
}

bool
app_parse_int(const char *text, long min, long max, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (errno || end == text || *end || v < min || v > max)
        return false;
    *out = v;
    return true;
}

bool
app_parse_size(const char *text, int *w, int *h)
{
    char buf[64];
    if (strlen(text) >= sizeof buf)
        return false;
    strcpy(buf, text);
    char *x = strchr(buf, 'x');
    if (!x)
        return false;
    *x = '\0';
    long lw, lh;
    if (!app_parse_int(buf, 1, 65536, &lw) || !app_parse_int(x + 1, 1, 65536, &lh))
        return false;
    *w = (int)lw;
    *h = (int)lh;
    return true;
}

bool
app_parse_timing(const char *text, fg_timing_mode *out)
{
    if (!strcmp(text, "sync"))
        *out = FG_TIMING_SYNC;
    else if (!strcmp(text, "queries"))
        *out = FG_TIMING_QUERIES;
    else if (!strcmp(text, "none"))
        *out = FG_TIMING_NONE;
    else
        return false;
    return true;
}

double
app_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

int
app_compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}
