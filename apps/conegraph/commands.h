/* apps/conegraph/commands.h: the subcommands of `conegraph`, one file each (cmd_NAME.c).
 *
 * Declares: cg_command, CG_COMMAND_LIST, one cmd_NAME() per subcommand and the cmd_NAME_usage()
 *           of those whose --help main.c answers.
 *
 * Each command returns the process exit code: 0 done, 1 failed while running,
 * 2 bad input or usage. `conegraph NAME ... --help` (or -h) prints its usage: main.c does it
 * for a command with a usage function, the others answer it themselves.
 */
#ifndef CONEGRAPH_COMMANDS_H
#define CONEGRAPH_COMMANDS_H

#include <stdio.h>

typedef int (*cg_command_fn)(int argc, char **argv);
typedef void (*cg_usage_fn)(FILE *out);

typedef struct cg_command {
    const char *name;
    cg_command_fn run;
    cg_usage_fn usage;      /* NULL: the command answers --help itself */
    const char *summary;
} cg_command;

int cmd_version(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_info(int argc, char **argv);
int cmd_export(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_passes(int argc, char **argv);
int cmd_graph(int argc, char **argv);
int cmd_bench(int argc, char **argv);

void cmd_version_usage(FILE *out);
void cmd_render_usage(FILE *out);
void cmd_info_usage(FILE *out);
void cmd_export_usage(FILE *out);
void cmd_graph_usage(FILE *out);
void cmd_compare_usage(FILE *out);
void cmd_bench_usage(FILE *out);

/* One line per command; keep them in the order `conegraph --help` lists them. */
#define CG_COMMAND_LIST                                                                   \
    { "version", cmd_version, cmd_version_usage, "print the version of conegraph and of its libraries" },   \
    { "render", cmd_render, cmd_render_usage, "render a scene through a graph file to .exr or .png" },    \
    { "info", cmd_info, cmd_info_usage, "print a scene's meshes, triangles, materials, lights, cameras" }, \
    { "export", cmd_export, cmd_export_usage, "write a scene (a file or a built-in) as .gltf or .glb" },   \
    { "passes", cmd_passes, NULL, "list the pass types with their parameters (from their tables)" },  \
    { "graph", cmd_graph, cmd_graph_usage, "check a graph file: compile it without GL, print order, culling, resources or DOT" }, \
    { "compare", cmd_compare, cmd_compare_usage, "error metrics of an image against a reference (RMSE, relMSE, SSIM, ...)" }, \
    { "bench", cmd_bench, cmd_bench_usage, "time, GI memory and error of graph settings against the path-traced reference" },

#endif
