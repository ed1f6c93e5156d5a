/* cg/graphfile.h: reading graph files (JSON, via jansson) into an fg_graph, and --set overrides.
 *
 * Declares: fg_graph_load_file, fg_graph_load_string, fg_graph_file_sky, fg_graph_apply_override.
 *
 * Format (docs/graph-files.md):
 *   { "version": 1,
 *     "sky": "0.5,0.6,0.8",
 *     "passes": { "NAME": { "type": "TYPE", "params": {...}, "inputs": { "SLOT": "pass.output" } }, ... },
 *     "outputs": [ "pass.output", ... ] }
 * "sky" (optional) is the scene sky the graph asks for, in --sky's syntax (cg_sky_parse): the
 * graph does not light the scene itself; the app applies it, after --sky, which wins.
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
/* The sky the file's "sky" asks for: true and *out filled when it has one. */
bool fg_graph_file_sky(const fg_graph *graph, cg_sky *out);
/* "pass.param=value", validated as a file value would be. */
bool fg_graph_apply_override(fg_graph *graph, const char *assignment, cg_error *err);

#endif
