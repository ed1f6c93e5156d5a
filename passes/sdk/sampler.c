/* Samplers of the lightmaps (sdk/sampler.h). */
#include "sdk/sampler.h"

#include "sdk/pass.h"

static GLuint
new_sampler(void *state, GLint min_filter, GLint mag_filter, GLint wrap, int dimensions)
{
    static const GLenum axes[3] = {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R};
    GLuint sampler;
    glCreateSamplers(1, &sampler);
    glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, min_filter);
    glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, mag_filter);
    for (int i = 0; i < dimensions; i++)
        glSamplerParameteri(sampler, axes[i], wrap);
    return cgp_own(state, CGP_GL_SAMPLER, sampler);
}

/* A volume sampler that reads empty space (0) outside the volume. */
static GLuint
volume_sampler(void *state, GLenum min_filter)
{
    GLuint sampler = new_sampler(state, min_filter, GL_LINEAR, GL_CLAMP_TO_BORDER, 3);
    const float border[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glSamplerParameterfv(sampler, GL_TEXTURE_BORDER_COLOR, border);
    return sampler;
}

GLuint
cgp_sampler_volume(void *state)
{
    return volume_sampler(state, GL_LINEAR_MIPMAP_LINEAR);
}

GLuint
cgp_sampler_volume_one_level(void *state)
{
    return volume_sampler(state, GL_LINEAR_MIPMAP_NEAREST);
}

GLuint
cgp_sampler_lightmap2d(void *state)
{
    return new_sampler(state, GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE, 2);
}

GLuint
cgp_sampler_table(void *state)
{
    /* Wrapping stays GL's default: the tables are read by texelFetch inside their bounds. */
    return new_sampler(state, GL_NEAREST_MIPMAP_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE, 0);
}
