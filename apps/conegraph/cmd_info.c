/* conegraph info: what a scene holds, and with --gl what GL context it would render with. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "app_session.h"
#include "cg/error.h"
#include "cg/gl.h"
#include "cg/scene.h"
#include "app_common.h"
#include "commands.h"

void
cmd_info_usage(FILE *out)
{
    fprintf(out,
            "usage: conegraph info SCENE [--gl] [--context egl|osmesa|glfw|auto] [--sky SKY]\n"
            "                            [--no-default-light]\n"
            "\n"
            "Loads SCENE and prints its meshes (with their kind: heightfield or complex, who set\n"
            "it, what eq. 5 of the hybrid cone tracing paper and the normal rule say, and eq. 5's\n"
            "height-field distance d), triangles, materials, textures, lights, cameras, sky and world bounds, lit as render\n"
            "lights it: a scene with no light, no emissive surface and no sky is given the default\n"
            "light (a sun and a sky: a notice on stderr, the lights marked \"added\").\n"
            "\n"
            "SCENE is a .gltf or .glb file, dem:IMAGE[?key=value&...] (a terrain from an elevation\n"
            "image, docs/scenes.md) or builtin:NAME[?key=value&...]:\n");
    for (const char *const *n = cg_scene_builtin_names(); *n; n++)
        fprintf(out, "  builtin:%s\n      %s\n", *n, cg_scene_builtin_doc(*n));
    fprintf(out,
            "\n"
            "Every SCENE takes the classification keys (after '?', '&' between them):\n"
            "  classify=eq5|normals    eq. 5 (default) or every triangle facing up\n"
            "  eq5_resolution=N        samples along the box's longer side (default %d)\n"
            "  eq5_threshold=T         a height field when d < T (default %g)\n"
            "  eq5_points=vertices|centroids   eq. 5's points (default vertices)\n"
            "A glTF mesh's extras \"conegraph_kind\": \"heightfield\" or \"complex\" set its kind.\n",
            CG_EQ5_DEFAULT_RESOLUTION, CG_EQ5_DEFAULT_THRESHOLD);
    fprintf(out,
            "\n"
            "options:\n"
            "  --gl             also create a GL 4.5 core context and print its version and renderer\n"
            "  --context NAME   create the context with this backend (implies --gl; without it:\n"
            "                   CONEGRAPH_CONTEXT, else egl then osmesa)\n"
            "  --sky SKY        the sky, as render --sky takes it\n"
            "  --no-default-light  list the scene as it is, unlit when nothing lights it\n"
            "  -h, --help       this help\n"
            "\n"
            "Exit codes: 0 done, 1 failed while running (no GL context), 2 bad scene or usage.\n");
}

static const char *
light_type_name(cg_light_type t)
{
    return t == CG_LIGHT_DIRECTIONAL ? "directional" : t == CG_LIGHT_POINT ? "point" : "spot";
}

static const char *
kind_name(cg_mesh_kind kind)
{
    return kind == CG_MESH_HEIGHTFIELD ? "heightfield" : "complex";
}

/* The kind of mesh i, who set it, eq. 5's d (computed again here, for every mesh: also where
 * the kind was given or the normal rule decided, and so that the time of eq. 5 is measured) and
 * the normal rule's verdict. */
static bool
print_class(const cg_scene *s, int i, double *eq5_ms, cg_error *err)
{
    const cg_mesh *m = &s->meshes[i];
    cg_mesh_class c = { .kind = m->kind, .source = CG_KIND_CLASSIFIED, .distance = NAN, .max_distance = NAN };
    if (i < s->mesh_class_count)
        c = s->mesh_class[i];
    static const char *const sources[] = { "classified", "glTF extras", "set by the scene" };
    printf("%s (%s", kind_name(m->kind), sources[c.source]);
    cg_mesh_class eq5;
    cg_classify_options o = s->classify;
    o.rule = CG_CLASSIFY_EQ5;
    double t0 = app_now_ms();
    if (!cg_mesh_classify(s, i, &o, &eq5, err))
        return false;
    *eq5_ms += app_now_ms() - t0;
    if (c.source != CG_KIND_CLASSIFIED || s->classify.rule != CG_CLASSIFY_EQ5)
        printf("; eq. 5: %s", kind_name(eq5.kind));
    printf("; normals: %s) d=%.3g max %.3g",
           kind_name(eq5.instances && eq5.normals_up ? CG_MESH_HEIGHTFIELD : CG_MESH_COMPLEX), eq5.distance,
           eq5.max_distance);
    return true;
}

static bool
print_scene(const cg_scene *s, int file_lights, cg_error *err)
{
    printf("scene %s\n", s->name);
    printf("triangles %zu (%d meshes, %d instances)\n", cg_scene_triangle_count(s), s->mesh_count,
           s->instance_count);
    printf("bounds [%g %g %g] .. [%g %g %g] m\n", s->bounds_min[0], s->bounds_min[1], s->bounds_min[2],
           s->bounds_max[0], s->bounds_max[1], s->bounds_max[2]);
    cg_classify_options o;
    cg_classify_defaults(&o, &s->classify);
    printf("classification %s: eq. 5 resolution %d, threshold %g, %s, %d threads\n",
           o.rule == CG_CLASSIFY_EQ5 ? "eq5" : "normals", o.resolution, o.threshold,
           o.points == CG_CLASSIFY_CENTROIDS ? "centroids" : "vertices", o.threads);
    printf("meshes %d\n", s->mesh_count);
    double eq5_ms = 0;
    for (int i = 0; i < s->mesh_count; i++) {
        const cg_mesh *m = &s->meshes[i];
        int instances = 0;
        for (int k = 0; k < s->instance_count; k++)
            instances += s->instances[k].mesh == i;
        printf("  %d '%s' ", i, m->name);
        if (!print_class(s, i, &eq5_ms, err))
            return false;
        printf(": %u triangles, %u vertices, material %d, %d instance%s%s%s\n", m->index_count / 3,
               m->vertex_count, m->material, instances, instances == 1 ? "" : "s",
               m->texcoords ? ", texcoords" : "", m->tangents ? ", tangents" : "");
    }
    printf("eq. 5 over the %d meshes: %.0f ms\n", s->mesh_count, eq5_ms);
    printf("materials %d\n", s->material_count);
    for (int i = 0; i < s->material_count; i++) {
        const cg_material *m = &s->materials[i];
        printf("  %d '%s' base [%g %g %g %g] tex %d, emissive [%g %g %g] x %g tex %d, metallic %g "
               "roughness %g\n",
               i, m->name, m->base_color[0], m->base_color[1], m->base_color[2], m->base_color[3],
               m->base_color_texture, m->emissive[0], m->emissive[1], m->emissive[2],
               m->emissive_strength, m->emissive_texture, m->metallic, m->roughness);
        static const char *const modes[] = { "OPAQUE", "MASK", "BLEND" };
        printf("      metallicRoughness tex %d, normal tex %d x %g, occlusion tex %d x %g, alpha %s",
               m->metallic_roughness_texture, m->normal_texture, m->normal_scale, m->occlusion_texture,
               m->occlusion_strength, (unsigned)m->alpha_mode <= CG_ALPHA_BLEND ? modes[m->alpha_mode] : "?");
        if (m->alpha_mode == CG_ALPHA_MASK)
            printf(" cutoff %g", m->alpha_cutoff);
        printf(", %s\n", m->double_sided ? "double-sided" : "single-sided");
        printf("      ior %g, specular %g [%g %g %g], transmission %g tex %d, thickness %g, attenuation %g m "
               "[%g %g %g]\n",
               m->ior, m->specular, m->specular_color[0], m->specular_color[1], m->specular_color[2],
               m->transmission, m->transmission_texture, m->thickness, m->attenuation_distance,
               m->attenuation_color[0], m->attenuation_color[1], m->attenuation_color[2]);
        /* KHR_texture_transform of each texture that is not the identity (cg/scene.h's matrix). */
        static const char *const slots[CG_TEX_COUNT] = { "baseColor", "emissive", "metallicRoughness",
                                                         "normal", "occlusion", "transmission" };
        for (int t = 0; t < CG_TEX_COUNT; t++) {
            const float *u = m->uv[t].m;
            if (u[0] != 1 || u[1] != 0 || u[2] != 0 || u[3] != 1 || u[4] != 0 || u[5] != 0)
                printf("      %s uv' = [%g %g] u + [%g %g] v + [%g %g]\n", slots[t], u[0], u[1], u[2], u[3],
                       u[4], u[5]);
        }
    }
    printf("textures %d\n", s->texture_count);
    for (int i = 0; i < s->texture_count; i++)
        printf("  %d '%s' %dx%d %s\n", i, s->textures[i].name, s->textures[i].width,
               s->textures[i].height, s->textures[i].srgb ? "sRGB" : "linear");
    printf("lights %d\n", s->light_count);
    for (int i = 0; i < s->light_count; i++) {
        const cg_light *l = &s->lights[i];
        printf("  %d '%s' %s%s: color [%g %g %g] intensity %g", i, l->name, light_type_name(l->type),
               i >= file_lights ? " (added: the default light)" : "", l->color[0], l->color[1], l->color[2],
               l->intensity);
        if (l->type != CG_LIGHT_DIRECTIONAL)
            printf(" position [%g %g %g]", l->position[0], l->position[1], l->position[2]);
        if (l->type != CG_LIGHT_POINT)
            printf(" direction [%g %g %g]", l->direction[0], l->direction[1], l->direction[2]);
        if (l->type == CG_LIGHT_SPOT)
            printf(" cone %g..%g rad", l->inner_cone_angle, l->outer_cone_angle);
        if (l->range > 0)
            printf(" range %g", l->range);
        if (l->angular_diameter > 0)
            printf(" angular diameter %g rad", l->angular_diameter);
        printf("\n");
    }
    char sky[128];
    cg_sky_format(&s->sky, sky, sizeof sky);
    printf("sky %s%s\n", sky,
           s->sky.type == CG_SKY_UNIFORM    ? " (uniform, W/(m^2 sr))"
           : s->sky.type == CG_SKY_PREETHAM ? " (Preetham: turbidity, scale)"
                                            : "");
    printf("cameras %d%s\n", s->camera_count,
           s->camera_count ? "" : " (views are framed from the bounds)");
    for (int i = 0; i < s->camera_count; i++) {
        const cg_camera *c = &s->cameras[i];
        printf("  %d '%s' ", i, c->name);
        if (c->type == CG_CAMERA_PERSPECTIVE)
        {
            char aspect[32] = "of the image";
            if (c->aspect > 0)
                snprintf(aspect, sizeof aspect, "%g", c->aspect);
            printf("perspective: yfov %g rad, aspect %s%s, znear %g, zfar %g%s", c->yfov, aspect,
                   c->aspect > 0 ? " (an image of another aspect widens the field of view, no stretch)" : "",
                   c->znear, c->zfar, c->zfar > 0 ? "" : " (finite far from the bounds)");
        }
        else
            printf("orthographic: xmag %g ymag %g, znear %g, zfar %g", c->xmag, c->ymag, c->znear,
                   c->zfar);
        printf(", at [%g %g %g] looking along [%g %g %g]\n", c->world[12], c->world[13], c->world[14],
               -c->world[8], -c->world[9], -c->world[10]);
    }
    int channels = 0, moving = 0;
    for (int a = 0; a < s->animation_count; a++)
        channels += s->animations[a].channel_count;
    for (int i = 0; i < s->instance_count; i++)
        moving += s->instances[i].moving;
    double start, end;
    cg_scene_animation_range(s, &start, &end);
    printf("animations %d", s->animation_count);
    if (s->animation_count)
        printf(" (%d channels on %d nodes, keys from %g to %g s; %d moving instances; bounds over the whole "
               "animation)", channels, s->node_count, start, end, moving);
    printf("\n");
    static const char *const paths[] = { "translation", "rotation", "scale" };
    static const char *const modes[] = { "LINEAR", "STEP", "CUBICSPLINE" };
    for (int a = 0; a < s->animation_count; a++)
        for (int c = 0; c < s->animations[a].channel_count; c++) {
            const cg_anim_channel *ch = &s->animations[a].channels[c];
            printf("  %d '%s' node '%s' %s %s, %d keys %g..%g s\n", a, s->animations[a].name,
                   s->nodes[ch->node].name, paths[ch->path], modes[ch->interpolation], ch->key_count,
                   ch->times[0], ch->times[ch->key_count - 1]);
        }
    return true;
}

int
cmd_info(int argc, char **argv)
{
    const char *source = NULL;
    bool gl = false, sky_given = false, no_default_light = false;
    cg_sky sky;
    cg_error err = { 0 };
    cg_context_desc desc = { 0 };
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--gl")) {
            gl = true;
        } else if (!strcmp(argv[i], "--no-default-light")) {
            no_default_light = true;
        } else if (!strcmp(argv[i], "--sky")) {
            if (i + 1 >= argc || !cg_sky_parse(argv[i + 1], &sky, &err)) {
                fprintf(stderr, "conegraph info: --sky: %s\n", i + 1 < argc ? err.message : "needs a value");
                return 2;
            }
            sky_given = true;
            i++;
        } else if (!strcmp(argv[i], "--context")) {
            if (i + 1 >= argc || !cg_context_backend_parse(argv[i + 1], &desc.backend)) {
                fprintf(stderr, "conegraph info: --context expects egl, osmesa, glfw or auto\n");
                return 2;
            }
            gl = true;
            i++;
        } else if (argv[i][0] == '-' && argv[i][1]) {
            fprintf(stderr, "conegraph info: unknown option '%s' (see conegraph info --help)\n", argv[i]);
            return 2;
        } else if (source) {
            fprintf(stderr, "conegraph info: more than one scene given ('%s', '%s')\n", source, argv[i]);
            return 2;
        } else {
            source = argv[i];
        }
    }
    if (!source) {
        cmd_info_usage(stderr);
        return 2;
    }
    cg_scene scene;
    if (!cg_scene_load(source, &scene, &err)) {
        fprintf(stderr, "conegraph info: %s\n", err.message);
        return cg_status_exit_code(err.status);
    }
    int file_lights = scene.light_count;
    if (!app_light_scene("conegraph info", &scene, sky_given ? &sky : NULL, "--sky", no_default_light, &err)) {
        fprintf(stderr, "conegraph info: %s\n", err.message);
        cg_scene_free(&scene);
        return cg_status_exit_code(err.status);
    }
    bool printed = print_scene(&scene, file_lights, &err);
    cg_scene_free(&scene);
    if (!printed) {
        fprintf(stderr, "conegraph info: %s\n", err.message);
        return cg_status_exit_code(err.status);
    }
    if (!gl)
        return 0;
    cg_context *ctx;
    if (!cg_context_create(&desc, &ctx, &err)) {
        fprintf(stderr, "conegraph info: %s\n", err.message);
        return cg_status_exit_code(err.status);
    }
    printf("gl context %s\n", cg_context_backend_name(cg_context_get_backend(ctx)));
    printf("gl version %s\n", cg_context_version(ctx));
    printf("gl renderer %s\n", cg_context_renderer(ctx));
    cg_context_destroy(ctx);
    return 0;
}
