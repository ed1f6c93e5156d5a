/* cg/scene.h: the plain C scene every pass reads: glTF 2.0 files and built-in scenes.
 *
 * Declares: cg_mesh_kind, cg_texture, cg_material, cg_mesh, cg_instance, cg_light_type,
 *           cg_light, cg_camera_type, cg_camera, cg_sky_type, cg_sky, cg_scene, cg_scene_load,
 *           cg_scene_free, cg_scene_export_gltf, cg_scene_compute_bounds, cg_scene_triangle_count,
 *           cg_scene_builtin_names, cg_scene_validate, cg_scene_set_sky, cg_sky_parse,
 *           cg_sky_model, cg_sky_model_init, cg_sky_model_radiance, cg_sky_format, cg_sky_equal,
 *           cg_sky_is_black, cg_scene_is_lit, the CG_DEFAULT_* constants, cg_default_sun, cg_default_sky,
 *           cg_scene_add_default_sun.
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

/* 8-bit RGBA texels, rows bottom to top as GL expects (glTF images are top to bottom: the loader flips). */
typedef struct cg_texture {
    char name[CG_NAME_MAX];
    int width, height;
    uint8_t *rgba;
    bool srgb; /* base colour and emissive textures are sRGB-encoded */
} cg_texture;

typedef struct cg_material {
    char name[CG_NAME_MAX];
    float base_color[4];     /* linear RGBA */
    int base_color_texture;  /* index into cg_scene.textures, -1 = none */
    float emissive[3];       /* linear RGB factor */
    int emissive_texture;    /* -1 = none */
    float emissive_strength; /* KHR_materials_emissive_strength, 1 by default */
    float metallic, roughness;
} cg_material;

/* One glTF primitive: a triangle list in the mesh's local space. */
typedef struct cg_mesh {
    char name[CG_NAME_MAX];
    uint32_t vertex_count;
    uint32_t index_count;   /* a multiple of 3 */
    float *positions;       /* vertex_count x 3 */
    float *normals;         /* vertex_count x 3, unit length (generated when the file has none) */
    float *texcoords;       /* vertex_count x 2, or NULL */
    uint32_t *indices;      /* index_count */
    int material;           /* index into cg_scene.materials; a default white material always exists at 0 */
    cg_mesh_kind kind;
    float bounds_min[3], bounds_max[3]; /* local space */
} cg_mesh;

/* A mesh placed in the world; glTF's node hierarchy is flattened into these. */
typedef struct cg_instance {
    int mesh;
    float world[16];        /* column-major 4x4, local to world */
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

typedef struct cg_scene {
    char name[256];         /* file path or builtin:name */
    cg_mesh *meshes;         int mesh_count;
    cg_instance *instances;  int instance_count;
    cg_material *materials;  int material_count;
    cg_texture *textures;    int texture_count;
    cg_light *lights;        int light_count;
    cg_camera *cameras;      int camera_count;
    float bounds_min[3], bounds_max[3]; /* world space, over all instances */
    cg_sky sky;             /* CG_SKY_NONE unless set (cg_scene_set_sky) */
} cg_scene;

/* Loads `source`: a .gltf/.glb path, or "builtin:NAME[?key=value&...]"
 * (e.g. "builtin:openworld?triangles=2000000&seed=7"). On failure *out is left empty
 * and err names the file and the problem. */
bool cg_scene_load(const char *source, cg_scene *out, cg_error *err);
void cg_scene_free(cg_scene *scene);

/* Writes the scene as glTF 2.0 (.gltf with embedded buffers, or .glb by extension),
 * with KHR_lights_punctual and KHR_materials_emissive_strength, through a temporary
 * file renamed into place. Mesh kinds are kept in mesh extras ("conegraph_kind"). */
bool cg_scene_export_gltf(const cg_scene *scene, const char *path, cg_error *err);

/* Recomputes world bounds from the instances. */
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
/* Whether anything lights the scene: a light, an instanced mesh whose material emits, or a sky
 * that is not black. */
bool cg_scene_is_lit(const cg_scene *scene);
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

/* NULL-terminated list of built-in scene names, and a one-line description of each. */
const char *const *cg_scene_builtin_names(void);
const char *cg_scene_builtin_doc(const char *name);

#endif
