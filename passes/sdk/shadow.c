/* The shadow-map inputs of a pass and their fallback (sdk/shadow.h). */
#include "sdk/shadow.h"

#include <stdlib.h>
#include <string.h>

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

void
cgp_lighting_read(const fg_pass *pass, const cgp_no_shadow *fallback, cgp_lighting_record *now)
{
    memset(now, 0, sizeof *now);
    const cg_scene *scene = fg_pass_frame(pass)->scene;
    now->taken = true;
    now->lights = scene->lights;
    now->light_count = scene->light_count;
    now->shadow_objects[0] = fg_slot_texture(pass, fallback->shadow);
    now->shadow_objects[1] = fg_slot_buffer(pass, fallback->matrix);
    const fg_resource_desc *matrix = fg_slot_resource(pass, fallback->matrix);
    if (matrix && now->shadow_objects[1]) {
        size_t bytes = matrix->buffer_bytes < sizeof now->shadow_block ? matrix->buffer_bytes : sizeof now->shadow_block;
        glGetNamedBufferSubData(now->shadow_objects[1], 0, (GLsizeiptr)bytes, now->shadow_block);
    }
}

cgp_lighting_change
cgp_lighting_changed(const cgp_lighting_record *record, const cgp_lighting_record *now)
{
    if (!record->taken || record->light_count != now->light_count ||
        (now->light_count > 0 && memcmp(record->lights, now->lights, sizeof *now->lights * (size_t)now->light_count)))
        return CGP_LIGHTING_LIGHTS;
    if (memcmp(record->shadow_objects, now->shadow_objects, sizeof now->shadow_objects) ||
        memcmp(record->shadow_block, now->shadow_block, sizeof now->shadow_block))
        return CGP_LIGHTING_SHADOW;
    return CGP_LIGHTING_SAME;
}

bool
cgp_lighting_remember(cgp_lighting_record *record, const cgp_lighting_record *now, cg_error *err)
{
    record->taken = false;
    if (now->light_count != record->light_count) {
        free(record->lights);
        record->lights = NULL;
        record->light_count = 0;
        if (now->light_count > 0) {
            record->lights = malloc(sizeof *record->lights * (size_t)now->light_count);
            if (!record->lights)
                return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory keeping %d lights", now->light_count);
        }
        record->light_count = now->light_count;
    }
    if (now->light_count > 0)
        memcpy(record->lights, now->lights, sizeof *now->lights * (size_t)now->light_count);
    memcpy(record->shadow_objects, now->shadow_objects, sizeof now->shadow_objects);
    memcpy(record->shadow_block, now->shadow_block, sizeof now->shadow_block);
    record->taken = true;
    return true;
}

void
cgp_lighting_record_free(cgp_lighting_record *record)
{
    free(record->lights);
    memset(record, 0, sizeof *record);
}
