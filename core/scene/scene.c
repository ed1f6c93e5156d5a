/* core/scene/scene.c: scene loading dispatch (file, built-in or DEM, with the classification
 * keys of the source's query), bounds, validation. The loaders build the scene through build.c,
 * which calls nothing back here; the height-field classification of meshes is classify.c's.
 */
#include "cg/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

static void
transform_point(const float m[16], const float p[3], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = (double)m[r] * p[0] + (double)m[4 + r] * p[1] + (double)m[8 + r] * p[2] + m[12 + r];
}

static bool
has_prefix(const char *s, const char *prefix)
{
    return strncmp(s, prefix, strlen(prefix)) == 0;
}

/* The classification keys of a source's query (cg/scene.h): parsed into *o and left out of
 * `rest` (the other "key=value" pairs, '&'-joined, for the loader; rest holds strlen(query) + 1). */
static bool
take_classify_keys(const char *source, const char *query, char *rest, cg_classify_options *o, cg_error *err)
{
    rest[0] = '\0';
    bool seen[4] = { false };
    for (const char *p = query; p && *p;) {
        const char *end = strchr(p, '&');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        char item[1100];
        if (len == 0)
            return cg_fail(err, CG_ERR_SCENE_PARAM, "%s: malformed parameter list (an empty item)", source);
        if (len >= sizeof item)
            return cg_fail(err, CG_ERR_SCENE_PARAM, "%s: parameter '%.40s...' too long", source, p);
        memcpy(item, p, len);
        item[len] = '\0';
        p = end ? end + 1 : p + len;
        static const char *const keys[4] = { "classify", "eq5_resolution", "eq5_threshold", "eq5_points" };
        char *eq = strchr(item, '=');
        int key = -1;
        for (int k = 0; eq && k < 4; k++)
            if ((size_t)(eq - item) == strlen(keys[k]) && !strncmp(item, keys[k], strlen(keys[k])))
                key = k;
        if (key < 0) {
            if (rest[0])
                strcat(rest, "&");
            strcat(rest, item);
            continue;
        }
        if (seen[key])
            return cg_fail(err, CG_ERR_SCENE_PARAM, "%s: parameter '%s' given twice", source, keys[key]);
        seen[key] = true;
        const char *v = eq + 1;
        char *tail = NULL;
        bool ok = true;
        if (key == 0) {
            ok = !strcmp(v, "eq5") || !strcmp(v, "normals");
            o->rule = !strcmp(v, "normals") ? CG_CLASSIFY_NORMALS : CG_CLASSIFY_EQ5;
        } else if (key == 1) {
            long n = strtol(v, &tail, 10);
            ok = v[0] && !*tail && n >= 2 && n <= CG_EQ5_MAX_RESOLUTION;
            o->resolution = (int)n;
        } else if (key == 2) {
            double t = strtod(v, &tail);
            ok = v[0] && !*tail && isfinite(t) && t > 0;
            o->threshold = t;
        } else {
            ok = !strcmp(v, "vertices") || !strcmp(v, "centroids");
            o->points = !strcmp(v, "centroids") ? CG_CLASSIFY_CENTROIDS : CG_CLASSIFY_VERTICES;
        }
        if (!ok) {
            static const char *const expected[4] = { "eq5 or normals", "an integer from 2 to 8192",
                                                     "a finite number > 0", "vertices or centroids" };
            return cg_fail(err, CG_ERR_SCENE_PARAM, "%s: %s=%s: expected %s", source, keys[key], v, expected[key]);
        }
    }
    return true;
}

static bool
is_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f)
        fclose(f);
    return f != NULL;
}

static bool
mark_all(cg_scene *scene, cg_kind_source source, cg_error *err)
{
    for (int m = 0; m < scene->mesh_count; m++)
        if (!cg_scene_set_kind_source(scene, m, source, err))
            return false;
    return true;
}

bool
cg_scene_load(const char *source, cg_scene *out, cg_error *err)
{
    memset(out, 0, sizeof *out);
    if (!source || !source[0])
        return cg_fail(err, CG_ERR_USAGE, "no scene given (a .gltf/.glb path, builtin:NAME or dem:IMAGE)");
    /* The query: after the '?' of a built-in or DEM source, or of a file name that is not itself
     * an existing file (so that a file whose name holds a '?' still loads). */
    const char *q = strchr(source, '?');
    bool builtin = has_prefix(source, "builtin:"), dem = has_prefix(source, "dem:");
    if (q && !builtin && !dem && is_file(source))
        q = NULL;
    size_t len = q ? (size_t)(q - source) : strlen(source);
    char *path = malloc(len + 1), *rest = malloc((q ? strlen(q) : 0) + 1);
    if (!path || !rest) {
        free(path);
        free(rest);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory loading '%s'", source);
    }
    memcpy(path, source, len);
    path[len] = '\0';
    cg_classify_options classify = { 0 };
    /* "loading NAME: 40%, 2.1 s, about 3.2 s left" when the load takes over 2 s (cg/progress.h). */
    char what[320];
    snprintf(what, sizeof what, "loading %s", source);
    cg_progress progress;
    cg_progress_begin(&progress, &(cg_progress_desc){ .what = what, .total = CG_LOAD_TOTAL });
    bool ok = take_classify_keys(source, q ? q + 1 : NULL, rest, &classify, err);
    if (ok && builtin) {
        ok = cg_builtin_scene_load(path + strlen("builtin:"), rest[0] ? rest : NULL, out, err) &&
             mark_all(out, CG_KIND_SCENE, err);
    } else if (ok && dem) {
        ok = cg_dem_load(path + strlen("dem:"), rest[0] ? rest : NULL, out, err);
    } else if (ok && rest[0]) {
        ok = cg_fail(err, CG_ERR_SCENE_PARAM, "%s: unknown parameter '%s' (a glTF file takes classify, "
                     "eq5_resolution, eq5_threshold, eq5_points)", source, rest);
    } else if (ok) {
        ok = cg_gltf_load(path, out, &progress, err);
    }
    free(path);
    free(rest);
    if (ok) {
        snprintf(out->name, sizeof out->name, "%s", source);
        out->classify = classify;
        ok = cg_scene_validate(out, err);
    }
    if (ok) {
        /* A loaded scene is posed at time 0 (before its first key: the first values). */
        cg_scene_evaluate(out, 0.0, NULL);
        out->revision = out->instances_revision = out->lights_revision = out->cameras_revision = 0;
        for (int i = 0; i < out->instance_count; i++)
            out->instances[i].revision = 0;
        for (int i = 0; i < out->mesh_count; i++)
            out->meshes[i].revision = 0;
        cg_scene_compute_bounds(out);
        /* Classified as posed at time 0; a moving instance makes its mesh complex (classify.c). */
        cg_progress_update(&progress, CG_LOAD_BUILT);
        ok = cg_scene_classify(out, &progress, err);
    }
    if (ok)
        cg_progress_end(&progress);
    if (!ok)
        cg_scene_free(out);
    return ok;
}

void
cg_scene_compute_bounds(cg_scene *scene)
{
    bool any = false;
    double lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
    /* The moving instances' boxes over the animation; without them (no instance moves, or no
     * memory for the sampling) every instance counts with its current box. */
    double mlo[3] = { INFINITY, INFINITY, INFINITY }, mhi[3] = { -INFINITY, -INFINITY, -INFINITY };
    bool animated = cg_scene_is_animated(scene) && cg_scene_motion_bounds(scene, mlo, mhi);
    for (int i = 0; i < scene->instance_count; i++) {
        cg_instance *inst = &scene->instances[i];
        if (inst->mesh < 0 || inst->mesh >= scene->mesh_count)
            continue;
        const cg_mesh *mesh = &scene->meshes[inst->mesh];
        if (mesh->vertex_count == 0 || (animated && inst->moving))
            continue;
        double ilo[3], ihi[3];
        for (int c = 0; c < 8; c++) {
            float corner[3] = { (c & 1) ? mesh->bounds_max[0] : mesh->bounds_min[0],
                                (c & 2) ? mesh->bounds_max[1] : mesh->bounds_min[1],
                                (c & 4) ? mesh->bounds_max[2] : mesh->bounds_min[2] };
            double w[3];
            transform_point(inst->world, corner, w);
            for (int k = 0; k < 3; k++) {
                if (!any || w[k] < lo[k]) lo[k] = w[k];
                if (!any || w[k] > hi[k]) hi[k] = w[k];
                if (c == 0 || w[k] < ilo[k]) ilo[k] = w[k];
                if (c == 0 || w[k] > ihi[k]) ihi[k] = w[k];
            }
            any = true;
        }
        for (int k = 0; k < 3; k++) {
            inst->motion_min[k] = (float)ilo[k];
            inst->motion_max[k] = (float)ihi[k];
        }
    }
    if (animated) {
        for (int k = 0; k < 3; k++) {
            lo[k] = any ? fmin(lo[k], mlo[k]) : mlo[k];
            hi[k] = any ? fmax(hi[k], mhi[k]) : mhi[k];
        }
    }
    for (int k = 0; k < 3; k++) {
        scene->bounds_min[k] = (float)lo[k];
        scene->bounds_max[k] = (float)hi[k];
    }
}

size_t
cg_scene_triangle_count(const cg_scene *scene)
{
    size_t n = 0;
    for (int i = 0; i < scene->instance_count; i++) {
        int m = scene->instances[i].mesh;
        if (m >= 0 && m < scene->mesh_count)
            n += scene->meshes[m].index_count / 3;
    }
    return n;
}

static bool
all_finite(const float *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return false;
    return true;
}

static bool
validate_mesh(const cg_scene *scene, int index, cg_error *err)
{
    const char *src = scene->name;
    const cg_mesh *m = &scene->meshes[index];
    if (m->index_count % 3 != 0)
        return cg_fail(err, CG_ERR_GLTF_ACCESSOR,
                       "%s: mesh %d '%s': %u indices is not a whole number of triangles", src,
                       index, m->name, m->index_count);
    if ((m->vertex_count && (!m->positions || !m->normals)) || (m->index_count && !m->indices))
        return cg_fail(err, CG_ERR_GLTF_ACCESSOR, "%s: mesh %d '%s': missing vertex data", src,
                       index, m->name);
    for (uint32_t i = 0; i < m->index_count; i++)
        if (m->indices[i] >= m->vertex_count)
            return cg_fail(err, CG_ERR_GLTF_INDEX_RANGE,
                           "%s: mesh %d '%s': index %u at position %u out of range (%u vertices)",
                           src, index, m->name, m->indices[i], i, m->vertex_count);
    for (uint32_t v = 0; v < m->vertex_count; v++)
        if (!all_finite(m->positions + 3 * (size_t)v, 3))
            return cg_fail(err, CG_ERR_GLTF_NONFINITE,
                           "%s: mesh %d '%s': vertex %u position is NaN or infinite", src, index,
                           m->name, v);
    if (!all_finite(m->normals, 3 * (size_t)m->vertex_count) ||
        (m->texcoords && !all_finite(m->texcoords, 2 * (size_t)m->vertex_count)))
        return cg_fail(err, CG_ERR_GLTF_NONFINITE,
                       "%s: mesh %d '%s': a normal or texture coordinate is NaN or infinite", src,
                       index, m->name);
    if (m->material < 0 || m->material >= scene->material_count)
        return cg_fail(err, CG_ERR_GLTF_INDEX_RANGE,
                       "%s: mesh %d '%s': material %d out of range (%d materials)", src, index,
                       m->name, m->material, scene->material_count);
    for (uint32_t v = 0; m->tangents && v < m->vertex_count; v++) {
        const float *t = m->tangents + 4 * (size_t)v;
        if (!all_finite(t, 4) || (t[3] != 1 && t[3] != -1))
            return cg_fail(err, CG_ERR_GLTF_NONFINITE,
                           "%s: mesh %d '%s': vertex %u tangent is NaN or infinite, or its w is not +-1", src,
                           index, m->name, v);
    }
    return true;
}

static bool
in_range(float x, float lo, float hi)
{
    return x >= lo && x <= hi;
}

static bool
validate_material(const cg_scene *scene, int index, cg_error *err)
{
    const cg_material *m = &scene->materials[index];
    bool uv_finite = true;
    for (int t = 0; t < CG_TEX_COUNT; t++)
        uv_finite = uv_finite && all_finite(m->uv[t].m, 6);
    if (!all_finite(m->base_color, 4) || !all_finite(m->emissive, 3) ||
        !isfinite(m->emissive_strength) || !isfinite(m->metallic) || !isfinite(m->roughness) ||
        !isfinite(m->normal_scale) || !isfinite(m->occlusion_strength) || !isfinite(m->alpha_cutoff) ||
        !isfinite(m->ior) || !isfinite(m->specular) || !all_finite(m->specular_color, 3) ||
        !isfinite(m->transmission) || !isfinite(m->thickness) || isnan(m->attenuation_distance) ||
        !all_finite(m->attenuation_color, 3) || !uv_finite)
        return cg_fail(err, CG_ERR_GLTF_NONFINITE, "%s: material %d '%s': a factor is NaN or infinite",
                       scene->name, index, m->name);
    /* The ranges the glTF schemas give (core and KHR_materials_*): factors in [0, 1] where they
     * are fractions, ior 0 (KHR_materials_ior: infinite) or >= 1, attenuation distance > 0. */
    const char *bad = NULL;
    if (!in_range(m->metallic, 0, 1) || !in_range(m->roughness, 0, 1))
        bad = "metallic and roughness must lie in [0, 1]";
    else if (!in_range(m->occlusion_strength, 0, 1))
        bad = "occlusion strength must lie in [0, 1]";
    else if (!in_range(m->transmission, 0, 1) || !in_range(m->specular, 0, 1))
        bad = "transmission and specular must lie in [0, 1]";
    else if (!(m->ior == 0 || m->ior >= 1))
        bad = "ior must be 0 (infinite) or at least 1";
    else if (m->alpha_cutoff < 0 || m->emissive_strength < 0 || m->thickness < 0 || m->specular_color[0] < 0 ||
             m->specular_color[1] < 0 || m->specular_color[2] < 0)
        bad = "alpha cutoff, emissive strength, thickness and specular colour must be >= 0";
    else if (!(m->attenuation_distance > 0) || !in_range(m->attenuation_color[0], 0, 1) ||
             !in_range(m->attenuation_color[1], 0, 1) || !in_range(m->attenuation_color[2], 0, 1))
        bad = "attenuation distance must be > 0 and the attenuation colour in [0, 1]";
    else if ((unsigned)m->alpha_mode > CG_ALPHA_BLEND)
        bad = "unknown alpha mode";
    if (bad)
        return cg_fail(err, CG_ERR_GLTF_SCHEMA, "%s: material %d '%s': %s", scene->name, index, m->name, bad);
    int tex[CG_TEX_COUNT] = { m->base_color_texture, m->emissive_texture, m->metallic_roughness_texture,
                              m->normal_texture, m->occlusion_texture, m->transmission_texture };
    for (int k = 0; k < CG_TEX_COUNT; k++)
        if (tex[k] < -1 || tex[k] >= scene->texture_count)
            return cg_fail(err, CG_ERR_GLTF_INDEX_RANGE,
                           "%s: material %d '%s': texture %d out of range (%d textures)",
                           scene->name, index, m->name, tex[k], scene->texture_count);
    return true;
}

static bool
validate_camera(const cg_scene *scene, int index, cg_error *err)
{
    const cg_camera *c = &scene->cameras[index];
    bool ok = all_finite(c->world, 16) && c->znear > 0 && c->aspect >= 0 && isfinite(c->aspect);
    if (c->type == CG_CAMERA_PERSPECTIVE)
        ok = ok && c->yfov > 0 && c->yfov < 3.14159f && (c->zfar == 0 || c->zfar > c->znear);
    else
        ok = ok && c->ymag > 0 && isfinite(c->ymag) && c->xmag >= 0 && c->zfar > c->znear;
    if (!ok || !isfinite(c->zfar))
        return cg_fail(err, CG_ERR_GLTF_PARSE,
                       "%s: camera %d '%s': needs finite values with znear > 0, zfar 0 or > znear, "
                       "0 < yfov < pi (perspective) or ymag > 0 (orthographic)",
                       scene->name, index, c->name);
    return true;
}

/* Nodes parents first, attachments and channels pointing at what exists, keys in order. */
static bool
validate_animation(const cg_scene *scene, cg_error *err)
{
    const char *src = scene->name;
    for (int i = 0; i < scene->node_count; i++) {
        const cg_node *n = &scene->nodes[i];
        if (n->parent < -1 || n->parent >= i)
            return cg_fail(err, CG_ERR_GLTF_INDEX_RANGE, "%s: node %d '%s': parent %d does not come before it",
                           src, i, n->name, n->parent);
        if (!all_finite(n->matrix, 16) || !all_finite(n->translation, 3) || !all_finite(n->rotation, 4) ||
            !all_finite(n->scale, 3))
            return cg_fail(err, CG_ERR_GLTF_NONFINITE, "%s: node %d '%s': a transform is NaN or infinite", src, i,
                           n->name);
    }
    static const char *const kinds[] = { "instance", "light", "camera" };
    for (int i = 0; i < scene->attachment_count; i++) {
        const cg_attachment *a = &scene->attachments[i];
        int count = a->kind == CG_ATTACH_INSTANCE ? scene->instance_count
                    : a->kind == CG_ATTACH_LIGHT  ? scene->light_count
                                                  : scene->camera_count;
        if ((unsigned)a->kind > CG_ATTACH_CAMERA || a->index < 0 || a->index >= count || a->node < 0 ||
            a->node >= scene->node_count)
            return cg_fail(err, CG_ERR_GLTF_INDEX_RANGE, "%s: attachment %d: %s %d on node %d out of range", src, i,
                           (unsigned)a->kind <= CG_ATTACH_CAMERA ? kinds[a->kind] : "element", a->index, a->node);
    }
    for (int a = 0; a < scene->animation_count; a++) {
        const cg_animation *anim = &scene->animations[a];
        for (int c = 0; c < anim->channel_count; c++) {
            const cg_anim_channel *ch = &anim->channels[c];
            if (ch->path == CG_ANIM_WEIGHTS && (ch->weight_count < 1 || ch->weight_count > CG_MAX_MORPH_TARGETS))
                return cg_fail(err, CG_ERR_GLTF_ACCESSOR, "%s: animation %d '%s' channel %d: %d weights per key "
                               "(1 to %d)", src, a, anim->name, c, ch->weight_count, CG_MAX_MORPH_TARGETS);
            if (ch->node < 0 || ch->node >= scene->node_count || (unsigned)ch->path > CG_ANIM_WEIGHTS ||
                (unsigned)ch->interpolation > CG_INTERP_CUBICSPLINE)
                return cg_fail(err, CG_ERR_GLTF_INDEX_RANGE, "%s: animation %d '%s' channel %d: node %d out of range",
                               src, a, anim->name, c, ch->node);
            if (scene->nodes[ch->node].has_matrix && ch->path != CG_ANIM_WEIGHTS)
                return cg_fail(err, CG_ERR_GLTF_SCHEMA,
                               "%s: animation %d '%s' channel %d animates node '%s', which has a matrix", src, a,
                               anim->name, c, scene->nodes[ch->node].name);
            int min_keys = ch->interpolation == CG_INTERP_CUBICSPLINE ? 2 : 1;
            if (ch->key_count < min_keys || !ch->times || !ch->values)
                return cg_fail(err, CG_ERR_GLTF_ACCESSOR, "%s: animation %d '%s' channel %d: %d keys (at least %d)",
                               src, a, anim->name, c, ch->key_count, min_keys);
            for (int k = 0; k < ch->key_count; k++)
                if (!isfinite(ch->times[k]) || ch->times[k] < 0 || (k > 0 && !(ch->times[k] > ch->times[k - 1])))
                    return cg_fail(err, CG_ERR_GLTF_ACCESSOR,
                                   "%s: animation %d '%s' channel %d: key time %d is %g; times must be finite, "
                                   ">= 0 and increasing", src, a, anim->name, c, k, ch->times[k]);
            if (!all_finite(ch->values, (size_t)ch->key_count * (size_t)cg_anim_channel_stride(ch)))
                return cg_fail(err, CG_ERR_GLTF_NONFINITE, "%s: animation %d '%s' channel %d: a value is NaN or infinite",
                               src, a, anim->name, c);
        }
    }
    return true;
}

/* Skins' joints on nodes that exist, skinned meshes on their own instance, joint indices in
 * range, weights finite and >= 0. */
static bool
validate_skins(const cg_scene *scene, cg_error *err)
{
    const char *src = scene->name;
    for (int i = 0; i < scene->skin_count; i++) {
        const cg_skin *s = &scene->skins[i];
        if (s->joint_count < 1 || !s->joints || !s->inverse_bind)
            return cg_fail(err, CG_ERR_GLTF_SCHEMA, "%s: skin %d '%s' has no joints", src, i, s->name);
        for (int j = 0; j < s->joint_count; j++)
            if (s->joints[j] < 0 || s->joints[j] >= scene->node_count)
                return cg_fail(err, CG_ERR_GLTF_INDEX_RANGE, "%s: skin %d '%s': joint %d is node %d, out of range",
                               src, i, s->name, j, s->joints[j]);
        if (!all_finite(s->inverse_bind, 16 * (size_t)s->joint_count))
            return cg_fail(err, CG_ERR_GLTF_NONFINITE, "%s: skin %d '%s': an inverse bind matrix is NaN or infinite",
                           src, i, s->name);
    }
    for (int i = 0; i < scene->skinned_count; i++) {
        const cg_skinned_mesh *k = &scene->skinned[i];
        if (k->skin < 0 || k->skin >= scene->skin_count || k->mesh < 0 || k->mesh >= scene->mesh_count ||
            k->instance < 0 || k->instance >= scene->instance_count || scene->instances[k->instance].mesh != k->mesh ||
            k->influences < 1 || !k->joints || !k->weights)
            return cg_fail(err, CG_ERR_GLTF_INDEX_RANGE, "%s: skinned mesh %d: skin %d, mesh %d or instance %d out "
                           "of range", src, i, k->skin, k->mesh, k->instance);
        size_t n = (size_t)scene->meshes[k->mesh].vertex_count * (size_t)k->influences;
        for (size_t v = 0; v < n; v++)
            if (k->joints[v] >= scene->skins[k->skin].joint_count || !isfinite(k->weights[v]) || k->weights[v] < 0)
                return cg_fail(err, CG_ERR_GLTF_ACCESSOR, "%s: skinned mesh '%s': vertex %zu weighs joint %u by %g "
                               "(joints below %d, weights finite and >= 0)", src, scene->meshes[k->mesh].name,
                               v / (size_t)k->influences, (unsigned)k->joints[v], k->weights[v],
                               scene->skins[k->skin].joint_count);
    }
    for (int i = 0; i < scene->morphed_count; i++) {
        const cg_morphed_mesh *m = &scene->morphed[i];
        if (m->mesh < 0 || m->mesh >= scene->mesh_count || m->instance < 0 || m->instance >= scene->instance_count ||
            scene->instances[m->instance].mesh != m->mesh || m->node < -1 || m->node >= scene->node_count ||
            m->target_count < 1 || m->target_count > CG_MAX_MORPH_TARGETS || !m->weights)
            return cg_fail(err, CG_ERR_GLTF_INDEX_RANGE, "%s: morphed mesh %d: mesh %d, instance %d, node %d or "
                           "%d targets out of range", src, i, m->mesh, m->instance, m->node, m->target_count);
        size_t n = (size_t)scene->meshes[m->mesh].vertex_count * 3 * (size_t)m->target_count;
        if (!all_finite(m->weights, (size_t)m->target_count) || (m->position_deltas && !all_finite(m->position_deltas, n)) ||
            (m->normal_deltas && !all_finite(m->normal_deltas, n)) || (m->tangent_deltas && !all_finite(m->tangent_deltas, n)))
            return cg_fail(err, CG_ERR_GLTF_NONFINITE, "%s: morphed mesh '%s': a weight or displacement is NaN or "
                           "infinite", src, scene->meshes[m->mesh].name);
    }
    return true;
}

bool
cg_scene_validate(const cg_scene *scene, cg_error *err)
{
    if (!validate_animation(scene, err) || !validate_skins(scene, err))
        return false;
    if (scene->material_count < 1)
        return cg_fail(err, CG_ERR_GLTF_PARSE, "%s: scene has no default material", scene->name);
    for (int i = 0; i < scene->material_count; i++)
        if (!validate_material(scene, i, err))
            return false;
    for (int i = 0; i < scene->texture_count; i++) {
        const cg_texture *t = &scene->textures[i];
        if (t->width <= 0 || t->height <= 0 || !t->rgba)
            return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: texture %d '%s': no pixels (%dx%d)",
                           scene->name, i, t->name, t->width, t->height);
    }
    for (int i = 0; i < scene->mesh_count; i++)
        if (!validate_mesh(scene, i, err))
            return false;
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_instance *inst = &scene->instances[i];
        if (inst->mesh < 0 || inst->mesh >= scene->mesh_count)
            return cg_fail(err, CG_ERR_GLTF_INDEX_RANGE,
                           "%s: instance %d: mesh %d out of range (%d meshes)", scene->name, i,
                           inst->mesh, scene->mesh_count);
        if (!all_finite(inst->world, 16))
            return cg_fail(err, CG_ERR_GLTF_NONFINITE,
                           "%s: instance %d (mesh '%s'): world transform is NaN or infinite",
                           scene->name, i, scene->meshes[inst->mesh].name);
    }
    for (int i = 0; i < scene->light_count; i++) {
        const cg_light *l = &scene->lights[i];
        bool ok = all_finite(l->color, 3) && isfinite(l->intensity) && l->intensity >= 0 &&
                  all_finite(l->position, 3) && all_finite(l->direction, 3) &&
                  isfinite(l->range) && l->range >= 0 && l->angular_diameter >= 0 &&
                  l->angular_diameter <= 1.5707964f && (l->type == CG_LIGHT_DIRECTIONAL || l->angular_diameter == 0);
        if (l->type == CG_LIGHT_SPOT)
            ok = ok && l->inner_cone_angle >= 0 && l->inner_cone_angle < l->outer_cone_angle &&
                 l->outer_cone_angle <= 1.5707964f;
        if (!ok)
            return cg_fail(err, CG_ERR_GLTF_PARSE,
                           "%s: light %d '%s': needs finite values, intensity >= 0, range >= 0, "
                           "for a spot 0 <= inner < outer <= pi/2, and an angular diameter in [0, pi/2] "
                           "(directional lights only)",
                           scene->name, i, l->name);
    }
    for (int i = 0; i < scene->camera_count; i++)
        if (!validate_camera(scene, i, err))
            return false;
    if (cg_scene_triangle_count(scene) == 0)
        return cg_fail(err, CG_ERR_GLTF_NO_TRIANGLES, "%s: scene has no triangles", scene->name);
    return true;
}
