/* The pass registry, the checks on pass descriptors, and the resource format table. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fg_internal.h"

/* ---------------------------------------------------------------- formats */

/* Nominal bytes per texel; image_unit follows the GL 4.5 core spec, table 8.26. */
static const fg_format_info format_table[] = {
    { GL_R8, "R8", 1, true, false },
    { GL_R8_SNORM, "R8_SNORM", 1, true, false },
    { GL_R16, "R16", 2, true, false },
    { GL_R16_SNORM, "R16_SNORM", 2, true, false },
    { GL_RG8, "RG8", 2, true, false },
    { GL_RG8_SNORM, "RG8_SNORM", 2, true, false },
    { GL_RG16, "RG16", 4, true, false },
    { GL_RG16_SNORM, "RG16_SNORM", 4, true, false },
    { GL_RGB8, "RGB8", 3, false, false },
    { GL_RGB16, "RGB16", 6, false, false },
    { GL_RGBA8, "RGBA8", 4, true, false },
    { GL_RGBA8_SNORM, "RGBA8_SNORM", 4, true, false },
    { GL_RGB10_A2, "RGB10_A2", 4, true, false },
    { GL_RGB10_A2UI, "RGB10_A2UI", 4, true, false },
    { GL_RGBA16, "RGBA16", 8, true, false },
    { GL_RGBA16_SNORM, "RGBA16_SNORM", 8, true, false },
    { GL_SRGB8, "SRGB8", 3, false, false },
    { GL_SRGB8_ALPHA8, "SRGB8_ALPHA8", 4, false, false },
    { GL_R16F, "R16F", 2, true, false },
    { GL_RG16F, "RG16F", 4, true, false },
    { GL_RGB16F, "RGB16F", 6, false, false },
    { GL_RGBA16F, "RGBA16F", 8, true, false },
    { GL_R32F, "R32F", 4, true, false },
    { GL_RG32F, "RG32F", 8, true, false },
    { GL_RGB32F, "RGB32F", 12, false, false },
    { GL_RGBA32F, "RGBA32F", 16, true, false },
    { GL_R11F_G11F_B10F, "R11F_G11F_B10F", 4, true, false },
    { GL_RGB9_E5, "RGB9_E5", 4, false, false },
    { GL_R8I, "R8I", 1, true, false },
    { GL_R8UI, "R8UI", 1, true, false },
    { GL_R16I, "R16I", 2, true, false },
    { GL_R16UI, "R16UI", 2, true, false },
    { GL_R32I, "R32I", 4, true, false },
    { GL_R32UI, "R32UI", 4, true, false },
    { GL_RG8I, "RG8I", 2, true, false },
    { GL_RG8UI, "RG8UI", 2, true, false },
    { GL_RG16I, "RG16I", 4, true, false },
    { GL_RG16UI, "RG16UI", 4, true, false },
    { GL_RG32I, "RG32I", 8, true, false },
    { GL_RG32UI, "RG32UI", 8, true, false },
    { GL_RGBA8I, "RGBA8I", 4, true, false },
    { GL_RGBA8UI, "RGBA8UI", 4, true, false },
    { GL_RGBA16I, "RGBA16I", 8, true, false },
    { GL_RGBA16UI, "RGBA16UI", 8, true, false },
    { GL_RGBA32I, "RGBA32I", 16, true, false },
    { GL_RGBA32UI, "RGBA32UI", 16, true, false },
    { GL_DEPTH_COMPONENT16, "DEPTH16", 2, false, true },
    { GL_DEPTH_COMPONENT24, "DEPTH24", 4, false, true },
    { GL_DEPTH_COMPONENT32F, "DEPTH32F", 4, false, true },
    { GL_DEPTH24_STENCIL8, "DEPTH24_STENCIL8", 4, false, true },
    { GL_DEPTH32F_STENCIL8, "DEPTH32F_STENCIL8", 8, false, true },
    { GL_STENCIL_INDEX8, "STENCIL8", 1, false, true },
};

const fg_format_info *
fg_format_find(GLenum format)
{
    for (size_t i = 0; i < sizeof format_table / sizeof format_table[0]; i++)
        if (format_table[i].format == format)
            return &format_table[i];
    return NULL;
}

const char *
fg_format_name(GLenum format, char *buf, size_t size)
{
    const fg_format_info *info = fg_format_find(format);
    if (info)
        return info->name;
    snprintf(buf, size, "0x%04x", (unsigned)format);
    return buf;
}

const char *
fg_kind_name(fg_resource_kind kind)
{
    switch (kind) {
    case FG_TEXTURE_2D: return "2d";
    case FG_TEXTURE_3D: return "3d";
    case FG_TEXTURE_2D_ARRAY: return "2d_array";
    case FG_BUFFER: return "buffer";
    }
    return "?";
}

const char *
fg_access_names(unsigned access, char *buf, size_t size)
{
    static const char *const names[] = { "sampled", "image_load", "image_store", "attachment",
                                         "storage", "uniform", "transfer" };
    size_t len = 0;
    buf[0] = '\0';
    for (unsigned bit = 0; bit < sizeof names / sizeof names[0]; bit++) {
        if (!(access & (1u << bit)))
            continue;
        int n = snprintf(buf + len, size - len, "%s%s", len ? "|" : "", names[bit]);
        if (n < 0 || (size_t)n >= size - len)
            break;
        len += (size_t)n;
    }
    if (!len)
        snprintf(buf, size, "none");
    return buf;
}

GLbitfield
fg_barrier_bits_for(unsigned writer, unsigned reader, fg_resource_kind kind)
{
    /* Only image stores and SSBO writes are incoherent (GL 4.5 core, 7.12.2); attachment
     * and transfer writes are ordered with later commands by GL itself and need no barrier. */
    if (!(writer & (FG_ACCESS_IMAGE_STORE | FG_ACCESS_STORAGE)))
        return 0;
    GLbitfield bits = 0;
    if (reader & FG_ACCESS_SAMPLED)
        bits |= GL_TEXTURE_FETCH_BARRIER_BIT;
    if (reader & (FG_ACCESS_IMAGE_LOAD | FG_ACCESS_IMAGE_STORE))
        bits |= GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    if (reader & FG_ACCESS_ATTACHMENT)
        bits |= GL_FRAMEBUFFER_BARRIER_BIT;
    if (reader & FG_ACCESS_STORAGE)
        bits |= GL_SHADER_STORAGE_BARRIER_BIT;
    if (reader & FG_ACCESS_UNIFORM)
        bits |= GL_UNIFORM_BARRIER_BIT;
    if (reader & FG_ACCESS_TRANSFER)
        bits |= kind == FG_BUFFER ? GL_BUFFER_UPDATE_BARRIER_BIT : GL_TEXTURE_UPDATE_BARRIER_BIT;
    return bits;
}

size_t
fg_resource_bytes(const fg_resource_desc *desc)
{
    if (desc->kind == FG_BUFFER)
        return desc->buffer_bytes;
    const fg_format_info *info = fg_format_find(desc->format);
    if (!info || desc->width <= 0 || desc->height <= 0)
        return 0;
    int levels = desc->levels > 0 ? desc->levels : 1;
    size_t depth = desc->depth > 0 ? (size_t)desc->depth : 1;
    size_t total = 0;
    for (int l = 0; l < levels; l++) {
        size_t w = (size_t)desc->width >> l, h = (size_t)desc->height >> l;
        /* A 3D texture halves its depth per level; an array keeps its layer count. */
        size_t d = desc->kind == FG_TEXTURE_3D ? depth >> l : depth;
        total += (w ? w : 1) * (h ? h : 1) * (d ? d : 1) * (size_t)info->bytes;
    }
    return total;
}

int
fg_mip_levels(int width, int height, int depth)
{
    int largest = width > height ? width : height;
    if (depth > largest)
        largest = depth;
    int levels = 1;
    while (largest > 1) {
        largest >>= 1;
        levels++;
    }
    return levels;
}

/* ---------------------------------------------------------------- registry */

fg_registry *
fg_registry_create(void)
{
    return calloc(1, sizeof(fg_registry));
}

bool
fg_registry_add(fg_registry *registry, const fg_pass_type *type, cg_error *err)
{
    if (!type)
        return cg_fail(err, CG_ERR_PLUGIN_LOAD, "pass type descriptor is NULL");
    const char *name = type->name ? type->name : "(unnamed)";
    if (type->abi_version != FG_ABI_VERSION)
        return cg_fail(err, CG_ERR_PLUGIN_ABI,
                       "pass type '%s' was built for frame-graph ABI %u; this conegraph has ABI %u "
                       "(rebuild the pass against this version's cg/fg.h)",
                       name, type->abi_version, FG_ABI_VERSION);
    if (!fg_is_identifier(type->name))
        return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                       "pass type name '%s' is not an identifier (letters, digits, '_' and '-')", name);
    if (fg_registry_find(registry, type->name))
        return cg_fail(err, CG_ERR_PLUGIN_LOAD, "pass type '%s' is already registered", name);
    if (!type->doc || !*type->doc)
        return cg_fail(err, CG_ERR_PLUGIN_LOAD, "pass type '%s' has no doc", name);
    if (!type->declare || !type->execute)
        return cg_fail(err, CG_ERR_PLUGIN_LOAD, "pass type '%s' lacks its %s callback", name,
                       type->declare ? "execute" : "declare");
    if (type->param_count < 0 || (type->param_count > 0 && !type->params))
        return cg_fail(err, CG_ERR_PLUGIN_LOAD, "pass type '%s': %d parameters but no table",
                       name, type->param_count);
    if (!fg_param_table_check(type, err))
        return false;
    if (!fg_grow((void **)&registry->types, &registry->cap, registry->count + 1, sizeof *registry->types))
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory registering pass type '%s'", name);
    registry->types[registry->count++] = type;
    return true;
}

const fg_pass_type *
fg_registry_find(const fg_registry *registry, const char *name)
{
    for (int i = 0; i < registry->count; i++)
        if (!strcmp(registry->types[i]->name, name))
            return registry->types[i];
    return NULL;
}

int
fg_registry_count(const fg_registry *registry)
{
    return registry->count;
}

const fg_pass_type *
fg_registry_at(const fg_registry *registry, int index)
{
    return index >= 0 && index < registry->count ? registry->types[index] : NULL;
}
