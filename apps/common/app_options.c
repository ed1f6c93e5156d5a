/* The command-line options shared by the apps: see app_options.h. */
#include "app_options.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"

bool
app_wants_help(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h"))
            return true;
    return false;
}

/* Appends to a repeatable option's list. */
static int
append(const char *tool, const char *name, const char *value, const char **list, int *count)
{
    if (*count == APP_MAX_LIST)
        return app_usage_error(tool, "%s: too many of this option", name);
    list[(*count)++] = value;
    return 0;
}

bool
app_parse_point(const char *text, float out[3])
{
    const char *p = text;
    for (int k = 0; k < 3; k++) {
        char *end;
        errno = 0;
        double v = strtod(p, &end);
        if (end == p || errno || !isfinite(v) || !isfinite((float)v))
            return false;
        out[k] = (float)v;
        if (*end != (k < 2 ? ',' : '\0'))
            return false;
        p = end + 1;
    }
    return true;
}

/* One of the common options: 0 taken, 2 bad value, -1 not a common option this app takes. */
static int
common_option(const char *tool, unsigned accepted, const char *a, const char *v, app_options *o)
{
    long n;
    cg_error err = { 0 };
    if ((accepted & APP_OPT_GRAPH) && !strcmp(a, "--graph"))
        o->graph = v;
    else if ((accepted & APP_OPT_CAMERA) && !strcmp(a, "--camera"))
        o->camera = v;
    else if ((accepted & APP_OPT_CAMERA) && (!strcmp(a, "--from") || !strcmp(a, "--look-at"))) {
        bool from = !strcmp(a, "--from");
        if (!app_parse_point(v, from ? o->from : o->look_at))
            return app_usage_error(tool, from ? "--from wants X,Y,Z (three numbers, metres), not '%s'"
                                              : "--look-at wants X,Y,Z (three numbers, metres), not '%s'", v);
        *(from ? &o->from_given : &o->look_at_given) = true;
    } else if ((accepted & APP_OPT_CAMERA) && !strcmp(a, "--fov")) {
        char *end;
        errno = 0;
        double deg = strtod(v, &end);
        if (end == v || *end || errno || !(deg > 0.0 && deg < 180.0))
            return app_usage_error(tool, "--fov wants a vertical field of view in degrees, above 0 and below "
                                   "180, not '%s'", v);
        o->yfov = (float)(deg * 3.14159265358979323846 / 180.0);
    } else if (!strcmp(a, "--sky")) {
        if (!cg_sky_parse(v, &o->sky, &err))
            return app_usage_error(tool, "--sky: %s", err.message);
        o->sky_given = true;
    }
    else if ((accepted & APP_OPT_SET) && !strcmp(a, "--set"))
        return append(tool, a, v, o->sets, &o->set_count);
    else if ((accepted & APP_OPT_PLUGIN) && !strcmp(a, "--plugin"))
        return append(tool, a, v, o->plugins, &o->plugin_count);
    else if ((accepted & APP_OPT_SIZE) && !strcmp(a, "--size")) {
        if (!app_parse_size(v, &o->width, &o->height))
            return app_usage_error(tool, "--size wants WxH with 1..65536 pixels each, not '%s'", v);
    } else if ((accepted & APP_OPT_FRAMES) && !strcmp(a, "--frames")) {
        if (!app_parse_int(v, 1, 1000000, &n))
            return app_usage_error(tool, "--frames wants a count from 1 to 1000000, not '%s'", v);
        o->frames = (int)n;
    } else if ((accepted & APP_OPT_TIMING) && !strcmp(a, "--timing")) {
        if (!app_parse_timing(v, &o->timing))
            return app_usage_error(tool, "--timing wants sync, queries or none, not '%s'", v);
        o->timing_given = true;
    } else if ((accepted & APP_OPT_CONTEXT) && !strcmp(a, "--context")) {
        if (!cg_context_backend_parse(v, &o->backend))
            return app_usage_error(tool, "--context wants egl, osmesa, glfw or auto, not '%s'", v);
    } else if ((accepted & APP_OPT_MAX_GPU_MEMORY) && !strcmp(a, "--max-gpu-memory")) {
        if (!app_parse_bytes(v, &o->max_gpu_memory))
            return app_usage_error(tool, "--max-gpu-memory wants " APP_BYTES_SYNTAX ", not '%s'", v);
    } else {
        return -1;
    }
    return 0;
}

int
app_parse_options(const char *tool, int argc, char **argv, unsigned accepted, app_options *o,
                  app_own_option_fn own, void *user)
{
    o->tool = tool;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] != '-' || a[1] == '\0') {
            if (o->scene)
                return app_usage_error(tool, "one scene only; '%s' is a second one", a);
            o->scene = a;
            continue;
        }
        if (!strcmp(a, "--no-default-light")) {
            o->no_default_light = true;
            continue;
        }
        if ((accepted & APP_OPT_VERBOSITY) && (!strcmp(a, "--verbose") || !strcmp(a, "--quiet"))) {
            *(a[2] == 'v' ? &o->verbose : &o->quiet) = true;
            if (o->verbose && o->quiet)
                return app_usage_error(tool, "%s", "--verbose and --quiet contradict each other");
            continue;
        }
        if (i + 1 == argc)
            return app_usage_error(tool, "%s needs a value", a);
        const char *v = argv[++i];
        int code = common_option(tool, accepted, a, v, o);
        if (code < 0 && own)
            code = own(user, a, v);
        if (code < 0)
            return app_usage_error(tool, "unknown option '%s'", a);
        if (code)
            return code;
    }
    return 0;
}

app_session_desc
app_options_session(const app_options *o)
{
    app_session_desc d = { .tool = o->tool, .scene = o->scene, .camera = o->camera, .plugins = o->plugins,
                           .plugin_count = o->plugin_count, .width = o->width, .height = o->height,
                           .compile = { .max_gpu_memory = o->max_gpu_memory },
                           .from_given = o->from_given, .look_at_given = o->look_at_given, .yfov = o->yfov,
                           .sky = o->sky_given ? &o->sky : NULL, .no_default_light = o->no_default_light };
    memcpy(d.from, o->from, sizeof d.from);
    memcpy(d.look_at, o->look_at, sizeof d.look_at);
    return d;
}

app_graph_desc
app_options_graph(const app_options *o)
{
    return (app_graph_desc){ .graph = o->graph, .sets = o->sets, .set_count = o->set_count };
}
