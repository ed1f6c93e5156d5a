/* The baked sky (sdk/sky.h). */
#include "sdk/sky.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sdk/pass.h"

#define SKY_PI 3.14159265358979323846

void
cgp_sky_direction(int i, int j, double dir[3])
{
    double phi = 2.0 * SKY_PI * (i + 0.5) / CGP_SKY_WIDTH - SKY_PI;
    double theta = SKY_PI * (j + 0.5) / CGP_SKY_HEIGHT;
    dir[0] = sin(theta) * sin(phi);
    dir[1] = cos(theta);
    dir[2] = sin(theta) * cos(phi);
}

double
cgp_sky_layer_half_angle(int layer)
{
    return layer <= 0 ? 0.0 : SKY_PI / CGP_SKY_HEIGHT * ldexp(1.0, layer - 1);
}

/* One lat-long grid of the sky at a coarser resolution: radiance (solid-angle-weighted mean of
 * its layer-0 texels), solid angle and centre direction of each texel. */
typedef struct sky_grid {
    int width, height;
    double *rgb, *omega, *dir;
} sky_grid;

static bool
grid_make(sky_grid *g, const float *layer0, int factor)
{
    g->width = CGP_SKY_WIDTH / factor;
    g->height = CGP_SKY_HEIGHT / factor;
    size_t n = (size_t)g->width * g->height;
    g->rgb = calloc(n * 3, sizeof *g->rgb);
    g->omega = calloc(n, sizeof *g->omega);
    g->dir = calloc(n * 3, sizeof *g->dir);
    if (!g->rgb || !g->omega || !g->dir)
        return false;
    double dphi = 2.0 * SKY_PI / CGP_SKY_WIDTH;
    for (int j = 0; j < CGP_SKY_HEIGHT; j++) {
        /* The exact solid angle of a lat-long texel: dphi (cos theta_top - cos theta_bottom). */
        double omega = dphi * (cos(SKY_PI * j / CGP_SKY_HEIGHT) - cos(SKY_PI * (j + 1) / CGP_SKY_HEIGHT));
        for (int i = 0; i < CGP_SKY_WIDTH; i++) {
            size_t k = (size_t)(j / factor) * g->width + (size_t)(i / factor);
            const float *src = layer0 + 4 * ((size_t)j * CGP_SKY_WIDTH + i);
            for (int c = 0; c < 3; c++)
                g->rgb[3 * k + c] += omega * src[c];
            g->omega[k] += omega;
        }
    }
    for (int j = 0; j < g->height; j++)
        for (int i = 0; i < g->width; i++) {
            size_t k = (size_t)j * g->width + i;
            for (int c = 0; c < 3; c++)
                g->rgb[3 * k + c] /= g->omega[k];
            double phi = 2.0 * SKY_PI * (i + 0.5) / g->width - SKY_PI;
            double theta = SKY_PI * (j + 0.5) / g->height;
            g->dir[3 * k + 0] = sin(theta) * sin(phi);
            g->dir[3 * k + 1] = cos(theta);
            g->dir[3 * k + 2] = sin(theta) * cos(phi);
        }
    return true;
}

static void
grid_free(sky_grid *g)
{
    free(g->rgb);
    free(g->omega);
    free(g->dir);
}

/* Layer k: at each texel, sum over the grid's texels within theta_k of its direction of
 * L omega cos / sum omega cos (the cosine-weighted mean over the cone). The grid is coarser for
 * wider cones, so that each cone spans about 8 grid texels in radius at least and the sum costs
 * about the same per layer (some 50 million terms for all layers). */
static void
bake_layer(const sky_grid *g, int layer, float *out)
{
    double half = cgp_sky_layer_half_angle(layer);
    double cos_half = cos(half);
    double row_angle = SKY_PI / g->height;
    for (int j = 0; j < CGP_SKY_HEIGHT; j++) {
        double theta = SKY_PI * (j + 0.5) / CGP_SKY_HEIGHT;
        /* Rows whose texels can lie in the cone: centres within half + one row of theta. */
        int r0 = (int)floor((theta - half) / row_angle - 1.0), r1 = (int)ceil((theta + half) / row_angle + 1.0);
        if (r0 < 0)
            r0 = 0;
        if (r1 > g->height - 1)
            r1 = g->height - 1;
        for (int i = 0; i < CGP_SKY_WIDTH; i++) {
            double d[3];
            cgp_sky_direction(i, j, d);
            double sum[3] = {0.0, 0.0, 0.0}, weight = 0.0;
            for (int r = r0; r <= r1; r++)
                for (int q = 0; q < g->width; q++) {
                    size_t k = (size_t)r * g->width + q;
                    const double *s = g->dir + 3 * k;
                    double c = d[0] * s[0] + d[1] * s[1] + d[2] * s[2];
                    if (c < cos_half || !(c > 0.0))
                        continue;
                    double w = g->omega[k] * c;
                    for (int ch = 0; ch < 3; ch++)
                        sum[ch] += w * g->rgb[3 * k + ch];
                    weight += w;
                }
            float *t = out + 4 * ((size_t)j * CGP_SKY_WIDTH + i);
            for (int ch = 0; ch < 3; ch++)
                t[ch] = weight > 0.0 ? (float)(sum[ch] / weight) : 0.0f;
            t[3] = 1.0f;
        }
    }
}

bool
cgp_sky_bake(const cg_scene *scene, float *texels, cg_error *err)
{
    cg_sky_model model;
    if (!cg_sky_model_init(scene, &model, err))
        return false;
    const size_t layer_floats = (size_t)CGP_SKY_WIDTH * CGP_SKY_HEIGHT * 4;
    for (int j = 0; j < CGP_SKY_HEIGHT; j++)
        for (int i = 0; i < CGP_SKY_WIDTH; i++) {
            double d[3];
            cgp_sky_direction(i, j, d);
            const float dir[3] = {(float)d[0], (float)d[1], (float)d[2]};
            float *t = texels + 4 * ((size_t)j * CGP_SKY_WIDTH + i);
            cg_sky_model_radiance(&model, dir, t);
            t[3] = 1.0f;
        }
    if (model.type != CG_SKY_PREETHAM) {
        /* Uniform (or none): every cone's mean is the radiance itself, to the bit. */
        for (int k = 1; k < CGP_SKY_LAYERS; k++)
            memcpy(texels + k * layer_floats, texels, layer_floats * sizeof *texels);
        return true;
    }
    sky_grid grids[3] = {{0}};
    bool ok = true;
    for (int g = 0; g < 3 && ok; g++)
        ok = grid_make(&grids[g], texels, 1 << g);
    for (int k = 1; k < CGP_SKY_LAYERS && ok; k++)
        bake_layer(&grids[k <= 4 ? 0 : k - 4 < 2 ? k - 4 : 2], k, texels + k * layer_floats);
    for (int g = 0; g < 3; g++)
        grid_free(&grids[g]);
    if (!ok)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory baking the sky", scene->name);
    return true;
}

void
cgp_sky_prepare(void *state, cgp_sky *sky)
{
    memset(sky, 0, sizeof *sky);
    glCreateSamplers(1, &sky->sampler);
    glSamplerParameteri(sky->sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(sky->sampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(sky->sampler, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glSamplerParameteri(sky->sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(sky->sampler, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    cgp_own(state, CGP_GL_SAMPLER, sky->sampler);
    sky->block = cgp_uniform_buffer(state, sizeof(cg_sky_block));
}

/* The texels of the last bake in this process, by the model they were baked from: every pass
 * that reads the sky (gbuffer, a gather) bakes the same sky, so the second one only uploads. The
 * model holds everything the radiance depends on (the sun's direction included). */
static struct {
    bool valid;
    cg_sky_model model;
    float *texels;
} last_bake;

static bool
bake_cached(const cg_scene *scene, const float **texels, cg_error *err)
{
    cg_sky_model model;
    if (!cg_sky_model_init(scene, &model, err))
        return false;
    if (!last_bake.valid || memcmp(&model, &last_bake.model, sizeof model) != 0) {
        if (!last_bake.texels && !(last_bake.texels = malloc(CGP_SKY_BYTES)))
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory baking the sky", scene->name);
        last_bake.valid = false;
        if (!cgp_sky_bake(scene, last_bake.texels, err))
            return false;
        last_bake.model = model;
        last_bake.valid = true;
    }
    *texels = last_bake.texels;
    return true;
}

bool
cgp_sky_update(void *state, cgp_sky *sky, const cg_scene *scene, cg_error *err)
{
    sky->present = scene && scene->sky.type != CG_SKY_NONE;
    if (sky->present) {
        bool follows_sun = scene->sky.type == CG_SKY_PREETHAM;
        bool changed = !sky->baked || !cg_sky_equal(&sky->sky, &scene->sky) ||
                       (follows_sun && sky->lights_revision != scene->lights_revision);
        if (changed) {
            const float *texels = NULL;
            if (!bake_cached(scene, &texels, err))
                return false;
            if (!sky->texture) {
                glCreateTextures(GL_TEXTURE_3D, 1, &sky->texture);
                glTextureStorage3D(sky->texture, 1, GL_RGBA32F, CGP_SKY_WIDTH, CGP_SKY_HEIGHT, CGP_SKY_LAYERS);
                cgp_own(state, CGP_GL_TEXTURE, sky->texture);
            }
            glTextureSubImage3D(sky->texture, 0, 0, 0, 0, CGP_SKY_WIDTH, CGP_SKY_HEIGHT, CGP_SKY_LAYERS, GL_RGBA,
                                GL_FLOAT, texels);
            sky->sky = scene->sky;
            sky->lights_revision = scene->lights_revision;
            sky->baked = true;
            sky->bakes++;
        }
    }
    const cg_sky_block block = {
        .info = {sky->present ? 1.0f : 0.0f, (float)CGP_SKY_LAYERS, (float)cgp_sky_layer_half_angle(1), 0.0f},
    };
    glNamedBufferSubData(sky->block, 0, sizeof block, &block);
    return true;
}

void
cgp_sky_bind(const cgp_sky *sky)
{
    glBindBufferBase(GL_UNIFORM_BUFFER, CG_BINDING_SKY, sky->block);
    glBindTextureUnit(CG_UNIT_SKY, sky->present ? sky->texture : 0);
    glBindSampler(CG_UNIT_SKY, sky->sampler);
}

void
cgp_sky_unbind(void)
{
    glBindSampler(CG_UNIT_SKY, 0);
}
