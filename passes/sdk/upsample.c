/* Decoupled GI resolution of a cone gather (sdk/upsample.h). */
#include "sdk/upsample.h"

#include <stdio.h>
#include <string.h>

#include "sdk/blocks.h"
#include "sdk/pass.h"

int
cgp_gather_downsample(const fg_pass *pass)
{
    int d = fg_param_int(pass, "downsample");
    if (d == 0)
        d = fg_pass_frame(pass)->height >= CGP_DOWNSAMPLE_AUTO_ROWS ? 8 : 4;
    return d;
}

const char *
cgp_gather_blocks_define(const fg_pass *pass, char *out, size_t size)
{
    int d = cgp_gather_downsample(pass);
    if (d > 1)
        snprintf(out, size, "#define CG_GATHER_DOWNSAMPLE %d\n%s", d,
                 fg_param_bool(pass, "interleave") ? "#define CG_GATHER_INTERLEAVE\n" : "");
    else if (size > 0)
        out[0] = '\0';
    return out;
}

/* An RGBA32F image of blocks, owned by `state`. */
static GLuint
block_texture(void *state, const cgp_gather_blocks *b)
{
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, b->width, b->height);
    /* Read by texelFetch only; a single level, complete under any filter. */
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return cgp_own(state, CGP_GL_TEXTURE, tex);
}

/* One of the gather shader's entry points (sdk/upsample.h): the full-resolution program's defines,
 * the model's and the material's as cgp_gather_prepare adds them, then `entry`'s. */
static bool
entry_point(void *state, const cgp_gather *g, const char *shader, const char *defines, const char *entry,
            GLuint *program, cg_error *err)
{
    char all[1024];
    snprintf(all, sizeof all, "%s%s%s%s", defines ? defines : "", cgp_gather_volume_define(g->model),
             g->material ? "#define CG_GATHER_MATERIAL\n" : "", entry);
    return cgp_compute_program(state, shader, all, program, err);
}

bool
cgp_gather_blocks_prepare(void *state, const fg_pass *pass, const cgp_gather *g, cgp_gather_blocks *b,
                          const char *shader, const char *defines, cg_error *err)
{
    *b = (cgp_gather_blocks){.downsample = cgp_gather_downsample(pass), .temporal = 1};
    const fg_resource_desc *out = fg_slot_resource(pass, g->slots.radiance);
    if (b->downsample <= 1 || !out)
        return true;
    b->temporal = fg_param_int(pass, "temporal");
    char temporal[96];
    snprintf(temporal, sizeof temporal, "#define CG_GATHER_TEMPORAL %d\n#define CG_GATHER_LOWRES\n", b->temporal);
    if (!entry_point(state, g, shader, defines, b->temporal > 1 ? temporal : "#define CG_GATHER_LOWRES\n",
                     &b->program, err) ||
        !entry_point(state, g, shader, defines, "#define CG_GATHER_DEFERRED\n", &b->deferred_program, err) ||
        !entry_point(state, g, shader, defines, "#define CG_GATHER_LOWRES\n#define CG_GATHER_DEFERRED\n",
                     &b->listed_program, err))
        return false;
    GLuint list = 0;
    glCreateBuffers(1, &list);
    glNamedBufferStorage(list, (GLsizeiptr)(sizeof(cg_gather_deferred_block) + sizeof(GLuint) * (size_t)out->width *
                                            (size_t)out->height),
                         NULL, GL_DYNAMIC_STORAGE_BIT);
    b->deferred = cgp_own(state, CGP_GL_BUFFER, list);
    b->width = (out->width + b->downsample - 1) / b->downsample;
    b->height = (out->height + b->downsample - 1) / b->downsample;
    b->texture[0] = block_texture(state, b);
    if (b->temporal > 1) {
        b->texture[1] = block_texture(state, b);
        for (int i = 0; i < 2; i++)
            for (int k = 0; k < 2; k++)
                b->history[i][k] = block_texture(state, b);
    }
    return true;
}

void
cgp_gather_blocks_trace(const fg_pass *pass, const cgp_gather *g, cgp_gather_blocks *b)
{
    if (b->downsample <= 1 || !b->program)
        return;
    /* The blocks that trace are listed first, then traced 64 to a lockstep group (common/upsample.glsl). */
    const cg_gather_deferred_block empty = {.dispatch = {0, 1, 1, 0}};
    glNamedBufferSubData(b->deferred, 0, sizeof empty, &empty);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_GATHER_DEFERRED, b->deferred);
    const fg_frame *frame = fg_pass_frame(pass);
    GLuint blocks = b->texture[b->temporal > 1 ? b->current : 0];
    glUseProgram(b->program);
    glBindImageTexture(0, blocks, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    if (b->temporal > 1) {
        /* common/upsample.glsl's cg_upsample_block_kept: this frame's turn, whether the last frame's
         * blocks and surfaces hold a traced frame, and the last camera; the last frame's blocks and
         * surfaces read, this frame's written. They are the state's, not graph resources that
         * another pass could reuse. */
        int last = 1 - b->current;
        for (int i = 0; i < 2; i++) {
            glBindImageTexture(CG_IMAGE_BLOCK_HISTORY + (GLuint)i, b->history[b->current][i], 0, GL_FALSE, 0,
                               GL_WRITE_ONLY, GL_RGBA32F);
            glBindTextureUnit(CG_UNIT_BLOCK_PREVIOUS + (GLuint)i, b->history[last][i]);
            glBindSampler(CG_UNIT_BLOCK_PREVIOUS + (GLuint)i, 0);
        }
        glBindTextureUnit(CG_UNIT_GATHER_BLOCKS, b->texture[last]);
        glBindSampler(CG_UNIT_GATHER_BLOCKS, 0);
        glUniform2i(CG_UPSAMPLE_TEMPORAL_LOCATION, (int)(frame->index % (uint64_t)b->temporal), b->traced ? 1 : 0);
        glUniformMatrix4fv(CG_UPSAMPLE_PREVIOUS_LOCATION, 1, GL_FALSE, b->previous_view_proj);
    }
    cgp_dispatch_2d(b->width, b->height);
    if (b->temporal > 1) {
        b->traced = true;
        memcpy(b->previous_view_proj, frame->view.view_proj, sizeof b->previous_view_proj);
        b->current = 1 - b->current;
        for (int i = 0; i < 2; i++) {
            glBindImageTexture(CG_IMAGE_BLOCK_HISTORY + (GLuint)i, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
            glBindTextureUnit(CG_UNIT_BLOCK_PREVIOUS + (GLuint)i, 0);
        }
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    glUseProgram(b->listed_program);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, b->deferred);
    glDispatchComputeIndirect(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    /* The full-resolution dispatch reads the blocks by texelFetch, and a pass's cost image written
     * at the representatives by the blocks' dispatch is written by it at the other pixels. */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindTextureUnit(CG_UNIT_GATHER_BLOCKS, blocks);
    glBindSampler(CG_UNIT_GATHER_BLOCKS, 0);
    /* The same list again, for the pixels that no block agrees with (cgp_gather_blocks_deferred). */
    glNamedBufferSubData(b->deferred, 0, sizeof empty, &empty);
    glUseProgram(g->program);
    glBindImageTexture(0, fg_slot_texture(pass, g->slots.radiance), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
}

void
cgp_gather_blocks_deferred(const fg_pass *pass, const cgp_gather *g, const cgp_gather_blocks *b)
{
    (void)pass;
    if (b->downsample <= 1 || !b->deferred_program)
        return;
    /* The list and its count (the indirect dispatch) and the pixels' other outputs written. */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glUseProgram(b->deferred_program);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, b->deferred);
    glDispatchComputeIndirect(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glUseProgram(g->program);
}

void
cgp_gather_blocks_end(const cgp_gather_blocks *b)
{
    if (b->downsample > 1) {
        glBindTextureUnit(CG_UNIT_GATHER_BLOCKS, 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_GATHER_DEFERRED, 0);
    }
}
