/* Query parameters of the built-in scenes ("builtin:NAME?key=value&..."). */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

bool
bs_parse_params(const char *scene, const char *query, bs_param *specs, int count, cg_error *err)
{
    if (!query || !query[0])
        return true;
    const char *p = query;
    while (*p) {
        const char *end = strchr(p, '&');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        char item[128];
        if (len == 0 || len >= sizeof item)
            return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: malformed parameter list '%s'",
                           scene, query);
        memcpy(item, p, len);
        item[len] = '\0';
        char *eq = strchr(item, '=');
        if (!eq)
            return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: parameter '%s' has no '=value'",
                           scene, item);
        *eq = '\0';
        const char *value = eq + 1;
        bs_param *spec = NULL;
        for (int i = 0; i < count; i++)
            if (!strcmp(item, specs[i].key))
                spec = &specs[i];
        if (!spec) {
            char known[256] = "";
            for (int i = 0; i < count; i++)
                snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s",
                         i ? ", " : "", specs[i].key);
            return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: unknown parameter '%s' (known: %s)",
                           scene, item, count ? known : "none");
        }
        if (spec->seen)
            return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: parameter '%s' given twice", scene,
                           item);
        spec->seen = true;
        char *rest = NULL;
        errno = 0;
        double v;
        if (spec->choices) {
            char names[256] = "";
            for (int i = 0; spec->choices[i]; i++) {
                if (!strcmp(value, spec->choices[i])) {
                    spec->count = (uint64_t)i;
                    spec->value = i;
                }
                snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", i ? ", " : "",
                         spec->choices[i]);
            }
            if (strcmp(value, spec->choices[spec->count]))
                return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: %s=%s: expected one of %s", scene, item,
                               value, names);
            if (!end)
                break;
            p = end + 1;
            continue;
        }
        if (spec->integer) {
            if (value[0] == '-' || value[0] == '+')
                return cg_fail(err, CG_ERR_SCENE_PARAM,
                               "builtin:%s: %s=%s: expected an unsigned integer", scene, item, value);
            spec->count = strtoull(value, &rest, 10);
            v = (double)spec->count;
        } else {
            v = strtod(value, &rest);
        }
        if (!value[0] || *rest || errno || !isfinite(v))
            return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: %s=%s: expected %s", scene, item,
                           value, spec->integer ? "an unsigned integer" : "a number");
        if (v < spec->min || v > spec->max)
            return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:%s: %s=%s out of range [%g, %g]",
                           scene, item, value, spec->min, spec->max);
        spec->value = v;
        if (!end)
            break;
        p = end + 1;
    }
    return true;
}
