/* cg/graphfile.h: reading graph files (JSON, via jansson) into an fg_graph, and --set overrides.
 *
 * Declares: fg_graph_load_file, fg_graph_load_string, fg_graph_apply_override.
 *
 * Format (docs/graph-files.md):
 *   { "version": 1,
 *     "passes": { "NAME": { "type": "TYPE", "params": {...}, "inputs": { "SLOT": "pass.output" } }, ... },
 *     "outputs": [ "pass.output", ... ] }
 * Every error names the file, line and column, the pass and the field, and what was expected.
 */
#ifndef CG_GRAPHFILE_H
#define CG_GRAPHFILE_H

#include <stdbool.h>

#include "cg/error.h"
#include "cg/fg.h"

bool fg_graph_load_file(fg_graph *graph, const char *path, cg_error *err);
/* `name` stands for the file name in messages. */
bool fg_graph_load_string(fg_graph *graph, const char *json, const char *name, cg_error *err);
/* "pass.param=value", validated as a file value would be. */
bool fg_graph_apply_override(fg_graph *graph, const char *assignment, cg_error *err);

#endif
