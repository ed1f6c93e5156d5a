/* cg/gpu_scene.h: a cg_scene uploaded to GL buffers and textures, and the one way passes draw it.
 *
 * Declares: cg_gpu_scene, cg_gpu_scene_upload, cg_gpu_scene_destroy, cg_gpu_scene_draw,
 *           cg_gpu_scene_draw_ranges, cg_gpu_scene_bind_instance, cg_mesh_filter, CG_BINDING_MATERIALS, CG_BINDING_LIGHTS,
 *           cg_gpu_scene_bind_lights, cg_gpu_scene_update_lights, cg_gpu_scene_update_meshes,
 *           CG_GPU_VERTEX_FLOATS,
 *           CG_SCENE_UNIT_*, CG_GPU_MATERIAL_DOUBLE_SIDED.
 *
 * Shader interface (shaders/common/scene.glsl): vertex attributes 0 = position,
 * 1 = normal, 2 = texcoord, 3 = tangent (vec4, glTF TANGENT; all zero where the mesh has
 * none, and the shaders then skip normal mapping); uniform location 0 = mat4 model, 1 = mat3
 * normal matrix, 2 = int material index; SSBO binding 0 = materials (struct CgMaterial in
 * scene.glsl: every field of cg_material the shaders need); texture units CG_SCENE_UNIT_*
 * (a 1x1 white texture where the material has none: the factors alone). A draw sets the front
 * face by the sign of the instance's determinant (glTF 3.7.4) and leaves GL_CCW after it.
 * Every program drawn with cg_gpu_scene_draw includes common/scene.glsl, which declares
 * all three uniforms; cg_gpu_scene_draw sets those the program keeps active.
 *
 * Lights (shaders/common/lights.glsl): SSBO binding 1 = a uvec4 header (x = light count)
 * followed by a std430 array of struct CgLight, one per cg_scene light in scene order,
 * so every pass that lights the scene binds the very same data. Passes number their own
 * bindings (shadow maps, lightmaps) in shaders/common/blocks.h, which repeats these two.
 */
#ifndef CG_GPU_SCENE_H
#define CG_GPU_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <glad/gl.h>

#include "cg/error.h"
#include "cg/scene.h"

/* SSBO bindings; shaders/common/blocks.h has the same (a C file seeing both checks it). */
#define CG_BINDING_MATERIALS 0
#define CG_BINDING_LIGHTS 1

/* Texture units of a material's textures (scene.glsl repeats them). The four glTF 2.0 textures
 * beyond base colour and emission sit at 24..27, clear of the units passes number for their own
 * inputs (0..20 today: blocks.h's CG_UNIT_*, a shadow map at 2), since a draw binds them after the
 * pass bound its own. GL 4.5 guarantees 80 combined units. */
#define CG_SCENE_UNIT_BASE_COLOR 0
#define CG_SCENE_UNIT_EMISSIVE 1
#define CG_SCENE_UNIT_METALLIC_ROUGHNESS 24
#define CG_SCENE_UNIT_NORMAL 25
#define CG_SCENE_UNIT_OCCLUSION 26
#define CG_SCENE_UNIT_TRANSMISSION 27

/* Floats per vertex in cg_gpu_mesh.vertex_buffer: position 3, normal 3, texcoord 2, tangent 4. */
#define CG_GPU_VERTEX_FLOATS 12

/* CgMaterial.textures2.w bits. */
#define CG_GPU_MATERIAL_DOUBLE_SIDED 1

typedef enum cg_mesh_filter {
    CG_MESHES_ALL,
    CG_MESHES_COMPLEX,      /* everything but height fields */
    CG_MESHES_HEIGHTFIELD
} cg_mesh_filter;

typedef struct cg_gpu_mesh {
    GLuint vao;
    GLuint vertex_buffer;   /* interleaved position(3) normal(3) texcoord(2) tangent(4) floats */
    GLuint index_buffer;
    GLsizei index_count;
    cg_mesh_kind kind;
    uint64_t revision;      /* the cg_mesh revision its vertices were uploaded at */
} cg_gpu_mesh;

typedef struct cg_gpu_scene {
    const cg_scene *scene;  /* not owned */
    cg_gpu_mesh *meshes;    /* one per cg_scene mesh */
    GLuint material_buffer; /* SSBO, std430 array of struct cg_gpu_material in scene.glsl */
    GLuint *textures;       /* one per cg_scene texture */
    GLuint white_texture;
    GLuint light_buffer;    /* SSBO, header + std430 array of struct CgLight in lights.glsl */
    size_t bytes;           /* GPU memory held by the buffers and textures */
    /* Unique to this upload within the process (never 0): a pass that keeps what it drew
     * across frames compares it to see that the meshes, materials or textures were uploaded
     * again (they may have changed in place), which no pointer can tell. */
    uint64_t generation;
} cg_gpu_scene;

bool cg_gpu_scene_upload(const cg_scene *scene, cg_gpu_scene *out, cg_error *err);
/* Uploads again the vertices of every mesh whose cg_mesh.revision is not the one uploaded (a
 * skin posed it: cg_scene_changes.meshes_deformed) and, when there was one, gives the upload a
 * new `generation`, so that a pass keeping what it drew (voxelize, heightmap_raster) rebuilds
 * it whole, its sorted chunks of a large mesh included. *updated (may be NULL): how many. */
bool cg_gpu_scene_update_meshes(cg_gpu_scene *gpu, int *updated, cg_error *err);
void cg_gpu_scene_destroy(cg_gpu_scene *gpu);

/* Draws every instance whose mesh passes `filter` with the bound program: sets the
 * model and normal matrices and material index uniforms, binds the material SSBO and
 * textures. Returns the number of triangles drawn. The matrices come from gpu->scene's
 * instances at every call, so a scene posed at a new time (cg_scene_evaluate) draws where it
 * is now with nothing uploaded; only its lights need cg_gpu_scene_update_lights. */
size_t cg_gpu_scene_draw(const cg_gpu_scene *gpu, cg_mesh_filter filter);

/* Draws ranges of one instance's triangles as cg_gpu_scene_draw draws the whole (same uniforms,
 * material and vertices): `ranges` runs of counts[r] indices from index firsts[r] (in indices, a
 * multiple of 3) of `index_buffer` (GLuint indices into the mesh's vertices; 0: the mesh's own).
 * For a pass that redraws only the part of a large mesh that lies in some region (voxelize's
 * partial re-voxelization), from an index buffer it sorted by where the triangles lie. Returns
 * the number of triangles drawn. */
size_t cg_gpu_scene_draw_ranges(const cg_gpu_scene *gpu, int instance, GLuint index_buffer, const GLsizei *counts,
                                const GLsizeiptr *firsts, GLsizei ranges);

/* What a draw of `instance` reads beside its vertices, set for the bound program as
 * cg_gpu_scene_draw sets it: the active uniforms 0..2 (model and normal matrices, material
 * index), the materials SSBO, the material textures, the mesh's VAO. For a compute program that
 * reads the mesh's buffers itself (voxelize's voxelizer=compute), so that both see one instance
 * alike. */
void cg_gpu_scene_bind_instance(const cg_gpu_scene *gpu, int instance);

/* Binds the light SSBO at CG_BINDING_LIGHTS. */
void cg_gpu_scene_bind_lights(const cg_gpu_scene *gpu);
/* Re-uploads the lights from gpu->scene (same light count as at upload), e.g. after the
 * demo moved the sun. Fails with CG_ERR_USAGE when the count changed. */
bool cg_gpu_scene_update_lights(cg_gpu_scene *gpu, cg_error *err);

/* True when some mesh passes the filter ("model only what a scene requires"). */
bool cg_gpu_scene_has(const cg_gpu_scene *gpu, cg_mesh_filter filter);

#endif
