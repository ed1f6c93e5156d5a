/* The pass SDK's registration, state and descriptor helpers (sdk/pass.h). */
#include "sdk/pass.h"

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include "cg/shader.h"
#include "common/blocks.h"

static void
cgp_state_destroy_object(cgp_gl_kind kind, GLuint name)
{
    switch (kind) {
    case CGP_GL_PROGRAM: glDeleteProgram(name); break;
    case CGP_GL_BUFFER: glDeleteBuffers(1, &name); break;
    case CGP_GL_SAMPLER: glDeleteSamplers(1, &name); break;
    case CGP_GL_FRAMEBUFFER: glDeleteFramebuffers(1, &name); break;
    case CGP_GL_TEXTURE: glDeleteTextures(1, &name); break;
    }
}

bool
cgp_register_passes(fg_registry *registry, uint32_t host_abi, const fg_pass_type *const *types, int count,
                    cg_error *err)
{
    for (int i = 0; i < count; i++) {
        const fg_pass_type *type = types[i];
        if (type->abi_version != host_abi)
            return cg_fail(err, CG_ERR_PLUGIN_ABI,
                           "pass type '%s' was built for frame-graph ABI %u, but the host has ABI %u; "
                           "rebuild it against the host's cg/fg.h and pass SDK",
                           type->name ? type->name : "(unnamed)", (unsigned)type->abi_version, (unsigned)host_abi);
    }
    for (int i = 0; i < count; i++)
        if (!fg_registry_add(registry, types[i], err))
            return false;
    return true;
}

/* Lies before the pass's bytes; the union keeps those aligned for any type. A pass owns a
 * handful of GL objects (hsat, the most, 7), hence a fixed list. */
#define STATE_MAX_OBJECTS 32

typedef union state_header {
    struct {
        void (*cleanup)(void *state);
        int count;
        struct owned {
            cgp_gl_kind kind;
            GLuint name;
        } objects[STATE_MAX_OBJECTS];
    } h;
    max_align_t align;
} state_header;

static state_header *
header_of(void *state)
{
    return (state_header *)state - 1;
}

void *
cgp_state_new(const fg_pass *pass, size_t bytes, cg_error *err)
{
    state_header *header = calloc(1, sizeof *header + bytes);
    if (!header) {
        cg_fail(err, CG_ERR_OUT_OF_MEMORY, "pass '%s': out of memory for its state (%zu bytes)",
                fg_pass_name(pass), bytes);
        return NULL;
    }
    return header + 1;
}

void
cgp_state_on_destroy(void *state, void (*cleanup)(void *state))
{
    header_of(state)->h.cleanup = cleanup;
}

GLuint
cgp_own(void *state, cgp_gl_kind kind, GLuint name)
{
    state_header *header = header_of(state);
    if (name == 0)
        return 0;
    if (header->h.count == STATE_MAX_OBJECTS) {
        /* A programming error, as asking for an undeclared parameter is (cg/fg.h). */
        fprintf(stderr, "pass state: more than %d GL objects owned (sdk/pass.c)\n", STATE_MAX_OBJECTS);
        abort();
    }
    header->h.objects[header->h.count++] = (struct owned){kind, name};
    return name;
}

void
cgp_state_destroy(void *state)
{
    if (!state)
        return;
    state_header *header = header_of(state);
    if (header->h.cleanup)
        header->h.cleanup(state);
    for (int i = header->h.count - 1; i >= 0; i--)
        cgp_state_destroy_object(header->h.objects[i].kind, header->h.objects[i].name);
    free(header);
}

bool
cgp_prepared(void **state, void *s, bool ok)
{
    if (ok)
        *state = s;
    else
        cgp_state_destroy(s);
    return ok;
}

bool
cgp_compute_program(void *state, const char *shader, const char *defines, GLuint *out, cg_error *err)
{
    if (!cg_program_compute(shader, defines, out, err))
        return false;
    cgp_own(state, CGP_GL_PROGRAM, *out);
    return true;
}

bool
cgp_graphics_program(void *state, const char *vertex, const char *geometry, const char *fragment,
                     const char *defines, GLuint *out, cg_error *err)
{
    if (!cg_program_graphics(vertex, geometry, fragment, defines, out, err))
        return false;
    cgp_own(state, CGP_GL_PROGRAM, *out);
    return true;
}

GLuint
cgp_framebuffer(void *state)
{
    GLuint fbo;
    glCreateFramebuffers(1, &fbo);
    return cgp_own(state, CGP_GL_FRAMEBUFFER, fbo);
}

GLuint
cgp_buffer(void *state, size_t bytes, const void *data, GLbitfield flags)
{
    GLuint buffer;
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, (GLsizeiptr)bytes, data, flags);
    return cgp_own(state, CGP_GL_BUFFER, buffer);
}

GLuint
cgp_reads_counter(void *state)
{
    return cgp_buffer(state, FG_READS_COUNTER, NULL, GL_DYNAMIC_STORAGE_BIT);
}

void
cgp_reads_begin(GLuint counter)
{
    const GLuint zero = 0;
    glClearNamedBufferData(counter, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_READS, counter);
}

void
cgp_reads_end(fg_pass *pass, GLuint counter, const char *item)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_READS, 0);
    fg_pass_report_reads(pass, counter, item);
}

fg_resource_desc
cgp_image_2d(GLenum format, int width, int height)
{
    return (fg_resource_desc){
        .kind = FG_TEXTURE_2D, .format = format, .width = width, .height = height, .depth = 1, .levels = 1,
    };
}

fg_resource_desc
cgp_image_like(const fg_pass *pass, const fg_resource_desc *like, GLenum format)
{
    const fg_frame *frame = fg_pass_frame(pass);
    return cgp_image_2d(format, like ? like->width : frame->width, like ? like->height : frame->height);
}

fg_resource_desc
cgp_buffer_desc(size_t bytes)
{
    return (fg_resource_desc){.kind = FG_BUFFER, .depth = 1, .levels = 1, .buffer_bytes = bytes};
}

int
cgp_volume_levels(int width, int height, int depth)
{
    int levels = 1;
    while (width > 1 && height > 1 && depth > 1 && width % 2 == 0 && height % 2 == 0 && depth % 2 == 0) {
        width /= 2, height /= 2, depth /= 2;
        levels++;
    }
    return levels;
}

void
cgp_declare_in_place_chain(fg_declare *decl, const char *name, const fg_resource_desc *in, const char *single_level)
{
    if (in->levels < 2)
        fg_declare_nothing_to_do(decl, single_level);
    else
        fg_declare_output(decl, name, in, FG_ACCESS_IMAGE_STORE);
}

bool
cgp_bind_optional(const fg_pass *pass, GLuint unit, fg_slot slot, GLuint stand_in)
{
    bool present = fg_slot_present(pass, slot);
    glBindTextureUnit(unit, present ? fg_slot_texture(pass, slot) : stand_in);
    return present;
}

void
cgp_dispatch_2d(int width, int height)
{
    glDispatchCompute((GLuint)(width + 7) / 8, (GLuint)(height + 7) / 8, 1);
}

void
cgp_dispatch_over(const fg_pass *pass, fg_slot slot)
{
    const fg_resource_desc *image = fg_slot_resource(pass, slot);
    cgp_dispatch_2d(image->width, image->height);
}

void
cgp_compute_end(int image_units, int storage_count, const GLuint *storage)
{
    for (int i = 0; i < image_units; i++)
        glBindImageTexture((GLuint)i, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
    for (int i = 0; i < storage_count; i++)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, storage[i], 0);
    glUseProgram(0);
}

void
cgp_depth_draw_begin(GLuint fbo, int width, int height)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
}

void
cgp_depth_draw_end(void)
{
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}
