/* cg/scene.h: the plain C scene every pass reads: glTF 2.0 files, built-in scenes, DEM images.
 *
 * Declares: cg_mesh_kind, cg_texture, cg_material, cg_mesh, cg_instance, cg_light_type,
 *           cg_light, cg_camera_type, cg_camera, cg_sky_type, cg_sky, cg_kind_source,
 *           cg_classify_rule, cg_classify_points, cg_classify_options, cg_mesh_class, cg_node,
 *           cg_attachment_kind, cg_attachment, cg_anim_path, cg_anim_interpolation, cg_anim_channel,
 *           cg_animation, cg_skin, cg_skinned_mesh, cg_morphed_mesh, CG_MAX_MORPH_TARGETS,
 *           cg_scene, cg_scene_load, cg_scene_free, cg_classify_defaults,
 *           cg_mesh_classify, cg_scene_export_gltf, cg_scene_compute_bounds,
 *           cg_scene_triangle_count, cg_scene_builtin_names, cg_scene_validate, cg_scene_set_sky,
 *           cg_sky_parse, cg_sky_model, cg_sky_model_init, cg_sky_model_radiance, cg_sky_format,
 *           cg_sky_equal, cg_sky_is_black, cg_scene_is_lit, cg_scene_emits, cg_scene_emitted_light,
 *           CG_EMITTERS_MIN_LIGHT, the CG_DEFAULT_* constants,
 *           cg_default_sun, cg_default_sky, cg_scene_add_default_sun, cg_scene_changes,
 *           cg_scene_evaluate, cg_scene_is_animated, cg_scene_animation_range,
 *           cg_scene_lights_changed, cg_anim_channel_sample.
 *
 * Units and conventions (see docs/architecture.md): metres, y up, glTF 2.0.
 * Lambertian BRDF with albedo = base_color x base colour texture.
 * Directional light: intensity x color is the irradiance E (W/m^2, or lux) on a
 * surface facing it; a white Lambertian surface facing it has radiance E/pi.
 * Point and spot lights: intensity x color is the radiant intensity I; E = I/d^2.
 * Emissive radiance = emissive x emissive texture x emissive_strength.
 * Sky: radiance in W/(m^2 sr) arriving from every direction where no surface is; none (black)
 * unless set with cg_scene_set_sky.
 */
#ifndef CG_SCENE_H
#define CG_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cg/error.h"

#define CG_NAME_MAX 64

/* The hybrid method puts height-field meshes (terrain) in a 2D lightmap and complex meshes in a 3D one. */
typedef enum cg_mesh_kind {
    CG_MESH_COMPLEX = 0,
    CG_MESH_HEIGHTFIELD = 1
} cg_mesh_kind;

/* 8-bit RGBA texels, rows top to bottom as glTF images store them. Uploaded as they are, the
 * first row lies at GL's t = 0, which is where glTF's v = 0 is: the image's top edge (glTF 2.0,
 * 3.9.1: "the origin of the UV coordinates (0, 0) corresponds to the upper left corner"), so
 * texture coordinates go to GL and the path tracer unchanged. */
typedef struct cg_texture {
    char name[CG_NAME_MAX];
    int width, height;
    uint8_t *rgba;
    bool srgb; /* base colour and emissive textures are sRGB-encoded */
} cg_texture;

/* glTF 2.0 material.alphaMode. */
typedef enum cg_alpha_mode {
    CG_ALPHA_OPAQUE = 0,    /* alpha ignored */
    CG_ALPHA_MASK,          /* covered where alpha >= alpha_cutoff, else not there at all */
    CG_ALPHA_BLEND          /* alpha is the coverage of a see-through surface (docs/gltf.md) */
} cg_alpha_mode;

/* The textures a material can sample, indexing cg_material.uv. */
typedef enum cg_material_texture {
    CG_TEX_BASE_COLOR = 0,
    CG_TEX_EMISSIVE,
    CG_TEX_METALLIC_ROUGHNESS,
    CG_TEX_NORMAL,
    CG_TEX_OCCLUSION,
    CG_TEX_TRANSMISSION,
    CG_TEX_COUNT
} cg_material_texture;

/* KHR_texture_transform as a 2x3 affine matrix, columns first: uv' = m[0..1] u + m[2..3] v + m[4..5]
 * (T x R x S of the extension). Identity: { 1, 0, 0, 1, 0, 0 }. */
typedef struct cg_uv_transform {
    float m[6];
} cg_uv_transform;

/* glTF 2.0 metallic-roughness material (the spec's Appendix B) with the extensions the renderer
 * implements. Texture fields index cg_scene.textures (-1 = none); every texture reads TEXCOORD_0
 * through its uv transform. */
typedef struct cg_material {
    char name[CG_NAME_MAX];
    float base_color[4];     /* linear RGBA */
    int base_color_texture;  /* index into cg_scene.textures, -1 = none */
    float emissive[3];       /* linear RGB factor */
    int emissive_texture;    /* -1 = none */
    float emissive_strength; /* KHR_materials_emissive_strength, 1 by default */
    float metallic, roughness;
    int metallic_roughness_texture; /* B = metallic, G = roughness (linear), x the factors */
    int normal_texture;      /* tangent-space normal map (linear) */
    float normal_scale;      /* scales the map's x and y (glTF normalTexture.scale, 1) */
    int occlusion_texture;   /* R = ambient occlusion (linear): darkens indirect light only */
    float occlusion_strength; /* 1 + strength x (occlusion - 1) (glTF occlusionTexture.strength, 1) */
    cg_alpha_mode alpha_mode;
    float alpha_cutoff;      /* MASK: 0.5 by default */
    bool double_sided;       /* false: back faces are culled (glTF doubleSided) */
    float ior;               /* KHR_materials_ior, 1.5; dielectric F0 = ((ior - 1)/(ior + 1))^2 */
    float specular;          /* KHR_materials_specular specularFactor: scales the dielectric F0 and */
    float specular_color[3]; /* is its F90; x specularColorFactor (F0 only). 0: no specular lobe, the */
                             /* pure Lambertian of the built-in scenes (cg_material_default) */
    float transmission;      /* KHR_materials_transmission factor (0: opaque) */
    int transmission_texture; /* R x the factor */
    float thickness;         /* KHR_materials_volume thicknessFactor, mesh units; 0: thin-walled */
    float attenuation_distance; /* metres light travels in the volume before attenuation_color is */
    float attenuation_color[3]; /* left of it (Beer-Lambert); INFINITY: no attenuation */
    cg_uv_transform uv[CG_TEX_COUNT]; /* KHR_texture_transform of each texture above */
} cg_material;

/* One glTF primitive: a triangle list in the mesh's local space. */
typedef struct cg_mesh {
    char name[CG_NAME_MAX];
    uint32_t vertex_count;
    uint32_t index_count;   /* a multiple of 3 */
    float *positions;       /* vertex_count x 3 */
    float *normals;         /* vertex_count x 3, unit length (generated when the file has none) */
    float *texcoords;       /* vertex_count x 2, or NULL */
    float *tangents;        /* vertex_count x 4: xyz unit tangent, w = +-1 bitangent sign (glTF
                             * TANGENT); from the file, else generated when the mesh's material has
                             * a normal texture; NULL otherwise */
    uint32_t *indices;      /* index_count */
    int material;           /* index into cg_scene.materials; a default white material always exists at 0 */
    cg_mesh_kind kind;
    float bounds_min[3], bounds_max[3]; /* local space */
    uint64_t revision;      /* cg_scene.revision when its vertices last changed (a skin posed them,
                             * cg_skinned_mesh); 0: never. GPU copies compare it (cg/gpu_scene.h) */
} cg_mesh;

/* A mesh placed in the world. glTF's node hierarchy is flattened into these, except where
 * animation needs it (cg_node): an instance on an animated node follows it. */
typedef struct cg_instance {
    int mesh;
    float world[16];        /* column-major 4x4, local to world, at the scene's time */
    bool moving;            /* follows an animated node (a cg_attachment): `world` changes with time */
    float motion_min[3], motion_max[3]; /* moving: its world box over the whole animation
                                         * (cg_scene_compute_bounds); else the current box */
    uint64_t revision;      /* cg_scene.revision when `world` last changed (0: never) */
} cg_instance;

typedef enum cg_light_type {
    CG_LIGHT_DIRECTIONAL,
    CG_LIGHT_POINT,
    CG_LIGHT_SPOT
} cg_light_type;

typedef struct cg_light {
    char name[CG_NAME_MAX];
    cg_light_type type;
    float color[3];
    float intensity;
    float position[3];      /* world space (point, spot) */
    float direction[3];     /* world space unit vector the light travels along (directional, spot) */
    float range;            /* 0 = infinite */
    float inner_cone_angle; /* spot, radians */
    float outer_cone_angle; /* spot, radians */
    float angular_diameter; /* directional: the apparent diameter of the source's disc, radians
                             * (the sun: 0.0093); 0 = a point, hard shadows. glTF has no field for
                             * it: a light's extras "conegraph_angular_diameter" (radians) */
} cg_light;

typedef enum cg_camera_type {
    CG_CAMERA_PERSPECTIVE,
    CG_CAMERA_ORTHOGRAPHIC
} cg_camera_type;

typedef struct cg_camera {
    char name[CG_NAME_MAX];
    cg_camera_type type;
    float yfov;             /* perspective, radians */
    float aspect;           /* 0 = follow the image */
    float znear, zfar;      /* zfar 0 = infinite (perspective) */
    float xmag, ymag;       /* orthographic half extents */
    float world[16];        /* column-major camera-to-world; the camera looks down its -z */
} cg_camera;

/* The sky (docs/reference.md has the formulas). Every loader leaves it CG_SKY_NONE. */
typedef enum cg_sky_type {
    CG_SKY_NONE = 0,        /* black */
    CG_SKY_UNIFORM,         /* `radiance` from every direction, the whole sphere */
    CG_SKY_PREETHAM         /* daylight of Preetham, Shirley and Smits (SIGGRAPH 1999), the sun
                             * in the direction the first directional light comes from; black
                             * below the horizon (y = 0 plane of directions) */
} cg_sky_type;

typedef struct cg_sky {
    cg_sky_type type;
    float radiance[3];      /* uniform: W/(m^2 sr) per channel */
    float turbidity;        /* preetham: 1.7 (very clear) to 10 (hazy) */
    float scale;            /* preetham: radiance = scale x the model's linear sRGB, whose
                             * luminance Y is in kcd/m^2 (scale 1: kilo-nits) */
} cg_sky;

/* ------------------------------------------------------------ height-field classification
 *
 * Which meshes are height fields (hybrid cone tracing paper, section V.A): eq. 5 by default, the
 * normal rule as an alternative (core/scene/classify.c has both; docs/scenes.md compares them).
 * A glTF mesh's "conegraph_kind" extra ("heightfield" or "complex") and the kinds a built-in or
 * DEM scene gives its meshes are kept as they are. */

typedef enum cg_kind_source {
    CG_KIND_CLASSIFIED = 0, /* by the classification rule, when the scene was loaded */
    CG_KIND_EXTRAS,         /* a glTF mesh's "conegraph_kind" extra */
    CG_KIND_SCENE           /* set by the built-in or DEM scene that made the mesh */
} cg_kind_source;

typedef enum cg_classify_rule {
    CG_CLASSIFY_EQ5 = 0,    /* eq. 5: the mean distance of the mesh to its height-field
                             * simplification, over the bounding box's diagonal, below a threshold */
    CG_CLASSIFY_NORMALS     /* every triangle faces up (world normal y > 1e-3) */
} cg_classify_rule;

typedef enum cg_classify_points {
    CG_CLASSIFY_VERTICES = 0, /* eq. 5's X: the mesh's vertices (the paper's) */
    CG_CLASSIFY_CENTROIDS     /* the centroids of its triangles (the paper's faster option) */
} cg_classify_points;

#define CG_EQ5_DEFAULT_RESOLUTION 2048
#define CG_EQ5_MAX_RESOLUTION 8192
#define CG_EQ5_DEFAULT_THRESHOLD 0.001

/* How meshes are classified; zero-initialised fields take the defaults. A scene source sets them
 * with query keys (cg_scene_load): classify=eq5|normals, eq5_resolution=N, eq5_threshold=T,
 * eq5_points=vertices|centroids. */
typedef struct cg_classify_options {
    cg_classify_rule rule;
    int resolution;         /* eq. 5: samples along the bounding box's longer horizontal side
                             * (the other side in proportion); 0: CG_EQ5_DEFAULT_RESOLUTION */
    double threshold;       /* eq. 5: a height field when d < threshold; 0: CG_EQ5_DEFAULT_THRESHOLD */
    cg_classify_points points;
    int threads;            /* 0: one per core (at most 16) */
} cg_classify_options;

/* What the classification found for one mesh (cg_scene.mesh_class, cg_mesh_classify). */
typedef struct cg_mesh_class {
    cg_mesh_kind kind;      /* the kind the rule gives */
    cg_kind_source source;  /* who decided the mesh's kind (cg_mesh.kind) */
    double distance;        /* eq. 5's d of its worst instance; +inf when an instance has no area
                             * seen from above; NaN when not computed (normal rule, kind given,
                             * no instance) */
    double max_distance;    /* the largest distance of one point, over the same diagonal */
    int instances;
    bool normals_up;        /* the normal rule's verdict (every instance's triangles face up) */
} cg_mesh_class;
/* ------------------------------------------------------------------ animation
 *
 * glTF 2.0 animations of node translation, rotation and scale (docs/gltf.md, "Animation").
 * Only the nodes animation needs are kept: the animated ones, their descendants and their
 * ancestors; every other node is flattened into the world matrices as before. Instances,
 * lights and cameras on kept nodes follow them through cg_attachment. cg_scene_evaluate
 * poses the scene at a time. */

/* A kept glTF node. Nodes are stored parents first (parent < index). */
typedef struct cg_node {
    char name[CG_NAME_MAX];
    int parent;             /* index of the parent node, or -1 */
    bool has_matrix;        /* the local transform is `matrix` (glTF forbids animating such a node) */
    float matrix[16];       /* column-major */
    float translation[3];   /* local T, R, S (local = T x R x S): the rest pose, or for an */
    float rotation[4];      /* animated property its value at the scene's time; rotation is */
    float scale[3];         /* a unit quaternion x, y, z, w */
    double world[16];       /* local to world at the scene's time */
} cg_node;

typedef enum cg_attachment_kind {
    CG_ATTACH_INSTANCE,
    CG_ATTACH_LIGHT,
    CG_ATTACH_CAMERA
} cg_attachment_kind;

/* An instance, light or camera that follows a node: an instance's and a camera's world
 * matrix is the node's; a light sits at the node's origin and shines down its -Z
 * (KHR_lights_punctual). */
typedef struct cg_attachment {
    cg_attachment_kind kind;
    int index;              /* into instances, lights or cameras */
    int node;
} cg_attachment;

typedef enum cg_anim_path {
    CG_ANIM_TRANSLATION,
    CG_ANIM_ROTATION,
    CG_ANIM_SCALE,
    CG_ANIM_WEIGHTS         /* the morph target weights of the meshes on the node (cg_morphed_mesh) */
} cg_anim_path;

/* The most morph targets a mesh may have for conegraph to read them (a file with more keeps the
 * base shape, with a notice). */
#define CG_MAX_MORPH_TARGETS 32

typedef enum cg_anim_interpolation {
    CG_INTERP_LINEAR,       /* lerp; slerp for rotations (glTF 2.0, Appendix C) */
    CG_INTERP_STEP,
    CG_INTERP_CUBICSPLINE   /* cubic Hermite with in- and out-tangents (glTF 2.0, Appendix C) */
} cg_anim_interpolation;

/* One animated property of one node: a glTF channel and its sampler. */
typedef struct cg_anim_channel {
    int node;               /* index into cg_scene.nodes */
    cg_anim_path path;
    cg_anim_interpolation interpolation;
    int key_count;          /* >= 1; >= 2 for CUBICSPLINE */
    int weight_count;       /* CG_ANIM_WEIGHTS: weights per key, 1..CG_MAX_MORPH_TARGETS */
    float *times;           /* key_count times in seconds, >= 0, strictly increasing */
    float *values;          /* per key N floats (N = 4 for rotations, x y z w; weight_count for
                             * weights; else 3), or for CUBICSPLINE 3 x N: in-tangent, value,
                             * out-tangent */
} cg_anim_channel;

/* A glTF skin (glTF 2.0, 3.7.3): the nodes that deform the meshes bound to it. */
typedef struct cg_skin {
    char name[CG_NAME_MAX];
    int joint_count;
    int *joints;            /* joint_count indices into cg_scene.nodes */
    float *inverse_bind;    /* joint_count column-major 4x4 inverse bind matrices (identity when
                             * the file gives none) */
} cg_skin;

/* A mesh a skin deforms (docs/dynamic.md, "Skins"). glTF 2.0, 3.7.3.3: a vertex's world position
 * is sum_i w_i x world(joint_i) x inverse_bind(joint_i) x its bind position, and the transform of
 * the node holding the mesh is ignored. The mesh is its own (one instance draws it, with the
 * identity world matrix); cg_scene_evaluate writes the posed world-space vertices into it on the
 * CPU, bumps its `revision` and its instance's, and counts it in cg_scene_changes. */
typedef struct cg_skinned_mesh {
    int mesh;               /* into cg_scene.meshes: its vertex arrays hold the posed vertices */
    int instance;           /* the one instance drawing it */
    int skin;               /* into cg_scene.skins */
    int influences;         /* joints per vertex: 4 per JOINTS_n / WEIGHTS_n pair */
    uint16_t *joints;       /* vertex_count x influences, indices into the skin's joints */
    float *weights;         /* vertex_count x influences, >= 0, summing to 1 */
    float *bind_positions;  /* vertex_count x 3: the mesh as the file gives it */
    float *bind_normals;    /* vertex_count x 3 */
    float *bind_tangents;   /* vertex_count x 4, or NULL when the mesh has none */
    float *joint_bounds;    /* joint_count x 6 (min xyz, max xyz): the box of the bind positions
                             * each joint weighs (min > max: none), for bounds over the animation */
    double *posed_with;     /* joint_count x 16: the skinning matrices of the last pose (NaN:
                             * not posed yet) */
} cg_skinned_mesh;

/* A mesh with morph targets (glTF 2.0, 3.7.2.2): its vertices are the base plus the weighted sum
 * of the targets' displacements (positions, normals and tangents, each where the file gives
 * them; normals and tangents normalised after). The mesh is its own (one instance draws it);
 * cg_scene_evaluate writes the morphed vertices into it when the weights changed (animated by
 * CG_ANIM_WEIGHTS channels on `node`), bumps its `revision` and its instance's, and counts it in
 * cg_scene_changes, as for a skin. A skinned mesh's targets are not read. */
typedef struct cg_morphed_mesh {
    int mesh;               /* into cg_scene.meshes: its vertex arrays hold the morphed vertices */
    int instance;           /* the one instance drawing it */
    int node;               /* the cg node whose weight channels drive it, or -1 (static weights) */
    int target_count;       /* 1..CG_MAX_MORPH_TARGETS */
    float *weights;         /* target_count: the weights at the scene's time (the file's default
                             * weights: the node's, else the mesh's, else 0) */
    float *applied;         /* target_count: the weights the vertices were last morphed with (NaN:
                             * not yet) */
    float *base_positions, *base_normals, *base_tangents; /* vertex_count x 3, 3, 4 (tangents NULL
                                                             * when the mesh has none) */
    float *position_deltas; /* target_count x vertex_count x 3, or NULL: no target moves positions */
    float *normal_deltas;   /* the same for normals, or NULL */
    float *tangent_deltas;  /* the same for tangents (xyz), or NULL */
    float *delta_bounds;    /* target_count x 6: each target's position displacements' box */
} cg_morphed_mesh;

/* A glTF animation. All of a scene's animations play together, from time 0. */
typedef struct cg_animation {
    char name[CG_NAME_MAX];
    cg_anim_channel *channels;
    int channel_count;
} cg_animation;

typedef struct cg_scene {
    char name[256];         /* file path or builtin:name */
    cg_mesh *meshes;         int mesh_count;
    cg_instance *instances;  int instance_count;
    cg_material *materials;  int material_count;
    cg_texture *textures;    int texture_count;
    cg_light *lights;        int light_count;
    cg_camera *cameras;      int camera_count;
    /* world space, over all instances; an animated scene's over the whole animation, so that
     * volumes and shadow fits fitted to them stay put from frame to frame */
    float bounds_min[3], bounds_max[3];
    cg_sky sky;             /* CG_SKY_NONE unless set (cg_scene_set_sky) */
    cg_classify_options classify;   /* as the source asked (cg_scene_load) */
    cg_mesh_class *mesh_class;      /* mesh_class_count entries (mesh_count after cg_scene_load);
                                     * NULL in a scene built by hand */
    int mesh_class_count;
    cg_node *nodes;              int node_count;
    cg_attachment *attachments;  int attachment_count;
    cg_animation *animations;    int animation_count;
    cg_skin *skins;              int skin_count;
    cg_skinned_mesh *skinned;    int skinned_count;
    cg_morphed_mesh *morphed;    int morphed_count;
    double time;            /* seconds: the time the scene is posed at (0 after loading) */
    /* Change stamps for caches: `revision` counts the changes to instance worlds, lights and
     * cameras (cg_scene_evaluate, cg_scene_lights_changed); instances_revision,
     * lights_revision and cameras_revision (and each instance's `revision`) hold the value it
     * had when they last changed. A cache that saw revision R rebuilds what is newer than R. */
    uint64_t revision, instances_revision, lights_revision, cameras_revision;
} cg_scene;

/* Loads `source`: a .gltf/.glb path, "builtin:NAME" or "dem:IMAGE" (docs/scenes.md), each
 * with an optional "?key=value&..." (e.g. "builtin:openworld?triangles=2000000&seed=7",
 * "town.glb?eq5_threshold=0.002"); the classification keys above are taken by every kind of
 * source. Then classifies the meshes whose kind the source does not give. On failure *out is
 * left empty and err names the file and the problem. */
bool cg_scene_load(const char *source, cg_scene *out, cg_error *err);
void cg_scene_free(cg_scene *scene);

/* *out = *in (or zero when in is NULL) with every default filled in; returns out. */
const cg_classify_options *cg_classify_defaults(cg_classify_options *out, const cg_classify_options *in);
/* Classifies mesh `mesh` of the scene by options->rule over all its instances (eq. 5's distance
 * is computed with the eq5 rule only) and fills *out, its `source` left as it was. Fails only
 * when out of memory. */
bool cg_mesh_classify(const cg_scene *scene, int mesh, const cg_classify_options *options, cg_mesh_class *out,
                      cg_error *err);

/* Writes the scene as glTF 2.0 (.gltf with embedded buffers, or .glb by extension),
 * with KHR_lights_punctual and KHR_materials_emissive_strength, through a temporary
 * file renamed into place. Mesh kinds are kept in mesh extras ("conegraph_kind"). */
bool cg_scene_export_gltf(const cg_scene *scene, const char *path, cg_error *err);

/* Recomputes world bounds from the instances; for an animated scene, the union over the
 * animation (sampled: posed at every key time and 15 evenly spaced times between consecutive
 * ones, 4096 poses at most) and each moving instance's motion box; the scene is left posed at
 * its time. Call it again after changing nodes or animations by hand. */
void cg_scene_compute_bounds(cg_scene *scene);
/* Triangles over all instances. */
size_t cg_scene_triangle_count(const cg_scene *scene);
/* Checks indices, finiteness and references; used by every loader. */
bool cg_scene_validate(const cg_scene *scene, cg_error *err);

/* Sets the scene's sky after checking it: finite radiance >= 0; turbidity in [1.7, 10] and
 * a finite scale >= 0 for Preetham, whose sun is the first directional light (the scene must
 * have one). Fails with CG_ERR_USAGE and a message naming the bad value. */
bool cg_scene_set_sky(cg_scene *scene, const cg_sky *sky, cg_error *err);

/* Parses a sky as `--sky` and graph files give it: "none"; "R,G,B" or "L" (uniform radiance,
 * W/(m^2 sr)); "preetham", "preetham:T" or "preetham:T,SCALE" (defaults T 3, SCALE 1).
 * Fails with CG_ERR_USAGE naming what was expected. */
bool cg_sky_parse(const char *text, cg_sky *out, cg_error *err);

/* The sky as cg_sky_parse reads it: "none", "L" (all channels alike), "R,G,B" or
 * "preetham:T,SCALE". */
void cg_sky_format(const cg_sky *sky, char *out, size_t size);
/* Whether two skies give the same radiance (the fields their type uses are equal). */
bool cg_sky_equal(const cg_sky *a, const cg_sky *b);

/* The default light (core/scene/lighting.c says why these values; docs/scenes.md): what the
 * apps add to a scene that nothing lights, unless told not to (--no-default-light). */
#define CG_DEFAULT_SUN_NAME "default_sun"
#define CG_DEFAULT_SUN_IRRADIANCE 3.0f      /* W/m^2 on a surface facing it, white */
#define CG_DEFAULT_SUN_ELEVATION_DEG 55.0   /* above the horizon (the y = 0 plane) */
#define CG_DEFAULT_SUN_AZIMUTH_DEG 30.0     /* from +z towards +x */
#define CG_DEFAULT_SKY_RADIANCE 0.2f        /* uniform, W/(m^2 sr) per channel */

/* Whether the sky gives no light: none, a uniform radiance of 0, a Preetham scale of 0. */
bool cg_sky_is_black(const cg_sky *sky);
/* Whether anything lights the scene: a light, a sky that is not black, or emissive surfaces
 * whose light (cg_scene_emitted_light) reaches CG_EMITTERS_MIN_LIGHT. */
bool cg_scene_is_lit(const cg_scene *scene);
/* Whether an instanced mesh's material emits. */
bool cg_scene_emits(const cg_scene *scene);
/* Whether a material has a lobe besides the Lambertian one, which the gathers trace a cone for: a
 * specular reflection (metallic or specular above 0) or a transmission (transmission above 0, or
 * alphaMode BLEND, whose uncovered part is a straight-through sheet). cg_material_default has none. */
bool cg_material_has_lobes(const cg_material *m);
/* Whether an instanced mesh's material has such a lobe. */
bool cg_scene_has_lobes(const cg_scene *scene);
/* The emitters' light spread over the scene: sum of emitted radiance x area over the area of
 * every instanced surface, W/(m^2 sr): the mean radiance of a white surface if all of it arrived
 * (core/scene/lighting.c says why). */
double cg_scene_emitted_light(const cg_scene *scene);
/* 1% of the radiance of a white surface facing the default sun: below it, emitters do not light
 * a scene. */
#define CG_EMITTERS_MIN_LIGHT (0.01 * CG_DEFAULT_SUN_IRRADIANCE / 3.14159265358979323846)
/* The default sun as a light, and the default sky. */
void cg_default_sun(cg_light *out);
void cg_default_sky(cg_sky *out);
/* Appends the default sun to the scene's lights (last, so that lights the scene had keep their
 * indices; a Preetham sky follows the first directional light). */
bool cg_scene_add_default_sun(cg_scene *scene, cg_error *err);

/* The sky's radiance in any direction, ready to evaluate: built once per scene. */
typedef struct cg_sky_model {
    cg_sky_type type;
    float radiance[3];      /* uniform */
    float sun[3];           /* preetham: unit direction towards the sun, world space (y up) */
    float sun_zenith;       /* preetham: the sun's zenith angle theta_s, radians, at most pi/2 */
    double perez[3][5];     /* preetham: A..E of the Perez function for Y, x, y */
    double zenith[3];       /* preetham: Y_z (kcd/m^2), x_z, y_z */
    double norm[3];         /* preetham: zenith value / F(0, theta_s), per quantity */
    double scale;
} cg_sky_model;

/* Fills the model for the scene's sky (CG_SKY_NONE gives a black model). Fails with
 * CG_ERR_USAGE when a Preetham sky has no directional light to follow. */
bool cg_sky_model_init(const cg_scene *scene, cg_sky_model *model, cg_error *err);
/* Radiance arriving from the unit world direction `dir` (towards the sky), linear RGB. */
void cg_sky_model_radiance(const cg_sky_model *model, const float dir[3], float rgb[3]);

/* What one cg_scene_evaluate changed. */
typedef struct cg_scene_changes {
    int instances_moved;    /* instances whose world matrix or (skinned) vertices changed (their
                             * `revision` says which) */
    int meshes_deformed;    /* skinned or morphed meshes whose vertices changed (their `revision`
                             * says which; a GPU copy needs cg_gpu_scene_update_meshes) */
    bool lights;            /* some light's position or direction changed */
    bool cameras;           /* some camera's world matrix changed */
} cg_scene_changes;

/* Poses the scene at time t (seconds, finite): samples every channel (before a channel's
 * first key its first value, after its last key its last value: no looping), recomputes the
 * kept nodes' world matrices and, from them, the world matrices of the instances, the
 * positions and directions of the lights and the world matrices of the cameras that follow
 * them, and the vertices of the skinned meshes whose joints moved. Bumps the change stamps of
 * what changed and reports it in *changes (may be NULL).
 * A scene without animation never changes. */
void cg_scene_evaluate(cg_scene *scene, double t, cg_scene_changes *changes);
/* Whether any channel animates the scene. */
bool cg_scene_is_animated(const cg_scene *scene);
/* The first and last key time over all channels (0 and 0 without animation). */
void cg_scene_animation_range(const cg_scene *scene, double *start, double *end);
/* Bumps the lights' change stamp: for an app that moved or changed a light by hand. */
void cg_scene_lights_changed(cg_scene *scene);
/* The channel's value at time t: 3 components, 4 for a rotation (a unit quaternion), or
 * weight_count for weights (out has room for 4, or for weight_count). */
void cg_anim_channel_sample(const cg_anim_channel *channel, double t, double *out);

/* NULL-terminated list of built-in scene names, and a one-line description of each. */
const char *const *cg_scene_builtin_names(void);
const char *cg_scene_builtin_doc(const char *name);

#endif
