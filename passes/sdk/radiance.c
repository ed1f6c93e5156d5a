/* Radiance bounds and half-float pre-exposure (sdk/radiance.h). */
#include "sdk/radiance.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sdk/scene.h"

/* Squared distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5). */
static double
point_triangle_dist2(const double p[3], const double a[3], const double b[3], const double c[3])
{
    double ab[3], ac[3], ap[3], q[3];
    for (int k = 0; k < 3; k++)
        ab[k] = b[k] - a[k], ac[k] = c[k] - a[k], ap[k] = p[k] - a[k];
#define DOT(u, v) ((u)[0] * (v)[0] + (u)[1] * (v)[1] + (u)[2] * (v)[2])
    double d1 = DOT(ab, ap), d2 = DOT(ac, ap);
    double bp[3], cp[3];
    for (int k = 0; k < 3; k++)
        bp[k] = p[k] - b[k], cp[k] = p[k] - c[k];
    double d3 = DOT(ab, bp), d4 = DOT(ac, bp), d5 = DOT(ab, cp), d6 = DOT(ac, cp);
    double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
#undef DOT
    if (d1 <= 0 && d2 <= 0) {
        memcpy(q, a, sizeof q);
    } else if (d3 >= 0 && d4 <= d3) {
        memcpy(q, b, sizeof q);
    } else if (d6 >= 0 && d5 <= d6) {
        memcpy(q, c, sizeof q);
    } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        double v = d1 / (d1 - d3);
        for (int k = 0; k < 3; k++) q[k] = a[k] + v * ab[k];
    } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        double w = d2 / (d2 - d6);
        for (int k = 0; k < 3; k++) q[k] = a[k] + w * ac[k];
    } else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (int k = 0; k < 3; k++) q[k] = b[k] + w * (c[k] - b[k]);
    } else {
        double denom = 1.0 / (va + vb + vc);
        double v = vb * denom, w = vc * denom;
        for (int k = 0; k < 3; k++) q[k] = a[k] + ab[k] * v + ac[k] * w;
    }
    double d2sum = 0;
    for (int k = 0; k < 3; k++)
        d2sum += (p[k] - q[k]) * (p[k] - q[k]);
    return d2sum;
}

/* Distance from a point light to the nearest surface the filter keeps. */
static double
nearest_surface(const cg_scene *scene, cg_mesh_filter filter, const float light[3])
{
    double p[3] = {light[0], light[1], light[2]}, best = DBL_MAX;
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_instance *inst = &scene->instances[i];
        const cg_mesh *mesh = &scene->meshes[inst->mesh];
        if (!cgp_mesh_passes(mesh->kind, filter))
            continue;
        for (uint32_t t = 0; t + 2 < mesh->index_count; t += 3) {
            double v[3][3];
            for (int j = 0; j < 3; j++)
                cgp_transform_point(inst->world, &mesh->positions[3 * mesh->indices[t + j]], v[j]);
            double d2 = point_triangle_dist2(p, v[0], v[1], v[2]);
            if (d2 < best)
                best = d2;
        }
    }
    return sqrt(best);
}

bool
cgp_radiance_bound(cgp_light_distances *cache, const cg_scene *scene, cg_mesh_filter filter, double min_distance,
                   double *bound, cg_error *err)
{
    double emission = 0.0, albedo = 0.0;
    for (int m = 0; m < scene->material_count; m++) {
        const cg_material *mat = &scene->materials[m];
        for (int k = 0; k < 3; k++) {
            emission = fmax(emission, (double)mat->emissive[k] * mat->emissive_strength);
            albedo = fmax(albedo, mat->base_color[k]);
        }
    }
    if (cache->count != scene->light_count || cache->revision != scene->instances_revision) {
        cgp_light_distances_free(cache);
        cache->positions = calloc((size_t)scene->light_count * 3 + 1, sizeof(float));
        cache->nearest = calloc((size_t)scene->light_count + 1, sizeof(double));
        if (!cache->positions || !cache->nearest)
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "radiance bound: light cache of %d lights", scene->light_count);
        for (int l = 0; l < scene->light_count; l++)
            cache->nearest[l] = -1.0;
        cache->count = scene->light_count;
        cache->revision = scene->instances_revision;
    }
    double irradiance = 0.0;
    for (int l = 0; l < scene->light_count; l++) {
        const cg_light *light = &scene->lights[l];
        double e = light->intensity * fmax(light->color[0], fmax(light->color[1], light->color[2]));
        if (light->type != CG_LIGHT_DIRECTIONAL) {
            float *cached = &cache->positions[3 * l];
            if (cache->nearest[l] < 0.0 || memcmp(cached, light->position, 3 * sizeof(float)) != 0) {
                memcpy(cached, light->position, 3 * sizeof(float));
                cache->nearest[l] = nearest_surface(scene, filter, light->position);
            }
            double d = fmax(cache->nearest[l], min_distance);
            e /= d * d;
        }
        irradiance += e;
    }
    *bound = emission + albedo * irradiance / M_PI;
    return true;
}

void
cgp_light_distances_free(cgp_light_distances *cache)
{
    free(cache->positions);
    free(cache->nearest);
    memset(cache, 0, sizeof *cache);
}

double
cgp_half_float_scale(double bound)
{
    if (!(bound > 0.0) || !isfinite(bound))
        return 1.0;
    return fmax(bound / CGP_HALF_TOP, FLT_MIN);
}
