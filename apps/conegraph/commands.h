/* apps/conegraph/commands.h: the subcommands of `conegraph`, one file each (cmd_NAME.c).
 *
 * Declares: cg_command, cg_commands, cg_command_count, one cmd_NAME() per subcommand.
 *
 * Each command returns the process exit code: 0 done, 1 failed while running,
 * 2 bad input or usage. Each answers --help with its own usage.
 */
#ifndef CONEGRAPH_COMMANDS_H
#define CONEGRAPH_COMMANDS_H

typedef int (*cg_command_fn)(int argc, char **argv);

typedef struct cg_command {
    const char *name;
    cg_command_fn run;
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

/* One line per command; keep them in the order `conegraph --help` lists them. */
#define CG_COMMAND_LIST                                                                   \
    { "version", cmd_version, "print the version of conegraph and of its libraries" },   \
    { "render", cmd_render, "render a scene through a graph file to .exr or .png" },    \
    { "info", cmd_info, "print a scene's meshes, triangles, materials, lights, cameras" }, \
    { "export", cmd_export, "write a scene (a file or a built-in) as .gltf or .glb" },   \
    { "passes", cmd_passes, "list the pass types with their parameters (from their tables)" },  \
    { "graph", cmd_graph, "check a graph file: compile it without GL, print order, culling, resources or DOT" }, \
    { "compare", cmd_compare, "error metrics of an image against a reference (RMSE, relMSE, SSIM, ...)" }, \
    { "bench", cmd_bench, "time, GI memory and error of graph settings against the path-traced reference" },

#endif
