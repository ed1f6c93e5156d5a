/* conegraph info: what a scene holds, and with --gl what GL context it would render with. */
#include <stdio.h>
#include <string.h>

#include "app_session.h"
#include "cg/error.h"
#include "cg/gl.h"
#include "cg/scene.h"
#include "commands.h"

void
cmd_info_usage(FILE *out)
{
    fprintf(out,
            "usage: conegraph info SCENE [--gl] [--context egl|osmesa|glfw|auto] [--sky SKY]\n"
            "                            [--no-default-light]\n"
            "\n"
            "Loads SCENE and prints its meshes (with their kind: heightfield or complex),\n"
            "triangles, materials, textures, lights, cameras, sky and world bounds, lit as render\n"
            "lights it: a scene with no light, no emissive surface and no sky is given the default\n"
            "light (a sun and a sky: a notice on stderr, the lights marked \"added\").\n"
            "\n"
            "SCENE is a .gltf or .glb file, or builtin:NAME[?key=value&...]:\n");
    for (const char *const *n = cg_scene_builtin_names(); *n; n++)
        fprintf(out, "  builtin:%s\n      %s\n", *n, cg_scene_builtin_doc(*n));
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

static void
print_scene(const cg_scene *s, int file_lights)
{
    printf("scene %s\n", s->name);
    printf("triangles %zu (%d meshes, %d instances)\n", cg_scene_triangle_count(s), s->mesh_count,
           s->instance_count);
    printf("bounds [%g %g %g] .. [%g %g %g] m\n", s->bounds_min[0], s->bounds_min[1], s->bounds_min[2],
           s->bounds_max[0], s->bounds_max[1], s->bounds_max[2]);
    printf("meshes %d\n", s->mesh_count);
    for (int i = 0; i < s->mesh_count; i++) {
        const cg_mesh *m = &s->meshes[i];
        int instances = 0;
        for (int k = 0; k < s->instance_count; k++)
            instances += s->instances[k].mesh == i;
        printf("  %d '%s' %s: %u triangles, %u vertices, material %d, %d instance%s%s\n", i, m->name,
               m->kind == CG_MESH_HEIGHTFIELD ? "heightfield" : "complex", m->index_count / 3,
               m->vertex_count, m->material, instances, instances == 1 ? "" : "s",
               m->texcoords ? ", texcoords" : "");
    }
    printf("materials %d\n", s->material_count);
    for (int i = 0; i < s->material_count; i++) {
        const cg_material *m = &s->materials[i];
        printf("  %d '%s' base [%g %g %g %g] tex %d, emissive [%g %g %g] x %g tex %d, metallic %g "
               "roughness %g\n",
               i, m->name, m->base_color[0], m->base_color[1], m->base_color[2], m->base_color[3],
               m->base_color_texture, m->emissive[0], m->emissive[1], m->emissive[2],
               m->emissive_strength, m->emissive_texture, m->metallic, m->roughness);
    }
    printf("textures %d\n", s->texture_count);
    for (int i = 0; i < s->texture_count; i++)
        printf("  %d '%s' %dx%d%s\n", i, s->textures[i].name, s->textures[i].width,
               s->textures[i].height, s->textures[i].srgb ? " sRGB" : "");
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
    print_scene(&scene, file_lights);
    cg_scene_free(&scene);
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
