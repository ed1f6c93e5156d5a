/* core/scene/build.c: building a scene and freeing it: appending materials, meshes, instances,
 * lights, cameras and textures, the default materials, a mesh's bounds, normals and tangents,
 * who gave a mesh its kind, and freeing all a scene holds (its skins and morphed meshes too).
 * The loaders (builtin/, dem.c, gltf_adapter.cpp, lighting.c), animation.c and classify.c build
 * through these; nothing here calls back into them or into scene.c, which calls the loaders. */
#include "cg/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

void
cg_copy_name(char dst[CG_NAME_MAX], const char *src)
{
    snprintf(dst, CG_NAME_MAX, "%s", src ? src : "");
}

/* Grows *array by one element of `size` bytes; returns the new element's index or -1. */
static int
append(void **array, int *count, size_t size, const void *element, const char *what, cg_error *err)
{
    void *bigger = realloc(*array, (size_t)(*count + 1) * size);
    if (!bigger) {
        cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory adding a %s to the scene", what);
        return -1;
    }
    *array = bigger;
    memcpy((char *)bigger + (size_t)*count * size, element, size);
    return (*count)++;
}

int
cg_scene_add_material(cg_scene *scene, const cg_material *material, cg_error *err)
{
    return append((void **)&scene->materials, &scene->material_count, sizeof *material, material,
                  "material", err);
}

int
cg_scene_add_mesh(cg_scene *scene, const cg_mesh *mesh, cg_error *err)
{
    return append((void **)&scene->meshes, &scene->mesh_count, sizeof *mesh, mesh, "mesh", err);
}

int
cg_scene_add_instance(cg_scene *scene, int mesh, const float world[16], cg_error *err)
{
    cg_instance instance = { .mesh = mesh };
    memcpy(instance.world, world, sizeof instance.world);
    return append((void **)&scene->instances, &scene->instance_count, sizeof instance, &instance,
                  "instance", err);
}

int
cg_scene_add_light(cg_scene *scene, const cg_light *light, cg_error *err)
{
    return append((void **)&scene->lights, &scene->light_count, sizeof *light, light, "light", err);
}

int
cg_scene_add_camera(cg_scene *scene, const cg_camera *camera, cg_error *err)
{
    return append((void **)&scene->cameras, &scene->camera_count, sizeof *camera, camera,
                  "camera", err);
}

int
cg_scene_add_texture(cg_scene *scene, const cg_texture *texture, cg_error *err)
{
    return append((void **)&scene->textures, &scene->texture_count, sizeof *texture, texture,
                  "texture", err);
}

cg_material
cg_material_default(const char *name)
{
    cg_material m = {
        .base_color = { 1, 1, 1, 1 },
        .base_color_texture = -1,
        .emissive = { 0, 0, 0 },
        .emissive_texture = -1,
        .emissive_strength = 1,
        .metallic = 0,
        .roughness = 1,
        .metallic_roughness_texture = -1,
        .normal_texture = -1,
        .normal_scale = 1,
        .occlusion_texture = -1,
        .occlusion_strength = 1,
        .alpha_mode = CG_ALPHA_OPAQUE,
        .alpha_cutoff = 0.5f,
        .double_sided = true,
        .ior = 1.5f,
        .specular = 0,          /* no specular lobe: Lambertian (scene_internal.h) */
        .specular_color = { 1, 1, 1 },
        .transmission = 0,
        .transmission_texture = -1,
        .thickness = 0,
        .attenuation_distance = INFINITY,
        .attenuation_color = { 1, 1, 1 },
    };
    for (int t = 0; t < CG_TEX_COUNT; t++)
        m.uv[t] = cg_uv_transform_identity();
    cg_copy_name(m.name, name);
    return m;
}

cg_uv_transform
cg_uv_transform_identity(void)
{
    return (cg_uv_transform){ { 1, 0, 0, 1, 0, 0 } };
}

cg_material
cg_material_gltf_default(const char *name)
{
    /* glTF 2.0, 5.19 (material), 5.22 (pbrMetallicRoughness): metallicFactor 1, roughnessFactor 1,
     * doubleSided false; the extensions' defaults: ior 1.5, specularFactor 1, specularColorFactor 1,
     * transmissionFactor 0, thicknessFactor 0, attenuationDistance +infinity, attenuationColor 1. */
    cg_material m = cg_material_default(name);
    m.metallic = 1;
    m.roughness = 1;
    m.double_sided = false;
    m.specular = 1;
    return m;
}

void
cg_mesh_compute_bounds(cg_mesh *mesh)
{
    if (mesh->vertex_count == 0) {
        memset(mesh->bounds_min, 0, sizeof mesh->bounds_min);
        memset(mesh->bounds_max, 0, sizeof mesh->bounds_max);
        return;
    }
    for (int k = 0; k < 3; k++)
        mesh->bounds_min[k] = mesh->bounds_max[k] = mesh->positions[k];
    for (uint32_t v = 1; v < mesh->vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            float x = mesh->positions[3 * v + k];
            if (x < mesh->bounds_min[k]) mesh->bounds_min[k] = x;
            if (x > mesh->bounds_max[k]) mesh->bounds_max[k] = x;
        }
}

static void
triangle_cross(const float *p, uint32_t a, uint32_t b, uint32_t c, double n[3])
{
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)p[3 * b + k] - p[3 * a + k];
        e2[k] = (double)p[3 * c + k] - p[3 * a + k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

bool
cg_mesh_generate_normals(cg_mesh *mesh, cg_error *err)
{
    if (!mesh->normals) {
        mesh->normals = malloc((size_t)mesh->vertex_count * 3 * sizeof(float) + 1);
        if (!mesh->normals)
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory for normals",
                           mesh->name);
    }
    double *sum = calloc((size_t)mesh->vertex_count * 3 + 1, sizeof(double));
    if (!sum)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory for normals",
                       mesh->name);
    /* The cross product's length is twice the triangle's area: summing it unnormalised
     * weights each face by its area. */
    for (uint32_t t = 0; t + 2 < mesh->index_count; t += 3) {
        uint32_t i[3] = { mesh->indices[t], mesh->indices[t + 1], mesh->indices[t + 2] };
        double n[3];
        triangle_cross(mesh->positions, i[0], i[1], i[2], n);
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++)
                sum[3 * (size_t)i[v] + k] += n[k];
    }
    for (uint32_t v = 0; v < mesh->vertex_count; v++) {
        double *s = sum + 3 * (size_t)v;
        double len = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        float *n = mesh->normals + 3 * (size_t)v;
        if (len > 0 && isfinite(len)) {
            n[0] = (float)(s[0] / len);
            n[1] = (float)(s[1] / len);
            n[2] = (float)(s[2] / len);
        } else {
            n[0] = 0, n[1] = 1, n[2] = 0;
        }
    }
    free(sum);
    return true;
}

/* Lengyel's per-triangle tangents ("Computing Tangent Space Basis Vectors for an Arbitrary
 * Mesh", 2001): for a triangle with edges e1, e2 and UV differences (du1, dv1), (du2, dv2),
 * T = dP/du = (e1 dv2 - e2 dv1) / det and B = dP/dv' = (e2 du1 - e1 du2) / det with
 * det = du1 dv2 - du2 dv1, accumulated unnormalised at the triangle's vertices (so larger
 * triangles weigh more), then T made orthogonal to the vertex normal (Gram-Schmidt) and
 * w = sign(dot(cross(N, T), B)).
 *
 * v' = -v: glTF's v grows downwards in the image, and its normal textures' +Y is the image's
 * up (glTF 2.0, 3.9.3), which is where bitangent = w cross(N, T) must point (3.7.2.1). A quad
 * laid out as an image (u right, v down) facing the viewer gets w = +1.
 *
 * glTF asks for MikkTSpace; Debian 12 packages no MikkTSpace library, so this is a departure.
 * It agrees with MikkTSpace inside a smooth UV chart; it differs (1) at UV seams and mirrored
 * halves: MikkTSpace splits a vertex's tangent by the faces' orientation and by angle, this
 * sums whatever the faces sharing the vertex give (a vertex shared by a mirrored and an
 * unmirrored face gets a tangent from their cancelling sum and one sign), and (2) in the
 * weighting (area here, angle in MikkTSpace). Baked normal maps from MikkTSpace tools then show
 * small shading errors at seams; a file's TANGENT attribute avoids that. */
bool
cg_mesh_generate_tangents(cg_mesh *mesh, cg_error *err)
{
    if (!mesh->normals)
        return cg_fail(err, CG_ERR_USAGE, "mesh '%s': tangents need normals", mesh->name);
    if (!mesh->tangents) {
        mesh->tangents = malloc((size_t)mesh->vertex_count * 4 * sizeof(float) + 1);
        if (!mesh->tangents)
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory for tangents", mesh->name);
    }
    double *sum = calloc((size_t)mesh->vertex_count * 6 + 1, sizeof(double));
    if (!sum)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory for tangents", mesh->name);
    const float *p = mesh->positions, *uv = mesh->texcoords;
    for (uint32_t t = 0; uv && t + 2 < mesh->index_count; t += 3) {
        uint32_t i[3] = { mesh->indices[t], mesh->indices[t + 1], mesh->indices[t + 2] };
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = (double)p[3 * i[1] + k] - p[3 * i[0] + k];
            e2[k] = (double)p[3 * i[2] + k] - p[3 * i[0] + k];
        }
        double du1 = (double)uv[2 * i[1]] - uv[2 * i[0]], dv1 = -((double)uv[2 * i[1] + 1] - uv[2 * i[0] + 1]);
        double du2 = (double)uv[2 * i[2]] - uv[2 * i[0]], dv2 = -((double)uv[2 * i[2] + 1] - uv[2 * i[0] + 1]);
        double det = du1 * dv2 - du2 * dv1;
        if (det == 0 || !isfinite(1 / det))
            continue; /* degenerate in UV: no direction to give */
        double r = 1 / det;
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++) {
                sum[6 * (size_t)i[v] + k] += (e1[k] * dv2 - e2[k] * dv1) * r;
                sum[6 * (size_t)i[v] + 3 + k] += (e2[k] * du1 - e1[k] * du2) * r;
            }
    }
    for (uint32_t v = 0; v < mesh->vertex_count; v++) {
        const float *n = mesh->normals + 3 * (size_t)v;
        double *s = sum + 6 * (size_t)v, *b = s + 3;
        double nd = n[0] * s[0] + n[1] * s[1] + n[2] * s[2];
        double x[3] = { s[0] - nd * n[0], s[1] - nd * n[1], s[2] - nd * n[2] };
        double len = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (!(len > 1e-12) || !isfinite(len)) {
            /* No UV direction: any unit vector perpendicular to the normal, from the axis the
             * normal is least aligned with. */
            double a[3] = { 0, 0, 0 };
            int k = fabs(n[0]) <= fabs(n[1]) && fabs(n[0]) <= fabs(n[2]) ? 0 : fabs(n[1]) <= fabs(n[2]) ? 1 : 2;
            a[k] = 1;
            nd = n[k];
            for (int c = 0; c < 3; c++)
                x[c] = a[c] - nd * n[c];
            len = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
            b[0] = b[1] = b[2] = 0;
        }
        float *out = mesh->tangents + 4 * (size_t)v;
        for (int c = 0; c < 3; c++)
            out[c] = (float)(x[c] / len);
        double cx = n[1] * x[2] - n[2] * x[1], cy = n[2] * x[0] - n[0] * x[2], cz = n[0] * x[1] - n[1] * x[0];
        out[3] = cx * b[0] + cy * b[1] + cz * b[2] < 0 ? -1.0f : 1.0f;
    }
    free(sum);
    return true;
}

bool
cg_scene_set_kind_source(cg_scene *scene, int mesh, cg_kind_source source, cg_error *err)
{
    if (scene->mesh_class_count < scene->mesh_count) {
        cg_mesh_class *bigger = realloc(scene->mesh_class, (size_t)scene->mesh_count * sizeof *bigger);
        if (!bigger)
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory", scene->name);
        memset(bigger + scene->mesh_class_count, 0,
               (size_t)(scene->mesh_count - scene->mesh_class_count) * sizeof *bigger);
        scene->mesh_class = bigger;
        scene->mesh_class_count = scene->mesh_count;
    }
    scene->mesh_class[mesh].source = source;
    return true;
}

/* ------------------------------------------------------------------ freeing */

void
cg_skinned_mesh_free(cg_skinned_mesh *sk)
{
    free(sk->joints);
    free(sk->weights);
    free(sk->bind_positions);
    free(sk->bind_normals);
    free(sk->bind_tangents);
    free(sk->joint_bounds);
    free(sk->posed_with);
    memset(sk, 0, sizeof *sk);
}

/* The skins and skinned meshes, and the morphed meshes. */
static void
free_skins(cg_scene *scene)
{
    for (int i = 0; i < scene->skin_count; i++) {
        free(scene->skins[i].joints);
        free(scene->skins[i].inverse_bind);
    }
    for (int i = 0; i < scene->skinned_count; i++)
        cg_skinned_mesh_free(&scene->skinned[i]);
    for (int i = 0; i < scene->morphed_count; i++)
        cg_morphed_mesh_free(&scene->morphed[i]);
    free(scene->skins);
    free(scene->skinned);
    free(scene->morphed);
    scene->skins = NULL;
    scene->skinned = NULL;
    scene->morphed = NULL;
    scene->skin_count = scene->skinned_count = scene->morphed_count = 0;
}

void
cg_morphed_mesh_free(cg_morphed_mesh *mm)
{
    free(mm->weights);
    free(mm->applied);
    free(mm->base_positions);
    free(mm->base_normals);
    free(mm->base_tangents);
    free(mm->position_deltas);
    free(mm->normal_deltas);
    free(mm->tangent_deltas);
    free(mm->delta_bounds);
    memset(mm, 0, sizeof *mm);
}

void
cg_scene_free(cg_scene *scene)
{
    if (!scene)
        return;
    for (int i = 0; i < scene->mesh_count; i++) {
        free(scene->meshes[i].positions);
        free(scene->meshes[i].normals);
        free(scene->meshes[i].texcoords);
        free(scene->meshes[i].tangents);
        free(scene->meshes[i].indices);
    }
    for (int i = 0; i < scene->texture_count; i++)
        free(scene->textures[i].rgba);
    free(scene->meshes);
    free(scene->instances);
    free(scene->materials);
    free(scene->textures);
    free(scene->lights);
    free(scene->cameras);
    free(scene->mesh_class);
    for (int a = 0; a < scene->animation_count; a++) {
        for (int c = 0; c < scene->animations[a].channel_count; c++) {
            free(scene->animations[a].channels[c].times);
            free(scene->animations[a].channels[c].values);
        }
        free(scene->animations[a].channels);
    }
    free(scene->animations);
    free(scene->nodes);
    free(scene->attachments);
    free_skins(scene);
    memset(scene, 0, sizeof *scene);
}
