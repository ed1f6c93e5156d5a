/* sdk/shadow.h (pass SDK): a pass that reads a shadow map (shaders/common/shadow.glsl).
 *
 * Declares: cgp_declare_shadow_inputs, cgp_no_shadow, cgp_no_shadow_create, cgp_bind_shadow,
 *           cgp_lighting_record, cgp_lighting_change, cgp_lighting_read, cgp_lighting_changed,
 *           cgp_lighting_remember, cgp_lighting_record_free.
 *
 * The shadow map is an optional pair of inputs, `shadow` (a shadow_map pass's `depth`) and
 * `shadow_matrix` (its `matrix`, the block CG_SHADOW_BLOCK of common/blocks.h). Without them one
 * shader still serves: cgp_bind_shadow() binds a block whose light index is -1 (no light is
 * shadowed) and a depth map at the far plane, objects the pass creates in prepare() and its state
 * owns (cgp_state_new, sdk/pass.h).
 */
#ifndef CGP_SHADOW_H
#define CGP_SHADOW_H

#include <stdbool.h>

#include "cg/error.h"
#include "cg/fg.h"
#include "cg/scene.h"

/* Declares the optional inputs `shadow` and `shadow_matrix`; fails when only one is connected
 * (CG_ERR_GRAPH_MISSING_INPUT), when `shadow` is not GL_DEPTH_COMPONENT32F or `shadow_matrix`
 * smaller than a CG_SHADOW_BLOCK (CG_ERR_GRAPH_INCOMPATIBLE). */
bool cgp_declare_shadow_inputs(fg_pass *pass, fg_declare *decl, cg_error *err);

/* The shadow inputs' slots and the "no shadow map" fallback of one pass. */
typedef struct cgp_no_shadow {
    fg_slot shadow, matrix; /* the inputs `shadow` and `shadow_matrix` */
    GLuint block;   /* CG_SHADOW_BLOCK with light index -1 */
    GLuint map;     /* 1x1 GL_DEPTH_COMPONENT32F at the far plane */
} cgp_no_shadow;

/* In prepare(): the slots of a pass that called cgp_declare_shadow_inputs, and the fallback. */
void cgp_no_shadow_create(void *state, const fg_pass *pass, cgp_no_shadow *out);

/* Binds the pass's inputs `shadow` at `texture_unit` and `shadow_matrix` at CG_BINDING_SHADOW,
 * or the fallback where they are absent. */
void cgp_bind_shadow(const fg_pass *pass, const cgp_no_shadow *fallback, GLuint texture_unit);

/* ---- what a kept, lit result read of the lighting (voxel_light's volumes, heightmap_raster's map)
 *
 * The scene's lights by value and the shadow map: its texture and matrix buffer (the pass's inputs,
 * or its fallback) and the first bytes of its matrix block, read back, since a shadow_map pass
 * keeps its objects and rewrites the block. Zero-initialised: nothing recorded. A caster that moved
 * changes the shadow map's content, not these: the pass compares its instances too
 * (sdk/instances.h over every mesh). */
typedef struct cgp_lighting_record {
    bool taken;
    cg_light *lights;
    int light_count;
    GLuint shadow_objects[2];           /* the shadow map's texture, its matrix buffer */
    unsigned char shadow_block[256];    /* the matrix block as read back (its first bytes) */
} cgp_lighting_record;

typedef enum cgp_lighting_change {
    CGP_LIGHTING_SAME,
    CGP_LIGHTING_LIGHTS,        /* the lights differ (the shadow map may too) */
    CGP_LIGHTING_SHADOW         /* the shadow map's objects or matrix block alone */
} cgp_lighting_change;

/* The lighting the pass reads this frame (the shadow map through its inputs or `fallback`), read
 * into `now`, the scene's lights borrowed (valid while the scene's lights are). */
void cgp_lighting_read(const fg_pass *pass, const cgp_no_shadow *fallback, cgp_lighting_record *now);
/* What differs between the record and `now` (a record not taken: CGP_LIGHTING_LIGHTS). */
cgp_lighting_change cgp_lighting_changed(const cgp_lighting_record *record, const cgp_lighting_record *now);
/* Copies `now` into the record, its lights by value. False only when out of memory; the record then
 * holds nothing (the next comparison reports a change). */
bool cgp_lighting_remember(cgp_lighting_record *record, const cgp_lighting_record *now, cg_error *err);
void cgp_lighting_record_free(cgp_lighting_record *record);

#endif
