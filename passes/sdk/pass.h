/* sdk/pass.h (pass SDK): what every pass needs beside cg/fg.h: its registration, its state,
 * the descriptors of its usual outputs and its compute dispatch.
 *
 * Declares: CGP_PARAMS, CGP_NO_PARAMS, CGP_SLOTS, CGP_PASS, CGP_REGISTER_PASS, CGP_PLUGIN, cgp_register_passes,
 *           cgp_gl_kind, cgp_state_new, cgp_state_on_destroy, cgp_state_destroy, cgp_prepared, cgp_own,
 *           cgp_compute_program,
 *           cgp_graphics_program, cgp_framebuffer, cgp_buffer, cgp_reads_counter, cgp_reads_begin,
 *           cgp_reads_end, cgp_image_2d, cgp_image_like, cgp_buffer_desc,
 *           cgp_declare_in_place_chain, cgp_bind_optional, cgp_dispatch_2d, cgp_dispatch_over, cgp_compute_end, cgp_depth_draw_begin,
 *           cgp_depth_draw_end.
 *
 * A built-in pass is defined by
 *     CGP_PASS(cone_gather, CGP_PARAMS(cone_gather_params), "doc ...");
 * which defines its fg_pass_type from cone_gather_state and cone_gather_declare, _prepare and
 * _execute, and, through CGP_REGISTER_PASS, cg_pass_register_cone_gather(registry, host_abi, err),
 * the function that passes/builtin.c (generated) calls, with the very signature of a plugin's
 * entry point. A plugin (a shared object loaded with --plugin) defines
 * its static fg_pass_type(s) and writes
 *     CGP_PLUGIN(&fill_type, &other_type);
 * which defines conegraph_plugin_register(). Both go through cgp_register_passes(), the one
 * place that compares the ABI a pass was built for with the host's; core's plugin loader
 * passes the host's FG_ABI_VERSION as host_abi. docs/architecture.md walks through a plugin.
 */
#ifndef CGP_PASS_H
#define CGP_PASS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cg/error.h"
#include "cg/fg.h"

/* The `params` and `param_count` of an fg_pass_type from a static table, or none. */
#define CGP_PARAMS(table) .params = (table), .param_count = (int)(sizeof(table) / sizeof((table)[0]))
#define CGP_NO_PARAMS .params = NULL, .param_count = 0

/* Sets each named member of the state `st` to the handle of the pass's slot of the same name:
 *     CGP_SLOTS(pass, st, position, normal, radiance);
 * is st->position = fg_pass_slot(pass, "position"), and so for normal and radiance, so that a
 * member and the slot it holds cannot be spelt apart. Up to 8 names; a prepare() with more calls
 * it twice. A misspelt name fails in fg_pass_slot as any lookup does. */
#define CGP_SLOTS(pass, st, ...)                                                                   \
    CGP_SLOTS_PICK_(__VA_ARGS__, CGP_SLOTS8_, CGP_SLOTS7_, CGP_SLOTS6_, CGP_SLOTS5_, CGP_SLOTS4_,  \
                    CGP_SLOTS3_, CGP_SLOTS2_, CGP_SLOTS1_, ~)((pass), (st), __VA_ARGS__)
#define CGP_SLOTS_PICK_(a, b, c, d, e, f, g, h, chosen, ...) chosen
#define CGP_SLOT_(p, s, m) ((s)->m = fg_pass_slot(p, #m))
#define CGP_SLOTS1_(p, s, m) CGP_SLOT_(p, s, m)
#define CGP_SLOTS2_(p, s, m, ...) (CGP_SLOT_(p, s, m), CGP_SLOTS1_(p, s, __VA_ARGS__))
#define CGP_SLOTS3_(p, s, m, ...) (CGP_SLOT_(p, s, m), CGP_SLOTS2_(p, s, __VA_ARGS__))
#define CGP_SLOTS4_(p, s, m, ...) (CGP_SLOT_(p, s, m), CGP_SLOTS3_(p, s, __VA_ARGS__))
#define CGP_SLOTS5_(p, s, m, ...) (CGP_SLOT_(p, s, m), CGP_SLOTS4_(p, s, __VA_ARGS__))
#define CGP_SLOTS6_(p, s, m, ...) (CGP_SLOT_(p, s, m), CGP_SLOTS5_(p, s, __VA_ARGS__))
#define CGP_SLOTS7_(p, s, m, ...) (CGP_SLOT_(p, s, m), CGP_SLOTS6_(p, s, __VA_ARGS__))
#define CGP_SLOTS8_(p, s, m, ...) (CGP_SLOT_(p, s, m), CGP_SLOTS7_(p, s, __VA_ARGS__))

/* Registers `count` pass types. Each type's abi_version is the FG_ABI_VERSION of the headers
 * it was compiled against; it must equal host_abi (CG_ERR_PLUGIN_ABI otherwise, naming the
 * type and both versions). This function reads only abi_version and name before that check,
 * the first two members of fg_pass_type, which every ABI keeps, so that it may refuse a
 * plugin of another ABI safely. Then fg_registry_add() checks the rest of each descriptor. */
bool cgp_register_passes(fg_registry *registry, uint32_t host_abi, const fg_pass_type *const *types, int count,
                         cg_error *err);

/* Defines cg_pass_register_NAME for the pass type `type`. Written with a semicolon after it. */
#define CGP_REGISTER_PASS(name, type)                                                        \
    bool cg_pass_register_##name(fg_registry *registry, uint32_t host_abi, cg_error *err);   \
    bool cg_pass_register_##name(fg_registry *registry, uint32_t host_abi, cg_error *err)    \
    {                                                                                        \
        static const fg_pass_type *const types[] = {&(type)};                                \
        return cgp_register_passes(registry, host_abi, types, 1, err);                       \
    }                                                                                        \
    bool cg_pass_register_##name(fg_registry *registry, uint32_t host_abi, cg_error *err)

/* The built-in pass `id`, by convention: its state type id_state (a struct), its callbacks
 *     static bool id_declare(fg_pass *pass, fg_declare *decl, cg_error *err);
 *     static bool id_prepare(fg_pass *pass, id_state *s, cg_error *err);
 *     static bool id_execute(fg_pass *pass, id_state *s, cg_error *err);
 * `params` (CGP_PARAMS(table) or CGP_NO_PARAMS) and `doc`. Defines its fg_pass_type id_type,
 * whose prepare allocates the state (cgp_state_new) and hands it to id_prepare, destroying it
 * when that fails, and whose destroy is cgp_state_destroy; and, by CGP_REGISTER_PASS, its
 * registration function cg_pass_register_id. Written with a semicolon after it. */
#define CGP_PASS(id, params, doc_)                                                           \
    static bool id##_declare(fg_pass *pass, fg_declare *decl, cg_error *err);                \
    static bool id##_prepare(fg_pass *pass, id##_state *s, cg_error *err);                   \
    static bool id##_execute(fg_pass *pass, id##_state *s, cg_error *err);                   \
    static bool id##_prepare_state(fg_pass *pass, void **state, cg_error *err)               \
    {                                                                                        \
        id##_state *s = cgp_state_new(pass, sizeof *s, err);                                 \
        return s && cgp_prepared(state, s, id##_prepare(pass, s, err));                      \
    }                                                                                        \
    static bool id##_execute_state(fg_pass *pass, void *state, cg_error *err)                \
    {                                                                                        \
        return id##_execute(pass, state, err);                                               \
    }                                                                                        \
    static const fg_pass_type id##_type = {                                                  \
        .abi_version = FG_ABI_VERSION, .name = #id, .doc = doc_, params,                     \
        .declare = id##_declare, .prepare = id##_prepare_state,                              \
        .execute = id##_execute_state, .destroy = cgp_state_destroy};                        \
    CGP_REGISTER_PASS(id, id##_type)

/* The plugin entry point FG_PLUGIN_ENTRY for the pass types given as pointers. Written with a
 * semicolon after it. */
#define CGP_PLUGIN(...)                                                                      \
    bool conegraph_plugin_register(fg_registry *registry, uint32_t host_abi, cg_error *err); \
    bool conegraph_plugin_register(fg_registry *registry, uint32_t host_abi, cg_error *err)  \
    {                                                                                        \
        static const fg_pass_type *const types[] = {__VA_ARGS__};                            \
        return cgp_register_passes(registry, host_abi, types,                                \
                                   (int)(sizeof types / sizeof types[0]), err);              \
    }                                                                                        \
    bool conegraph_plugin_register(fg_registry *registry, uint32_t host_abi, cg_error *err)

/* ---- the state a pass makes in prepare() and the GL objects it owns
 *
 * cgp_state_new() returns `bytes` zeroed, with room beside them for a list of GL objects that
 * the SDK deletes together with the state: cgp_state_destroy() is the pass type's destroy (or is
 * called by it). Objects made through cgp_compute_program(), cgp_graphics_program(),
 * cgp_framebuffer(), cgp_uniform_buffer(), cgp_no_shadow_create() or handed over by cgp_own()
 * belong to the state, so that a prepare() that fails half-way frees what it made (cgp_prepared)
 * and a pass writes no destroy of its own for GL objects. */

typedef enum cgp_gl_kind {
    CGP_GL_PROGRAM,
    CGP_GL_BUFFER,
    CGP_GL_SAMPLER,
    CGP_GL_FRAMEBUFFER,
    CGP_GL_TEXTURE
} cgp_gl_kind;

/* A zeroed state; NULL with CG_ERR_OUT_OF_MEMORY naming the pass. */
void *cgp_state_new(const fg_pass *pass, size_t bytes, cg_error *err);
/* `cleanup` will run first in cgp_state_destroy, for what the state holds beside GL objects. */
void cgp_state_on_destroy(void *state, void (*cleanup)(void *state));
/* Runs the cleanup, deletes the state's GL objects and frees it; NULL does nothing. */
void cgp_state_destroy(void *state);
/* The end of a prepare(): with `ok`, hands `s` to the graph (*state = s); otherwise destroys it
 * (the graph destroys only the states of passes that prepared). Returns ok. */
bool cgp_prepared(void **state, void *s, bool ok);
/* Hands the GL object `name` of `kind` to the state; returns it. */
GLuint cgp_own(void *state, cgp_gl_kind kind, GLuint name);
/* cg_program_compute / cg_program_graphics (cg/shader.h), the program owned by the state. */
bool cgp_compute_program(void *state, const char *shader, const char *defines, GLuint *out, cg_error *err);
bool cgp_graphics_program(void *state, const char *vertex, const char *geometry, const char *fragment,
                          const char *defines, GLuint *out, cg_error *err);
/* A framebuffer object owned by the state. */
GLuint cgp_framebuffer(void *state);
/* A buffer of `bytes` (glNamedBufferStorage with `data` and `flags`) owned by the state. */
GLuint cgp_buffer(void *state, size_t bytes, const void *data, GLbitfield flags);

/* The texture reads of a pass's shaders (fg_pass_report_reads; common/reads.glsl counts them):
 * a counter of FG_READS_COUNTER bytes owned by the state; cgp_reads_begin, before the pass's
 * dispatches, zeroes it and binds it at CG_BINDING_READS; cgp_reads_end, after them, hands it to
 * the graph, the reads made for `item`s (a string that outlives the graph: "pixel", "voxel"). */
GLuint cgp_reads_counter(void *state);
void cgp_reads_begin(GLuint counter);
void cgp_reads_end(fg_pass *pass, GLuint counter, const char *item);

/* A single-level 2D texture. */
fg_resource_desc cgp_image_2d(GLenum format, int width, int height);
/* A single-level 2D texture of `format` the size of `like` (a G-buffer input, say), or of
 * the frame's output image when `like` is NULL (an absent input, while compiling). */
fg_resource_desc cgp_image_like(const fg_pass *pass, const fg_resource_desc *like, GLenum format);
/* A buffer of `bytes`. */
fg_resource_desc cgp_buffer_desc(size_t bytes);
/* Mip levels of a 3D lightmap of width x height x depth voxels: level 0 and every level at which
 * all three sides still halve exactly, so that each voxel of a level is 2 x 2 x 2 voxels of the one
 * below (a cube of 2^n: n + 1 levels, the full chain; a box such as 128 x 32 x 80: 5). */
int cgp_volume_levels(int width, int height, int depth);

/* The last step of the declare of a pass that filters its input `name` (`in`) down the input's own
 * mip chain (mip2d, mip3d): with two levels or more, the output of the same name, which the graph
 * makes an update of the input's resource in place; with one, nothing to do, `single_level`
 * saying why. */
void cgp_declare_in_place_chain(fg_declare *decl, const char *name, const fg_resource_desc *in,
                                const char *single_level);

/* Binds the texture of the optional input `slot` at texture `unit`, or, where it is absent,
 * `stand_in` (a texture the pass has, so that the unit holds something valid that the shader
 * is told not to read). Returns whether the input is present. */
bool cgp_bind_optional(const fg_pass *pass, GLuint unit, fg_slot slot, GLuint stand_in);

/* glDispatchCompute over width x height invocations in groups of 8 x 8 (local_size 8 x 8). */
void cgp_dispatch_2d(int width, int height);
/* cgp_dispatch_2d over the size of the pass's image `slot` (the output it writes a texel an invocation). */
void cgp_dispatch_over(const fg_pass *pass, fg_slot slot);
/* What a compute pass leaves behind it: image units 0 .. image_units - 1 and the `storage_count`
 * shader storage binding points `storage` unbound, no program in use; so that no later pass finds
 * this one's textures and buffers bound where it binds nothing of its own. */
void cgp_compute_end(int image_units, int storage_count, const GLuint *storage);

/* Binds the framebuffer `fbo` for a depth-tested draw over width x height: the viewport, the
 * depth test LESS with depth writes, no face culling (a scene's faces are drawn from both
 * sides; a pass that keeps back faces out says so in its shader). gbuffer, shadow_map and
 * heightmap_raster draw the scene this way. */
void cgp_depth_draw_begin(GLuint fbo, int width, int height);
/* After such a draw: the depth test off, the default framebuffer bound. */
void cgp_depth_draw_end(void);

#endif
