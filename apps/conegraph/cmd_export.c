/* conegraph export: any scene (a file or a built-in) written as glTF for other renderers. */
#include <stdio.h>
#include <string.h>

#include "cg/error.h"
#include "cg/scene.h"
#include "commands.h"

void
cmd_export_usage(FILE *out)
{
    fprintf(out,
            "usage: conegraph export SCENE OUT.gltf|OUT.glb\n"
            "\n"
            "Loads SCENE (a .gltf/.glb file or builtin:NAME[?key=value&...], see conegraph info\n"
            "--help) and writes it as glTF 2.0: .gltf with the buffers and textures embedded as\n"
            "base64, or a binary .glb, chosen by OUT's extension. Lights are written with\n"
            "KHR_lights_punctual, emissive strengths above 1 with KHR_materials_emissive_strength,\n"
            "each mesh's kind (heightfield or complex) in its extras as \"conegraph_kind\", and\n"
            "the animations with the nodes they move (a built-in's motion= included), so that\n"
            "the file loads back as the same scene. The file is written to a temporary\n"
            "name and renamed, so a failure leaves no partial file.\n"
            "\n"
            "Exit codes: 0 done, 1 failed while writing, 2 bad scene or usage.\n");
}

int
cmd_export(int argc, char **argv)
{
    const char *args[2];
    int n = 0;
    for (int i = 1; i < argc; i++) {
        if (argv[i][0] == '-' && argv[i][1]) {
            fprintf(stderr, "conegraph export: unknown option '%s' (see conegraph export --help)\n", argv[i]);
            return 2;
        }
        if (n == 2) {
            fprintf(stderr, "conegraph export: unexpected argument '%s'\n", argv[i]);
            return 2;
        }
        args[n++] = argv[i];
    }
    if (n != 2) {
        cmd_export_usage(stderr);
        return 2;
    }
    size_t len = strlen(args[1]);
    if (!((len > 5 && !strcmp(args[1] + len - 5, ".gltf")) || (len > 4 && !strcmp(args[1] + len - 4, ".glb")))) {
        fprintf(stderr, "conegraph export: %s: the output must end in .gltf or .glb\n", args[1]);
        return 2;
    }
    cg_scene scene;
    cg_error err = { 0 };
    if (!cg_scene_load(args[0], &scene, &err)) {
        fprintf(stderr, "conegraph export: %s\n", err.message);
        return cg_status_exit_code(err.status);
    }
    bool ok = cg_scene_export_gltf(&scene, args[1], &err);
    if (ok)
        printf("wrote %s: %zu triangles, %d meshes, %d lights, %d cameras\n", args[1],
               cg_scene_triangle_count(&scene), scene.mesh_count, scene.light_count, scene.camera_count);
    cg_scene_free(&scene);
    if (!ok) {
        fprintf(stderr, "conegraph export: %s\n", err.message);
        return cg_status_exit_code(err.status);
    }
    return 0;
}
