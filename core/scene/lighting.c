/* core/scene/lighting.c: whether anything lights a scene, the default light for one that
 * nothing lights, and a sky written back as text.
 *
 * Most glTF files carry no light (KHR_lights_punctual is an extension few exporters write),
 * and a scene without one renders black. The default light is a sun and a sky:
 *
 * - The sun: a directional light of irradiance 3 W/m^2, white, from 55 degrees above the
 *   horizon and 30 degrees from +z towards +x (the unit vector towards it is
 *   (cos 55 sin 30, sin 55, cos 55 cos 30) = (0.287, 0.819, 0.497); it travels the other
 *   way). Why these: glTF is y up and its models face +z (its default camera looks down -z),
 *   and the automatic framing looks from (1, 0.6, 1), so the faces these views see are lit,
 *   each by a different cosine (+y 0.82, +z 0.50, +x 0.29): a box shows three shades, not
 *   one. 3 W/m^2 puts a white surface facing the sun at radiance 3/pi = 0.95, just below 1,
 *   bright and unclipped under the graphs' default exposure (0 EV) and tonemap; it is the
 *   irradiance of builtin:openworld's sun. It is not physical daylight (about 1000 W/m^2):
 *   scale the exposure, not the light, for that.
 * - The sky: uniform, radiance 0.2 W/(m^2 sr) in every channel from the whole sphere. An
 *   unoccluded surface receives pi x 0.2 = 0.63 W/m^2 from it, a sixth of the total on a
 *   surface facing the sun: shadows stay readable and albedo colours show without a tint.
 *   Uniform rather than Preetham's daylight: every method reproduces a constant radiance
 *   exactly (it is a visibility integral), it tints nothing, and it has no absolute scale to
 *   match with the sun (Preetham's luminance is in kcd/m^2).
 * A scene is lit when it has a light, a sky that is not black, or emissive surfaces bright and
 * large enough to light it: their radiance times their area over the area of every surface,
 * the mean radiance of a white surface that all their light reached (a Lambertian emitter of
 * radiance L and area A sends pi L A per side; spread over both sides of area A_all, each
 * receives E = pi L A / A_all, reflected as E / pi), at least CG_EMITTERS_MIN_LIGHT, 1% of a
 * white surface facing the default sun (3/pi W/(m^2 sr)). A third-party model whose emissive
 * labels or LEDs cover a speck of it (ClearCoatTest: 0.0004) is not lit by them: it gets the
 * default light, and says so. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "cg/scene.h"
#include "scene_internal.h"

/* A mesh that some instance places in the world, with a material that emits. */
static bool
emits(const cg_scene *scene)
{
    for (int i = 0; i < scene->instance_count; i++) {
        int mesh = scene->instances[i].mesh;
        if (mesh < 0 || mesh >= scene->mesh_count || scene->meshes[mesh].index_count == 0)
            continue;
        int material = scene->meshes[mesh].material;
        if (material < 0 || material >= scene->material_count)
            continue;
        const cg_material *m = &scene->materials[material];
        for (int c = 0; c < 3; c++)
            if (m->emissive[c] * m->emissive_strength > 0.0f)
                return true;
    }
    return false;
}

/* Area of a mesh's triangles placed by an instance's world matrix (column-major). */
static double
instance_area(const cg_mesh *mesh, const float *w)
{
    double area = 0.0;
    for (uint32_t t = 0; t + 2 < mesh->index_count; t += 3) {
        double p[3][3];
        for (int k = 0; k < 3; k++) {
            const float *v = &mesh->positions[3 * (size_t)mesh->indices[t + (uint32_t)k]];
            for (int r = 0; r < 3; r++)
                p[k][r] = (double)w[r] * v[0] + (double)w[4 + r] * v[1] + (double)w[8 + r] * v[2] + w[12 + r];
        }
        double e1[3], e2[3];
        for (int r = 0; r < 3; r++) {
            e1[r] = p[1][r] - p[0][r];
            e2[r] = p[2][r] - p[0][r];
        }
        double c[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0] };
        area += 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    return area;
}

double
cg_scene_emitted_light(const cg_scene *scene)
{
    double emitted = 0.0, total = 0.0;
    for (int i = 0; i < scene->instance_count; i++) {
        int mesh = scene->instances[i].mesh;
        if (mesh < 0 || mesh >= scene->mesh_count)
            continue;
        const cg_mesh *m = &scene->meshes[mesh];
        double area = instance_area(m, scene->instances[i].world);
        total += area;
        int material = m->material;
        if (material < 0 || material >= scene->material_count)
            continue;
        const cg_material *mat = &scene->materials[material];
        /* The factor bounds the textured radiance (a texel is at most 1). */
        double mean = ((double)mat->emissive[0] + mat->emissive[1] + mat->emissive[2]) / 3.0 * mat->emissive_strength;
        emitted += mean > 0.0 ? mean * area : 0.0;
    }
    return total > 0.0 ? emitted / total : 0.0;
}

bool
cg_sky_is_black(const cg_sky *sky)
{
    if (sky->type == CG_SKY_UNIFORM)
        return !(sky->radiance[0] > 0.0f || sky->radiance[1] > 0.0f || sky->radiance[2] > 0.0f);
    if (sky->type == CG_SKY_PREETHAM)
        return !(sky->scale > 0.0f);
    return true;
}

bool
cg_scene_is_lit(const cg_scene *scene)
{
    return scene->light_count > 0 || !cg_sky_is_black(&scene->sky) ||
           (emits(scene) && cg_scene_emitted_light(scene) >= CG_EMITTERS_MIN_LIGHT);
}

bool
cg_scene_emits(const cg_scene *scene)
{
    return emits(scene);
}

bool
cg_material_has_lobes(const cg_material *m)
{
    return m->metallic > 0.0f || m->specular > 0.0f || m->transmission > 0.0f || m->alpha_mode == CG_ALPHA_BLEND;
}

bool
cg_scene_has_lobes(const cg_scene *scene)
{
    for (int i = 0; i < scene->instance_count; i++) {
        int mesh = scene->instances[i].mesh;
        if (mesh < 0 || mesh >= scene->mesh_count)
            continue;
        int material = scene->meshes[mesh].material;
        if (material >= 0 && material < scene->material_count && cg_material_has_lobes(&scene->materials[material]))
            return true;
    }
    return false;
}

void
cg_default_sun(cg_light *out)
{
    memset(out, 0, sizeof *out);
    cg_copy_name(out->name, CG_DEFAULT_SUN_NAME);
    out->type = CG_LIGHT_DIRECTIONAL;
    out->color[0] = out->color[1] = out->color[2] = 1.0f;
    out->intensity = CG_DEFAULT_SUN_IRRADIANCE;
    const double elevation = CG_DEFAULT_SUN_ELEVATION_DEG * 3.14159265358979323846 / 180.0;
    const double azimuth = CG_DEFAULT_SUN_AZIMUTH_DEG * 3.14159265358979323846 / 180.0;
    /* The light travels away from the sun. */
    out->direction[0] = (float)(-cos(elevation) * sin(azimuth));
    out->direction[1] = (float)(-sin(elevation));
    out->direction[2] = (float)(-cos(elevation) * cos(azimuth));
}

void
cg_default_sky(cg_sky *out)
{
    memset(out, 0, sizeof *out);
    out->type = CG_SKY_UNIFORM;
    out->radiance[0] = out->radiance[1] = out->radiance[2] = CG_DEFAULT_SKY_RADIANCE;
}

bool
cg_scene_add_default_sun(cg_scene *scene, cg_error *err)
{
    cg_light sun;
    cg_default_sun(&sun);
    return cg_scene_add_light(scene, &sun, err) >= 0;
}

void
cg_sky_format(const cg_sky *sky, char *out, size_t size)
{
    switch (sky->type) {
    case CG_SKY_UNIFORM:
        if (sky->radiance[0] == sky->radiance[1] && sky->radiance[1] == sky->radiance[2])
            snprintf(out, size, "%g", (double)sky->radiance[0]);
        else
            snprintf(out, size, "%g,%g,%g", (double)sky->radiance[0], (double)sky->radiance[1],
                     (double)sky->radiance[2]);
        break;
    case CG_SKY_PREETHAM:
        snprintf(out, size, "preetham:%g,%g", (double)sky->turbidity, (double)sky->scale);
        break;
    default:
        snprintf(out, size, "none");
        break;
    }
}

bool
cg_sky_equal(const cg_sky *a, const cg_sky *b)
{
    if (a->type != b->type)
        return false;
    if (a->type == CG_SKY_UNIFORM)
        return !memcmp(a->radiance, b->radiance, sizeof a->radiance);
    if (a->type == CG_SKY_PREETHAM)
        return a->turbidity == b->turbidity && a->scale == b->scale;
    return true;
}
