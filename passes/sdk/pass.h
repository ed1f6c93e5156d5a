/* sdk/pass.h (pass SDK): what every pass needs beside cg/fg.h: its registration, its state,
 * the descriptors of its usual outputs and its compute dispatch.
 *
 * Declares: CGP_PARAMS, CGP_NO_PARAMS, CGP_REGISTER_PASS, CGP_PLUGIN, cgp_register_passes,
 *           cgp_state_new, cgp_image_2d, cgp_image_like, cgp_buffer_desc, cgp_dispatch_2d.
 *
 * A pass type is a static fg_pass_type; a built-in pass registers it with
 *     CGP_REGISTER_PASS(cone_gather, cone_gather_type)
 * which defines cg_pass_register_cone_gather(registry, host_abi, err), the function that
 * passes/builtin.c (generated) calls, with the very signature of a plugin's entry point. A
 * plugin (a shared object loaded with --plugin) writes instead
 *     CGP_PLUGIN(&fill_type, &other_type)
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

/* Registers `count` pass types. Each type's abi_version is the FG_ABI_VERSION of the headers
 * it was compiled against; it must equal host_abi (CG_ERR_PLUGIN_ABI otherwise, naming the
 * type and both versions). This function reads only abi_version and name before that check,
 * the first two members of fg_pass_type, which every ABI keeps, so that it may refuse a
 * plugin of another ABI safely. Then fg_registry_add() checks the rest of each descriptor. */
bool cgp_register_passes(fg_registry *registry, uint32_t host_abi, const fg_pass_type *const *types, int count,
                         cg_error *err);

#define CGP_REGISTER_PASS(name, type)                                                        \
    bool cg_pass_register_##name(fg_registry *registry, uint32_t host_abi, cg_error *err);   \
    bool cg_pass_register_##name(fg_registry *registry, uint32_t host_abi, cg_error *err)    \
    {                                                                                        \
        static const fg_pass_type *const types[] = {&(type)};                                \
        return cgp_register_passes(registry, host_abi, types, 1, err);                       \
    }

/* The plugin entry point FG_PLUGIN_ENTRY for the pass types given as pointers. */
#define CGP_PLUGIN(...)                                                                      \
    bool conegraph_plugin_register(fg_registry *registry, uint32_t host_abi, cg_error *err); \
    bool conegraph_plugin_register(fg_registry *registry, uint32_t host_abi, cg_error *err)  \
    {                                                                                        \
        static const fg_pass_type *const types[] = {__VA_ARGS__};                            \
        return cgp_register_passes(registry, host_abi, types,                                \
                                   (int)(sizeof types / sizeof types[0]), err);              \
    }

/* A zeroed state of `bytes` for prepare(); NULL with CG_ERR_OUT_OF_MEMORY naming the pass. */
void *cgp_state_new(const fg_pass *pass, size_t bytes, cg_error *err);

/* A single-level 2D texture. */
fg_resource_desc cgp_image_2d(GLenum format, int width, int height);
/* A single-level 2D texture of `format` the size of `like` (a G-buffer input, say), or of
 * the frame's output image when `like` is NULL (an absent input, while compiling). */
fg_resource_desc cgp_image_like(const fg_pass *pass, const fg_resource_desc *like, GLenum format);
/* A buffer of `bytes`. */
fg_resource_desc cgp_buffer_desc(size_t bytes);

/* glDispatchCompute over width x height invocations in groups of 8 x 8 (local_size 8 x 8). */
void cgp_dispatch_2d(int width, int height);

#endif
