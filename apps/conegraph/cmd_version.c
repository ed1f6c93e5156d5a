#include <stdio.h>

#include "commands.h"

void
cmd_version_usage(FILE *out)
{
    fprintf(out, "usage: conegraph version\n\nPrints the version of conegraph.\n");
}

int
cmd_version(int argc, char **argv)
{
    if (argc > 1) {
        fprintf(stderr, "conegraph version: unexpected argument '%s'\n", argv[1]);
        return 2;
    }
    printf("conegraph %s\n", CONEGRAPH_VERSION);
    return 0;
}
