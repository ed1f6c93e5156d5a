/* apps/conegraph/app_common.h: what `render`, `bench` and `conegraph-demo` share: finding graph files,
 * reading graph resources back into images, parsing sizes and counts, a clock.
 *
 * Declares: app_graph_dir, app_resolve_graph, app_load_graph, app_find_output, app_read_resource,
 *           app_parse_int, app_parse_size, app_parse_timing, app_now_ms, app_compare_double.
 */
#ifndef CONEGRAPH_APP_COMMON_H
#define CONEGRAPH_APP_COMMON_H

#include <stdbool.h>
#include <stddef.h>

#include "cg/error.h"
#include "cg/fg.h"
#include "cg/image.h"

/* $CONEGRAPH_GRAPH_DIR, else the source tree's graphs/ when it exists, else the installed one. */
const char *app_graph_dir(void);
/* The graph file to read: as given when it exists or names a directory, else from the graph
 * directory; NULL = vct.json from the graph directory if it exists, else direct.json. */
void app_resolve_graph(const char *given, char *out, size_t size);
/* Reads a graph file into `graph` and applies the "pass.param=value" overrides in order
 * (validated as file values are); the error names the file or the override. */
bool app_load_graph(fg_graph *graph, const char *path, const char *const *sets, int set_count,
                    cg_error *err);
/* The graph output whose output name is `suffix` ("hdr", "ldr"), or NULL. */
const char *app_find_output(const fg_graph *graph, const char *suffix);
/* Reads a texture resource into a top-to-bottom float image: 2D as is, 3D and array layers
 * stacked top to bottom (layer 0 first); depth formats land in RGB. srgb_encoded: the texels
 * hold sRGB-encoded values (an ldr output), decoded here so that the image is linear. */
bool app_read_resource(const fg_graph *graph, const char *source, bool srgb_encoded, cg_image *out,
                       cg_error *err);

bool app_parse_int(const char *text, long min, long max, long *out);
/* "WxH", each 1..65536. */
bool app_parse_size(const char *text, int *w, int *h);
/* "sync", "queries" or "none"; false for anything else. */
bool app_parse_timing(const char *text, fg_timing_mode *out);
double app_now_ms(void);
/* qsort comparator for doubles. */
int app_compare_double(const void *a, const void *b);

#endif
