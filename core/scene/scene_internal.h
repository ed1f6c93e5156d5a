/* core/scene/scene_internal.h: what the scene's files share: the builders the loaders call
 * (build.c, animation.c's nodes, animations, skins and morphs), and the loaders scene.c calls
 * (dem.c, builtin/ (one file per scene), gltf_adapter.cpp) and classify.c. The loaders build
 * through build.c and never call scene.c, so that no two files lean on each other (the layers
 * test checks it). Not a public header: passes and apps use cg/scene.h only.
 *
 * Declares: cg_scene_add_material, cg_scene_add_mesh, cg_scene_add_instance,
 *           cg_scene_add_light, cg_scene_add_camera, cg_scene_add_texture,
 *           cg_material_default, cg_material_gltf_default, cg_uv_transform_identity,
 *           cg_mesh_compute_bounds, cg_mesh_generate_normals, cg_mesh_generate_tangents,
 *           CG_HEIGHTFIELD_MIN_NY,
 *           cg_scene_set_kind_source, cg_scene_classify, cg_dem_load, cg_builtin_scene_load,
 *           cg_gltf_load, cg_gltf_check_json, cg_copy_name, cg_node_default,
 *           cg_node_local, cg_scene_add_node, cg_scene_attach, cg_anim_channel_alloc,
 *           cg_anim_channel_components, cg_anim_channel_stride, cg_scene_add_animation,
 *           cg_scene_pose, cg_scene_motion_bounds, cg_scene_add_skin, cg_scene_add_skinned_mesh,
 *           cg_scene_add_morphed_mesh, cg_skinned_mesh_free, cg_morphed_mesh_free.
 */
#ifndef CG_SCENE_INTERNAL_H
#define CG_SCENE_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cg/error.h"
#include "cg/progress.h"
#include "cg/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Copies src into a CG_NAME_MAX buffer, truncating (names are labels, not keys). */
void cg_copy_name(char dst[CG_NAME_MAX], const char *src);

/* Each add_* appends one element (arrays grow by realloc) and returns its index,
 * or -1 with err set (CG_ERR_OUT_OF_MEMORY). The scene takes ownership of the
 * pointers inside *mesh and *texture. */
int cg_scene_add_material(cg_scene *scene, const cg_material *material, cg_error *err);
int cg_scene_add_mesh(cg_scene *scene, const cg_mesh *mesh, cg_error *err);
int cg_scene_add_instance(cg_scene *scene, int mesh, const float world[16], cg_error *err);
int cg_scene_add_light(cg_scene *scene, const cg_light *light, cg_error *err);
int cg_scene_add_camera(cg_scene *scene, const cg_camera *camera, cg_error *err);
int cg_scene_add_texture(cg_scene *scene, const cg_texture *texture, cg_error *err);

/* A root node named `name` with the identity transform (T 0, R identity, S 1). */
cg_node cg_node_default(const char *name);
/* The node's local transform: its matrix, or T x R x S (the quaternion normalised). */
void cg_node_local(const cg_node *node, double m[16]);
/* Appends a node (its parent must come before it); returns its index or -1. */
int cg_scene_add_node(cg_scene *scene, const cg_node *node, cg_error *err);
/* Makes instance, light or camera `index` follow `node` (an instance is then `moving`);
 * returns the attachment's index or -1. */
int cg_scene_attach(cg_scene *scene, cg_attachment_kind kind, int index, int node, cg_error *err);
/* Components per value of a channel (4 for rotations, else 3) and floats per key (three
 * values for CUBICSPLINE). */
int cg_anim_channel_components(const cg_anim_channel *channel);
int cg_anim_channel_stride(const cg_anim_channel *channel);
/* Allocates times and values for `key_count` keys (path and interpolation set first). */
bool cg_anim_channel_alloc(cg_anim_channel *channel, int key_count, cg_error *err);
/* Appends an animation; the scene takes ownership of its channels and their keys (freed
 * here on failure too). Returns its index or -1. */
int cg_scene_add_animation(cg_scene *scene, cg_animation *animation, cg_error *err);
/* Poses the nodes and what follows them at time t without touching the change stamps
 * (cg_scene_evaluate and the bounds' sampling use it). */
void cg_scene_pose(cg_scene *scene, double t);
/* The world boxes of the moving instances over the whole animation (each instance's
 * motion_min/max) and their union, added to lo/hi; false when no instance moves. */
bool cg_scene_motion_bounds(cg_scene *scene, double lo[3], double hi[3]);

/* Appends a skin; the scene takes `joints` (joint_count node indices) and `inverse_bind`
 * (joint_count x 16 floats), freed here on failure too. Returns its index or -1. */
int cg_scene_add_skin(cg_scene *scene, const char *name, int joint_count, int *joints, float *inverse_bind,
                      cg_error *err);
/* Binds mesh `mesh`, drawn by instance `instance` alone, to skin `skin`: the scene takes
 * `joints` and `weights` (vertex_count x influences each; joints below the skin's joint
 * count, weights >= 0 summing to 1), freed here on failure too; the mesh's vertex arrays as
 * they are now become its bind pose, and the instance's world matrix the identity (the skin
 * places the vertices in world space). Returns its index in scene->skinned or -1. */
int cg_scene_add_skinned_mesh(cg_scene *scene, int mesh, int instance, int skin, int influences, uint16_t *joints,
                              float *weights, cg_error *err);
/* Binds mesh `morph->mesh`, drawn by instance `morph->instance` alone, to its morph targets: the
 * scene takes morph's weights and deltas (freed here on failure too); the mesh's vertex arrays
 * as they are now become its base. Returns its index in scene->morphed or -1. */
int cg_scene_add_morphed_mesh(cg_scene *scene, const cg_morphed_mesh *morph, cg_error *err);
/* Frees what a skinned or a morphed mesh holds (not the mesh it deforms) and zeroes it: the
 * add_* above on failure, cg_scene_free for each one the scene holds. */
void cg_skinned_mesh_free(cg_skinned_mesh *sk);
void cg_morphed_mesh_free(cg_morphed_mesh *mm);

/* A white Lambertian material: base colour 1, metallic 0, roughness 1, and specular 0
 * (KHR_materials_specular), which leaves glTF's BRDF its Lambertian diffuse lobe alone; the
 * built-in scenes' materials start from it. The glTF loader starts from glTF's own defaults
 * (metallic 1, specular 1) instead. */
cg_material cg_material_default(const char *name);
/* glTF 2.0's default material (spec 5.19, with the defaults of KHR_materials_ior, _specular,
 * _transmission, _volume, _emissive_strength): base colour 1, metallic 1, roughness 1, ior 1.5,
 * specular 1 (colour 1), no transmission, thin (thickness 0), no attenuation, OPAQUE with cutoff
 * 0.5, single-sided, no textures, identity uv transforms. The glTF loader's material 0 (what a
 * primitive without a material uses) and the start of every material it reads. */
cg_material cg_material_gltf_default(const char *name);
/* { 1, 0, 0, 1, 0, 0 } (cg_uv_transform). */
cg_uv_transform cg_uv_transform_identity(void);

/* Local-space bounds of the vertices. */
void cg_mesh_compute_bounds(cg_mesh *mesh);
/* Area-weighted vertex normals from the triangles (allocates mesh->normals when NULL).
 * A vertex used by no triangle with non-zero area gets (0, 1, 0). */
bool cg_mesh_generate_normals(cg_mesh *mesh, cg_error *err);
/* Per-vertex tangents (allocates mesh->tangents when NULL; normals must be there) from the
 * triangles' texture-coordinate derivatives, accumulated per vertex, made orthogonal to the
 * normal (Gram-Schmidt), w = the handedness glTF's TANGENT has: bitangent = w cross(N, T)
 * points where the image's +Y (up, towards smaller v) lies. Not MikkTSpace (build.c says
 * where it differs). Without texcoords, or where the UVs give no direction, a tangent
 * perpendicular to the normal is chosen (w = 1). */
bool cg_mesh_generate_tangents(cg_mesh *mesh, cg_error *err);

/* The normal rule's bound (classify.c): every triangle's world normal has y above it. */
#define CG_HEIGHTFIELD_MIN_NY 1e-3f
/* Records who gave mesh `mesh` its kind (scene->mesh_class grows to mesh_count entries, new
 * ones CG_KIND_CLASSIFIED). */
bool cg_scene_set_kind_source(cg_scene *scene, int mesh, cg_kind_source source, cg_error *err);
/* Classifies (cg_mesh_classify, with scene->classify) every mesh whose kind source is
 * CG_KIND_CLASSIFIED and sets its kind; the others keep theirs. Called by cg_scene_load, which
 * passes its progress (may be NULL: taken from CG_LOAD_BUILT to CG_LOAD_TOTAL by triangles). */
bool cg_scene_classify(cg_scene *scene, cg_progress *progress, cg_error *err);

/* Where a scene load stands in the progress cg_scene_load reports (units of CG_LOAD_TOTAL):
 * the file read and parsed, the meshes built, then classified. The shares are those of a
 * 2-million-triangle glTF without mesh kinds (docs/scenes.md, "Loading time"). */
#define CG_LOAD_PARSED 33.0
#define CG_LOAD_BUILT 60.0
#define CG_LOAD_TOTAL 100.0

/* A height-field scene from a DEM image, "dem:PATH?key=value&..." (dem.c, docs/scenes.md); query
 * may be NULL. */
bool cg_dem_load(const char *path, const char *query, cg_scene *out, cg_error *err);

/* "NAME" and "key=value&..." (query may be NULL) of a "builtin:" source. */
bool cg_builtin_scene_load(const char *name, const char *query, cg_scene *out, cg_error *err);

/* Loads a .gltf or .glb file (the adapter decides by magic). A mesh with a "conegraph_kind"
 * extra gets that kind (source CG_KIND_EXTRAS); cg_scene_load classifies the others.
 * `progress` (may be NULL) is taken to CG_LOAD_PARSED and on to CG_LOAD_BUILT. */
bool cg_gltf_load(const char *path, cg_scene *out, cg_progress *progress, cg_error *err);

/* Checks the JSON of a glTF file (a .gltf, or a .glb's JSON chunk) as the Khronos
 * glTF-Validator would, before tinygltf reads it (gltf_check.c): JSON types, required
 * fields, ranges, enumerations, index references, asset.version (2.x; glTF 1.0 named as
 * such), extensionsRequired, buffers without uri. `glb_bin` is the size of a .glb's BIN chunk
 * (0 when it has none), -1 for a .gltf. `file` names the file in messages, which give the
 * JSON path of the field: CG_ERR_GLTF_PARSE, _VERSION, _SCHEMA, _INDEX_RANGE, _BUFFER,
 * _ACCESSOR (an animation sampler's accessors) or _EXTENSION. */
bool cg_gltf_check_json(const char *file, const char *json, size_t size, long long glb_bin, cg_error *err);

#ifdef __cplusplus
}
#endif

#endif
