/* libFuzzer target: the glTF loader (cg_scene_load on a .gltf or .glb file; the loader
 * tells them apart by content, so one target serves both).
 *
 * Each input is written to a file in a private directory and loaded from there, as a user's
 * file would be: relative URIs resolve inside that directory, where the seed corpus's
 * buffer file `fuzz.bin` is copied at start-up (from $CONEGRAPH_FUZZ_GLTF_DIR, else the
 * corpus directory of the source tree). Besides crashes and sanitizer reports, a refusal
 * without a status, without a message, or with a message that does not name the file
 * aborts, and so does a loaded scene without a triangle. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cg/error.h"
#include "cg/fs.h"
#include "cg/scene.h"
#include "fuzz_input.h"

#ifndef CG_FUZZ_GLTF_CORPUS
#error "tests/fuzz/meson.build defines CG_FUZZ_GLTF_CORPUS"
#endif

/* The side file copy_side_file put beside the input. */
static void
remove_side_file(void)
{
    char side[4200];
    snprintf(side, sizeof side, "%s/fuzz.bin", fuzz_input_dir);
    unlink(side);
}

static void
copy_side_file(const char *from_dir, const char *name)
{
    char from[4200], to[4200];
    snprintf(from, sizeof from, "%s/%s", from_dir, name);
    snprintf(to, sizeof to, "%s/%s", fuzz_input_dir, name);
    char *data;
    size_t size;
    cg_error err = { 0 };
    if (!cg_read_file(from, &data, &size, &err))
        return; /* a missing side file only makes the URI inputs fail to load */
    FILE *fp = fopen(to, "wb");
    if (fp) {
        fwrite(data, 1, size, fp);
        fclose(fp);
    }
    free(data);
}

int
LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    fuzz_input_open("gltf", "input.gltf", remove_side_file);
    const char *corpus = getenv("CONEGRAPH_FUZZ_GLTF_DIR");
    copy_side_file(corpus && *corpus ? corpus : CG_FUZZ_GLTF_CORPUS, "fuzz.bin");
    return 0;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input_write(data, size);
    cg_scene scene;
    cg_error err = { 0 };
    if (cg_scene_load(fuzz_input_path, &scene, &err)) {
        if (cg_scene_triangle_count(&scene) == 0) {
            fprintf(stderr, "fuzz_gltf: a scene without triangles loaded\n");
            abort();
        }
        cg_scene_free(&scene);
    } else if (err.status == CG_OK || !strstr(err.message, fuzz_input_path)) {
        fprintf(stderr, "fuzz_gltf: refused with status %s and message '%s', which does not name the file\n",
                cg_status_name(err.status), err.message);
        abort();
    }
    return 0;
}
