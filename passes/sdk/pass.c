/* The pass SDK's registration, state and descriptor helpers (sdk/pass.h). */
#include "sdk/pass.h"

#include <stdlib.h>

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

void *
cgp_state_new(const fg_pass *pass, size_t bytes, cg_error *err)
{
    void *state = calloc(1, bytes);
    if (!state)
        cg_fail(err, CG_ERR_OUT_OF_MEMORY, "pass '%s': out of memory for its state (%zu bytes)",
                fg_pass_name(pass), bytes);
    return state;
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

void
cgp_dispatch_2d(int width, int height)
{
    glDispatchCompute((GLuint)(width + 7) / 8, (GLuint)(height + 7) / 8, 1);
}
