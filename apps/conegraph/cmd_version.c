#include <stdio.h>
#include <string.h>

#include "commands.h"

int
cmd_version(int argc, char **argv)
{
    if (argc > 1 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        printf("usage: conegraph version\n\nPrints the version of conegraph.\n");
        return 0;
    }
    if (argc > 1) {
        fprintf(stderr, "conegraph version: unexpected argument '%s'\n", argv[1]);
        return 2;
    }
    printf("conegraph %s\n", CONEGRAPH_VERSION);
    return 0;
}
