/* cg_gpu_scene: a cg_scene in GL buffers and textures (DSA), and the one way passes draw it.
 * The std430 layouts written here are mirrored by shaders/common/scene.glsl (CgMaterial)
 * and shaders/common/lights.glsl (CgLight); change both together. */
#include "cg/gpu_scene.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>

#include "cg/log.h"

/* std430 struct CgMaterial in scene.glsl: twenty vec4-sized members, 320 bytes. */
typedef struct gpu_material {
    float base_color[4];
    float emissive[4];      /* rgb = emissive factor x emissive strength, w = alpha cutoff */
    int32_t textures[4];    /* base colour, emissive, metallicRoughness, normal (-1 none) */
    int32_t textures2[4];   /* x = occlusion, y = transmission (-1 none), z = alpha mode,
                             * w = flags (CG_GPU_MATERIAL_DOUBLE_SIDED) */
    float pbr[4];           /* x = metallic, y = roughness, z = normal scale, w = occlusion strength */
    float specular[4];      /* rgb = KHR_materials_specular colour, a = specular factor */
    float volume[4];        /* x = ior, y = transmission, z = thickness (mesh units), w = 0 */
    float attenuation[4];   /* rgb = sigma = -ln(attenuation colour) / distance (1/m), w = 0 */
    float uv[CG_TEX_COUNT][2][4]; /* KHR_texture_transform: (m0, m1, m2, m3), (m4, m5, 0, 0) */
} gpu_material;

/* std430 struct CgLight in lights.glsl. */
typedef struct gpu_light {
    float position_type[4];     /* xyz world position, w = type (0 directional, 1 point, 2 spot) */
    float direction_range[4];   /* xyz unit direction the light travels, w = range (0 = infinite) */
    float radiance[4];          /* rgb = color x intensity, w unused */
    float cone[4];              /* x = angle scale, y = angle offset (KHR_lights_punctual) */
} gpu_light;

_Static_assert(sizeof(gpu_material) == 320, "CgMaterial is 320 bytes in std430");
_Static_assert(CG_TEX_COUNT == 6, "scene.glsl reads six uv transforms");
_Static_assert(sizeof(gpu_light) == 64, "CgLight is 64 bytes in std430");

#define LIGHT_HEADER_BYTES 16

static size_t
texture_bytes(int width, int height, int levels)
{
    size_t bytes = 0;
    for (int l = 0; l < levels; l++) {
        bytes += (size_t)width * (size_t)height * 4u;
        width = width > 1 ? width / 2 : 1;
        height = height > 1 ? height / 2 : 1;
    }
    return bytes;
}

static int
mip_levels(int width, int height)
{
    int levels = 1;
    int size = width > height ? width : height;
    while (size > 1) {
        size /= 2;
        levels++;
    }
    return levels;
}

static bool
upload_mesh(const cg_mesh *mesh, cg_gpu_mesh *out, size_t *bytes, cg_error *err)
{
    size_t vertex_bytes = (size_t)mesh->vertex_count * CG_GPU_VERTEX_FLOATS * sizeof(float);
    float *interleaved = malloc(vertex_bytes ? vertex_bytes : 1);
    if (!interleaved)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "gpu scene: mesh '%s': %zu bytes of vertices",
                       mesh->name, vertex_bytes);
    for (uint32_t v = 0; v < mesh->vertex_count; v++) {
        float *dst = interleaved + (size_t)v * CG_GPU_VERTEX_FLOATS;
        memcpy(dst, mesh->positions + (size_t)v * 3u, 3 * sizeof(float));
        memcpy(dst + 3, mesh->normals + (size_t)v * 3u, 3 * sizeof(float));
        if (mesh->texcoords)
            memcpy(dst + 6, mesh->texcoords + (size_t)v * 2u, 2 * sizeof(float));
        else
            dst[6] = dst[7] = 0.0f;
        /* A zero tangent tells the shaders that the mesh has none: no normal mapping there. */
        if (mesh->tangents)
            memcpy(dst + 8, mesh->tangents + (size_t)v * 4u, 4 * sizeof(float));
        else
            dst[8] = dst[9] = dst[10] = dst[11] = 0.0f;
    }
    size_t index_bytes = (size_t)mesh->index_count * sizeof(uint32_t);

    glCreateBuffers(1, &out->vertex_buffer);
    glNamedBufferStorage(out->vertex_buffer, (GLsizeiptr)(vertex_bytes ? vertex_bytes : 32),
                         vertex_bytes ? interleaved : NULL, 0);
    free(interleaved);
    glCreateBuffers(1, &out->index_buffer);
    glNamedBufferStorage(out->index_buffer, (GLsizeiptr)(index_bytes ? index_bytes : 4),
                         index_bytes ? mesh->indices : NULL, 0);

    glCreateVertexArrays(1, &out->vao);
    glVertexArrayVertexBuffer(out->vao, 0, out->vertex_buffer, 0, CG_GPU_VERTEX_FLOATS * sizeof(float));
    glVertexArrayElementBuffer(out->vao, out->index_buffer);
    static const struct { GLuint location; GLint size; GLuint offset; } attribs[] = {
        { 0, 3, 0 }, { 1, 3, 3 * sizeof(float) }, { 2, 2, 6 * sizeof(float) }, { 3, 4, 8 * sizeof(float) },
    };
    for (size_t i = 0; i < sizeof attribs / sizeof attribs[0]; i++) {
        glEnableVertexArrayAttrib(out->vao, attribs[i].location);
        glVertexArrayAttribFormat(out->vao, attribs[i].location, attribs[i].size, GL_FLOAT,
                                  GL_FALSE, attribs[i].offset);
        glVertexArrayAttribBinding(out->vao, attribs[i].location, 0);
    }
    out->index_count = (GLsizei)mesh->index_count;
    out->kind = mesh->kind;
    *bytes += vertex_bytes + index_bytes;
    return true;
}

static GLuint
upload_texture(const cg_texture *tex, size_t *bytes)
{
    int levels = mip_levels(tex->width, tex->height);
    GLuint name;
    glCreateTextures(GL_TEXTURE_2D, 1, &name);
    glTextureStorage2D(name, levels, tex->srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, tex->width, tex->height);
    glTextureSubImage2D(name, 0, 0, 0, tex->width, tex->height, GL_RGBA, GL_UNSIGNED_BYTE, tex->rgba);
    glGenerateTextureMipmap(name);
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(name, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(name, GL_TEXTURE_WRAP_T, GL_REPEAT);
    *bytes += texture_bytes(tex->width, tex->height, levels);
    return name;
}

static void
pack_light(const cg_light *light, gpu_light *out)
{
    memset(out, 0, sizeof *out);
    memcpy(out->position_type, light->position, sizeof light->position);
    out->position_type[3] = (float)light->type;
    /* Normalised here so that shaders can trust it (the path tracer normalises too). */
    float len = sqrtf(light->direction[0] * light->direction[0] + light->direction[1] * light->direction[1] +
                      light->direction[2] * light->direction[2]);
    for (int c = 0; c < 3 && len > 0.0f; c++)
        out->direction_range[c] = light->direction[c] / len;
    out->direction_range[3] = light->range;
    for (int c = 0; c < 3; c++)
        out->radiance[c] = light->color[c] * light->intensity;
    if (light->type == CG_LIGHT_SPOT) {
        /* KHR_lights_punctual, "Inner and Outer Cone Angles": the smooth falloff is
         * saturate(cd * scale + offset)^2 with cd the cosine to the spot axis. */
        float cos_outer = cosf(light->outer_cone_angle);
        float cos_inner = cosf(light->inner_cone_angle);
        float scale = 1.0f / fmaxf(0.001f, cos_inner - cos_outer);
        out->cone[0] = scale;
        out->cone[1] = -cos_outer * scale;
    }
}

static bool
write_lights(cg_gpu_scene *gpu, bool create, cg_error *err)
{
    const cg_scene *scene = gpu->scene;
    size_t bytes = LIGHT_HEADER_BYTES + (size_t)scene->light_count * sizeof(gpu_light);
    unsigned char *data = calloc(1, bytes);
    if (!data)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "gpu scene: %zu bytes of lights", bytes);
    uint32_t count = (uint32_t)scene->light_count;
    memcpy(data, &count, sizeof count);
    for (int i = 0; i < scene->light_count; i++)
        pack_light(&scene->lights[i], (gpu_light *)(data + LIGHT_HEADER_BYTES) + i);
    if (create) {
        glCreateBuffers(1, &gpu->light_buffer);
        glNamedBufferStorage(gpu->light_buffer, (GLsizeiptr)bytes, data, GL_DYNAMIC_STORAGE_BIT);
        gpu->bytes += bytes;
    } else {
        glNamedBufferSubData(gpu->light_buffer, 0, (GLsizeiptr)bytes, data);
    }
    free(data);
    return true;
}

/* A texture index as the shaders test it: -1 where the scene has no such texture. */
static int32_t
texture_index(const cg_scene *scene, int index)
{
    return index >= 0 && index < scene->texture_count ? index : -1;
}

static void
pack_material(const cg_scene *scene, const cg_material *m, gpu_material *out)
{
    memset(out, 0, sizeof *out);
    memcpy(out->base_color, m->base_color, sizeof m->base_color);
    for (int c = 0; c < 3; c++)
        out->emissive[c] = m->emissive[c] * m->emissive_strength;
    out->emissive[3] = m->alpha_cutoff;
    out->textures[0] = texture_index(scene, m->base_color_texture);
    out->textures[1] = texture_index(scene, m->emissive_texture);
    out->textures[2] = texture_index(scene, m->metallic_roughness_texture);
    out->textures[3] = texture_index(scene, m->normal_texture);
    out->textures2[0] = texture_index(scene, m->occlusion_texture);
    out->textures2[1] = texture_index(scene, m->transmission_texture);
    out->textures2[2] = (int32_t)m->alpha_mode;
    out->textures2[3] = m->double_sided ? CG_GPU_MATERIAL_DOUBLE_SIDED : 0;
    out->pbr[0] = m->metallic;
    out->pbr[1] = m->roughness;
    out->pbr[2] = m->normal_scale;
    out->pbr[3] = m->occlusion_strength;
    memcpy(out->specular, m->specular_color, sizeof m->specular_color);
    out->specular[3] = m->specular;
    out->volume[0] = m->ior;
    out->volume[1] = m->transmission;
    out->volume[2] = m->thickness;
    /* KHR_materials_volume: attenuationDistance is in world units (metres), so sigma is per metre
     * whatever the instance's scale; an infinite distance attenuates nothing. As cg_bsdf_from_material. */
    for (int c = 0; c < 3; c++)
        if (isfinite(m->attenuation_distance) && m->attenuation_distance > 0.0f)
            out->attenuation[c] = -logf(fmaxf(m->attenuation_color[c], 1e-6f)) / m->attenuation_distance;
    for (int t = 0; t < CG_TEX_COUNT; t++) {
        memcpy(out->uv[t][0], m->uv[t].m, 4 * sizeof(float));
        out->uv[t][1][0] = m->uv[t].m[4];
        out->uv[t][1][1] = m->uv[t].m[5];
    }
}

/* What a scene without materials draws with: white and Lambertian, both sides (cg_material_default). */
static cg_material
white_lambertian(void)
{
    cg_material m = {
        .base_color = { 1, 1, 1, 1 }, .base_color_texture = -1, .emissive_texture = -1,
        .emissive_strength = 1, .roughness = 1, .metallic_roughness_texture = -1,
        .normal_texture = -1, .normal_scale = 1, .occlusion_texture = -1, .occlusion_strength = 1,
        .alpha_mode = CG_ALPHA_OPAQUE, .alpha_cutoff = 0.5f, .double_sided = true, .ior = 1.5f,
        .specular = 0, .specular_color = { 1, 1, 1 }, .transmission_texture = -1,
        .attenuation_distance = INFINITY, .attenuation_color = { 1, 1, 1 },
    };
    for (int t = 0; t < CG_TEX_COUNT; t++)
        m.uv[t] = (cg_uv_transform){ { 1, 0, 0, 1, 0, 0 } };
    return m;
}

/* Uploads run on the thread whose GL context is current; an atomic keeps the counter unique
 * should two threads with two contexts upload at once. */
static atomic_uint_fast64_t uploads;

bool
cg_gpu_scene_upload(const cg_scene *scene, cg_gpu_scene *out, cg_error *err)
{
    memset(out, 0, sizeof *out);
    out->scene = scene;
    out->generation = (uint64_t)atomic_fetch_add(&uploads, 1) + 1;
    if (scene->mesh_count > 0) {
        out->meshes = calloc((size_t)scene->mesh_count, sizeof *out->meshes);
        if (!out->meshes)
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "gpu scene: %d meshes", scene->mesh_count);
    }
    for (int i = 0; i < scene->mesh_count; i++)
        if (!upload_mesh(&scene->meshes[i], &out->meshes[i], &out->bytes, err)) {
            cg_gpu_scene_destroy(out);
            return false;
        } else {
            out->meshes[i].revision = scene->meshes[i].revision;
        }

    int material_count = scene->material_count > 0 ? scene->material_count : 1;
    gpu_material *materials = calloc((size_t)material_count, sizeof *materials);
    if (!materials) {
        cg_gpu_scene_destroy(out);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "gpu scene: %d materials", material_count);
    }
    if (scene->material_count > 0) {
        for (int i = 0; i < scene->material_count; i++)
            pack_material(scene, &scene->materials[i], &materials[i]);
    } else {
        /* A scene without materials still draws: a white Lambertian default. */
        cg_material white = white_lambertian();
        pack_material(scene, &white, &materials[0]);
    }
    glCreateBuffers(1, &out->material_buffer);
    glNamedBufferStorage(out->material_buffer, (GLsizeiptr)(material_count * sizeof *materials),
                         materials, 0);
    out->bytes += (size_t)material_count * sizeof *materials;
    free(materials);

    if (scene->texture_count > 0) {
        out->textures = calloc((size_t)scene->texture_count, sizeof *out->textures);
        if (!out->textures) {
            cg_gpu_scene_destroy(out);
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "gpu scene: %d textures", scene->texture_count);
        }
    }
    for (int i = 0; i < scene->texture_count; i++)
        out->textures[i] = upload_texture(&scene->textures[i], &out->bytes);

    static const uint8_t white[4] = { 255, 255, 255, 255 };
    glCreateTextures(GL_TEXTURE_2D, 1, &out->white_texture);
    glTextureStorage2D(out->white_texture, 1, GL_RGBA8, 1, 1);
    glTextureSubImage2D(out->white_texture, 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, white);
    out->bytes += 4;

    if (!write_lights(out, true, err)) {
        cg_gpu_scene_destroy(out);
        return false;
    }
    cg_log_debug("gpu scene '%s': %d meshes, %d textures, %d lights, %zu bytes", scene->name,
                 scene->mesh_count, scene->texture_count, scene->light_count, out->bytes);
    return true;
}

bool
cg_gpu_scene_update_meshes(cg_gpu_scene *gpu, int *updated, cg_error *err)
{
    const cg_scene *scene = gpu->scene;
    int n = 0;
    for (int i = 0; i < scene->mesh_count; i++) {
        cg_gpu_mesh *m = &gpu->meshes[i];
        if (m->revision == scene->meshes[i].revision)
            continue;
        /* Immutable storage (upload_mesh): new buffers, the old ones deleted once these exist.
         * Same sizes, so gpu->bytes stands. */
        cg_gpu_mesh fresh = { 0 };
        size_t bytes = 0;
        if (!upload_mesh(&scene->meshes[i], &fresh, &bytes, err))
            return false;
        glDeleteVertexArrays(1, &m->vao);
        glDeleteBuffers(1, &m->vertex_buffer);
        glDeleteBuffers(1, &m->index_buffer);
        *m = fresh;
        m->revision = scene->meshes[i].revision;
        n++;
    }
    if (n > 0)
        gpu->generation = (uint64_t)atomic_fetch_add(&uploads, 1) + 1;
    if (updated)
        *updated = n;
    return true;
}

void
cg_gpu_scene_destroy(cg_gpu_scene *gpu)
{
    if (!gpu)
        return;
    if (gpu->meshes && gpu->scene) {
        for (int i = 0; i < gpu->scene->mesh_count; i++) {
            glDeleteVertexArrays(1, &gpu->meshes[i].vao);
            glDeleteBuffers(1, &gpu->meshes[i].vertex_buffer);
            glDeleteBuffers(1, &gpu->meshes[i].index_buffer);
        }
    }
    if (gpu->textures && gpu->scene)
        glDeleteTextures(gpu->scene->texture_count, gpu->textures);
    glDeleteBuffers(1, &gpu->material_buffer);
    glDeleteBuffers(1, &gpu->light_buffer);
    glDeleteTextures(1, &gpu->white_texture);
    free(gpu->meshes);
    free(gpu->textures);
    memset(gpu, 0, sizeof *gpu);
}

static bool
mesh_passes(cg_mesh_kind kind, cg_mesh_filter filter)
{
    switch (filter) {
    case CG_MESHES_ALL: return true;
    case CG_MESHES_COMPLEX: return kind == CG_MESH_COMPLEX;
    case CG_MESHES_HEIGHTFIELD: return kind == CG_MESH_HEIGHTFIELD;
    }
    return false;
}

static GLuint
material_texture(const cg_gpu_scene *gpu, int index)
{
    if (index < 0 || index >= gpu->scene->texture_count)
        return gpu->white_texture;
    return gpu->textures[index];
}

/* Which of the scene uniform locations 0..2 the bound program keeps. A stage that does not
 * read one (a depth-only shader and the normal matrix) lets the linker drop it, and the GL
 * spec leaves glUniform on such a location to the driver (Mesa ignores it, others may
 * raise GL_INVALID_OPERATION), so only the active ones are set. */
static void
active_scene_uniforms(bool active[3])
{
    GLint program = 0, count = 0;
    active[0] = active[1] = active[2] = false;
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    if (!program)
        return;
    glGetProgramInterfaceiv((GLuint)program, GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
    for (GLint i = 0; i < count; i++) {
        const GLenum prop = GL_LOCATION;
        GLint location = -1;
        glGetProgramResourceiv((GLuint)program, GL_UNIFORM, (GLuint)i, 1, &prop, 1, NULL, &location);
        if (location >= 0 && location < 3)
            active[location] = true;
    }
}

/* Sets what a draw of instance `inst` reads beside its vertices: the matrices and material
 * uniforms the bound program keeps (`active`), the material textures; binds its mesh's VAO. */
static void
bind_instance(const cg_gpu_scene *gpu, const cg_instance *inst, const bool active[3])
{
    const cg_scene *scene = gpu->scene;
    mat4 model;
    memcpy(model, inst->world, sizeof model);
    /* Normals transform by the inverse transpose of the linear part. */
    mat3 linear, normal_matrix;
    glm_mat4_pick3(model, linear);
    glm_mat3_inv(linear, normal_matrix);
    glm_mat3_transpose(normal_matrix);
    int material = scene->meshes[inst->mesh].material;
    if (material < 0 || material >= scene->material_count)
        material = 0;
    if (active[0])
        glUniformMatrix4fv(0, 1, GL_FALSE, (const float *)model);
    if (active[1])
        glUniformMatrix3fv(1, 1, GL_FALSE, (const float *)normal_matrix);
    if (active[2])
        glUniform1i(2, material);
    const cg_material *m = scene->material_count > 0 ? &scene->materials[material] : NULL;
    glBindTextureUnit(CG_SCENE_UNIT_BASE_COLOR, material_texture(gpu, m ? m->base_color_texture : -1));
    glBindTextureUnit(CG_SCENE_UNIT_EMISSIVE, material_texture(gpu, m ? m->emissive_texture : -1));
    glBindTextureUnit(CG_SCENE_UNIT_METALLIC_ROUGHNESS,
                      material_texture(gpu, m ? m->metallic_roughness_texture : -1));
    glBindTextureUnit(CG_SCENE_UNIT_NORMAL, material_texture(gpu, m ? m->normal_texture : -1));
    glBindTextureUnit(CG_SCENE_UNIT_OCCLUSION, material_texture(gpu, m ? m->occlusion_texture : -1));
    glBindTextureUnit(CG_SCENE_UNIT_TRANSMISSION, material_texture(gpu, m ? m->transmission_texture : -1));
    /* glTF 2.0, 3.7.4 (meshes): a world matrix with a negative determinant mirrors the mesh, and
     * its triangles' winding must be reversed for the front face to stay the front (single-sided
     * materials cull by gl_FrontFacing, gbuffer.frag). */
    glFrontFace(glm_mat3_det(linear) < 0.0f ? GL_CW : GL_CCW);
    glBindVertexArray(gpu->meshes[inst->mesh].vao);
}

void
cg_gpu_scene_bind_instance(const cg_gpu_scene *gpu, int instance)
{
    if (instance < 0 || instance >= gpu->scene->instance_count)
        return;
    bool active[3];
    active_scene_uniforms(active);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_MATERIALS, gpu->material_buffer);
    bind_instance(gpu, &gpu->scene->instances[instance], active);
}

size_t
cg_gpu_scene_draw(const cg_gpu_scene *gpu, cg_mesh_filter filter)
{
    const cg_scene *scene = gpu->scene;
    size_t triangles = 0;
    bool active[3];
    active_scene_uniforms(active);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_MATERIALS, gpu->material_buffer);
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_instance *inst = &scene->instances[i];
        const cg_gpu_mesh *mesh = &gpu->meshes[inst->mesh];
        if (!mesh_passes(mesh->kind, filter) || mesh->index_count == 0)
            continue;
        bind_instance(gpu, inst, active);
        glDrawElements(GL_TRIANGLES, mesh->index_count, GL_UNSIGNED_INT, NULL);
        triangles += (size_t)mesh->index_count / 3u;
    }
    glBindVertexArray(0);
    glFrontFace(GL_CCW);
    return triangles;
}

size_t
cg_gpu_scene_draw_ranges(const cg_gpu_scene *gpu, int instance, GLuint index_buffer, const GLsizei *counts,
                         const GLsizeiptr *firsts, GLsizei ranges)
{
    const cg_scene *scene = gpu->scene;
    if (instance < 0 || instance >= scene->instance_count || ranges <= 0)
        return 0;
    const cg_instance *inst = &scene->instances[instance];
    const cg_gpu_mesh *mesh = &gpu->meshes[inst->mesh];
    if (mesh->index_count == 0)
        return 0;
    bool active[3];
    active_scene_uniforms(active);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_MATERIALS, gpu->material_buffer);
    bind_instance(gpu, inst, active);
    /* The caller's element buffer stands in for the mesh's own for this draw only: the VAO is
     * shared by every pass, so it gets its own back before anything else draws with it. */
    if (index_buffer)
        glVertexArrayElementBuffer(mesh->vao, index_buffer);
    size_t triangles = 0;
    const void *offsets[64];
    for (GLsizei done = 0; done < ranges;) {
        GLsizei batch = ranges - done < 64 ? ranges - done : 64;
        for (GLsizei r = 0; r < batch; r++) {
            offsets[r] = (const void *)(firsts[done + r] * (GLsizeiptr)sizeof(GLuint));
            triangles += (size_t)counts[done + r] / 3u;
        }
        glMultiDrawElements(GL_TRIANGLES, counts + done, GL_UNSIGNED_INT, offsets, batch);
        done += batch;
    }
    if (index_buffer)
        glVertexArrayElementBuffer(mesh->vao, mesh->index_buffer);
    glBindVertexArray(0);
    glFrontFace(GL_CCW);
    return triangles;
}

bool
cg_gpu_scene_has(const cg_gpu_scene *gpu, cg_mesh_filter filter)
{
    for (int i = 0; i < gpu->scene->instance_count; i++) {
        const cg_gpu_mesh *mesh = &gpu->meshes[gpu->scene->instances[i].mesh];
        if (mesh_passes(mesh->kind, filter) && mesh->index_count > 0)
            return true;
    }
    return false;
}

void
cg_gpu_scene_bind_lights(const cg_gpu_scene *gpu)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_LIGHTS, gpu->light_buffer);
}

bool
cg_gpu_scene_update_lights(cg_gpu_scene *gpu, cg_error *err)
{
    GLint64 size = 0;
    glGetNamedBufferParameteri64v(gpu->light_buffer, GL_BUFFER_SIZE, &size);
    size_t expected = LIGHT_HEADER_BYTES + (size_t)gpu->scene->light_count * sizeof(gpu_light);
    if ((size_t)size != expected)
        return cg_fail(err, CG_ERR_USAGE,
                       "gpu scene: light count changed since upload (buffer %lld bytes, need %zu)",
                       (long long)size, expected);
    return write_lights(gpu, false, err);
}
