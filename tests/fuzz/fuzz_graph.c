/* libFuzzer target: the graph-file reader (fg_graph_load_string) and --set overrides
 * (fg_graph_apply_override) against the registry of built-in passes.
 *
 * Input: a graph file's text, then any number of overrides, each after a NUL byte:
 *     {"version": 1, ...}\0shadow.resolution=1024\0final.tonemap=aces
 * Overrides are applied only to a graph that loaded, in order, until one is refused.
 * Besides crashes and sanitizer reports, a refusal without a status or message aborts:
 * every failure must be explained to the user. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/error.h"
#include "cg/fg.h"
#include "cg/graphfile.h"
#include "sdk/builtin.h"

static fg_registry *registry;

static void
check_refusal(const cg_error *err, const char *what)
{
    if (err->status == CG_OK || err->message[0] == '\0') {
        fprintf(stderr, "fuzz_graph: %s failed without %s\n", what,
                err->status == CG_OK ? "a status" : "a message");
        abort();
    }
}

int
LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    cg_error err = { 0 };
    registry = fg_registry_create();
    if (!registry || !cg_builtin_passes_register(registry, &err)) {
        fprintf(stderr, "fuzz_graph: cannot register the built-in passes: %s\n", err.message);
        abort();
    }
    return 0;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* One NUL more than the input: the last override ends there. */
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    fg_graph *graph = fg_graph_create(registry);
    cg_error err = { 0 };
    if (fg_graph_load_string(graph, text, "fuzz.json", &err)) {
        for (const char *p = text + strlen(text) + 1; p <= text + size; p += strlen(p) + 1) {
            cg_error_clear(&err);
            if (!fg_graph_apply_override(graph, p, &err)) {
                check_refusal(&err, "fg_graph_apply_override");
                break;
            }
        }
    } else {
        check_refusal(&err, "fg_graph_load_string");
    }
    fg_graph_destroy(graph);
    free(text);
    return 0;
}
