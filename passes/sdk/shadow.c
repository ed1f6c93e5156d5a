/* The shadow-map inputs of a pass and their fallback (sdk/shadow.h). */
#include "sdk/shadow.h"

#include "sdk/blocks.h"
#include "sdk/pass.h"

/* Declared by these names, found by them in cgp_no_shadow_create. */
static const char *const shadow_name = "shadow", *const matrix_name = "shadow_matrix";

bool
cgp_declare_shadow_inputs(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_resource_desc *shadow = fg_declare_input(decl, shadow_name, FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
    const fg_resource_desc *matrix = fg_declare_input(decl, matrix_name, FG_BUFFER, FG_ACCESS_UNIFORM, false);
    if (!shadow != !matrix)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': inputs 'shadow' and 'shadow_matrix' go together (a shadow_map "
                       "pass's outputs 'depth' and 'matrix'); only one is present", fg_pass_name(pass));
    if (shadow && shadow->format != GL_DEPTH_COMPONENT32F)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'shadow' must be a GL_DEPTH_COMPONENT32F shadow map", fg_pass_name(pass));
    if (matrix && matrix->buffer_bytes < sizeof(cg_shadow_block))
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'shadow_matrix' holds %zu bytes; a shadow_map 'matrix' holds %zu",
                       fg_pass_name(pass), matrix->buffer_bytes, sizeof(cg_shadow_block));
    return true;
}

void
cgp_no_shadow_create(void *state, const fg_pass *pass, cgp_no_shadow *out)
{
    out->shadow = fg_pass_slot(pass, shadow_name);
    out->matrix = fg_pass_slot(pass, matrix_name);
    const cg_shadow_block block = {.frustum = {-1.0f, 0.0f, 0.0f, 0.0f}};
    glCreateBuffers(1, &out->block);
    glNamedBufferStorage(out->block, sizeof block, &block, 0);
    glCreateTextures(GL_TEXTURE_2D, 1, &out->map);
    glTextureStorage2D(out->map, 1, GL_DEPTH_COMPONENT32F, 1, 1);
    const float far_depth = 1.0f;
    glClearTexImage(out->map, 0, GL_DEPTH_COMPONENT, GL_FLOAT, &far_depth);
    cgp_own(state, CGP_GL_BUFFER, out->block);
    cgp_own(state, CGP_GL_TEXTURE, out->map);
}

void
cgp_bind_shadow(const fg_pass *pass, const cgp_no_shadow *fallback, GLuint texture_unit)
{
    GLuint map = fg_slot_texture(pass, fallback->shadow), block = fg_slot_buffer(pass, fallback->matrix);
    bool shadowed = map != 0 && block != 0;
    glBindBufferBase(GL_UNIFORM_BUFFER, CG_BINDING_SHADOW, shadowed ? block : fallback->block);
    glBindTextureUnit(texture_unit, shadowed ? map : fallback->map);
}
