/* conegraph: the command line. Dispatches to one subcommand per file (cmd_NAME.c). */
#include <stdio.h>
#include <string.h>

#include "app_options.h"
#include "commands.h"

static const cg_command commands[] = { CG_COMMAND_LIST };
static const int command_count = (int)(sizeof commands / sizeof commands[0]);

static void
usage(FILE *out)
{
    fprintf(out,
            "usage: conegraph COMMAND [ARGS...]\n"
            "\n"
            "Real-time global illumination as a frame graph of passes (voxel cone tracing,\n"
            "hybrid 2D/3D cone tracing), measured against a path-traced reference.\n"
            "\n"
            "commands:\n");
    for (int i = 0; i < command_count; i++)
        fprintf(out, "  %-10s %s\n", commands[i].name, commands[i].summary);
    fprintf(out,
            "\n"
            "`conegraph COMMAND --help` describes each command; `conegraph --version` is\n"
            "`conegraph version`.\n"
            "Exit codes: 0 done, 1 failed while running, 2 bad input or usage.\n"
            "Environment: CONEGRAPH_CONTEXT (egl|osmesa|glfw), CONEGRAPH_SHADER_DIR,\n"
            "CONEGRAPH_PLUGIN_PATH, CONEGRAPH_LOG (debug|info|warn|error|silent).\n");
}

int
main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(argv[1], "--version"))
        return cmd_version(1, argv + 1);
    for (int i = 0; i < command_count; i++) {
        if (strcmp(argv[1], commands[i].name))
            continue;
        if (commands[i].usage && app_wants_help(argc - 1, argv + 1)) {
            commands[i].usage(stdout);
            return 0;
        }
        return commands[i].run(argc - 1, argv + 1);
    }
    fprintf(stderr, "conegraph: unknown command '%s' (see conegraph --help)\n", argv[1]);
    return 2;
}
