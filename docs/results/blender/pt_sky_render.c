/* Renders a scene with the path tracer under a sky, for the Cycles check (run_courtyard.sh)
 * until `conegraph render` takes `--sky` (the scene field exists: cg_scene_set_sky):
 *
 *   pt_sky_render SCENE OUT.exr W H SPP BOUNCES SKY
 *
 * SKY as cg_sky_parse reads it (R,G,B, L, preetham[:T[,SCALE]]); the scene's first camera;
 * samples over the pixel area (jitter), seed 1, as `render --graph reference.json --set
 * trace.jitter=true` does. Built by run_courtyard.sh against the build's core library.
 */
#include <stdio.h>
#include <stdlib.h>

#include "cg/camera.h"
#include "cg/image.h"
#include "cg/pt_render.h"
#include "cg/scene.h"

int
main(int argc, char **argv)
{
    if (argc != 8) {
        fprintf(stderr, "usage: pt_sky_render SCENE OUT.exr W H SPP BOUNCES SKY\n");
        return 2;
    }
    cg_error err = { 0 };
    cg_scene scene;
    cg_sky sky;
    int w = atoi(argv[3]), h = atoi(argv[4]);
    if (!cg_scene_load(argv[1], &scene, &err) || !cg_sky_parse(argv[7], &sky, &err) ||
        !cg_scene_set_sky(&scene, &sky, &err)) {
        fprintf(stderr, "pt_sky_render: %s\n", err.message);
        return cg_status_exit_code(err.status);
    }
    cg_view view;
    cg_view_from_scene(&scene, scene.camera_count > 0 ? 0 : -1, w, h, &view);
    pt_settings s = pt_settings_default();
    s.spp = atoi(argv[5]);
    s.bounces = atoi(argv[6]);
    s.jitter = true;
    pt_scene *pts = NULL;
    cg_image img = { 0 };
    if (!cg_image_alloc(&img, w, h, &err) || !pt_scene_create(&scene, &pts, &err) ||
        !pt_render(pts, &view, &s, img.rgba, NULL, &err) || !cg_image_write(argv[2], &img, CG_EXR_FLOAT, &err)) {
        fprintf(stderr, "pt_sky_render: %s\n", err.message);
        return cg_status_exit_code(err.status);
    }
    pt_scene_destroy(pts);
    cg_image_free(&img);
    cg_scene_free(&scene);
    return 0;
}
