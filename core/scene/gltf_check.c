/* The JSON of a glTF 2.0 file checked before tinygltf reads it (scene_internal.h).
 *
 * tinygltf takes a field of the wrong JSON type for an absent one and carries on with the
 * default (a material whose "metallicFactor" is the string "0" reads metallic 1), reads -1
 * as "no texture" or "no material", and refuses files that require an extension it cannot
 * decode with a message about accessors. So the JSON is walked here first, with jansson, the
 * way the Khronos glTF-Validator reads it (its rules, stricter in the few places listed in
 * docs/gltf.md): the type of every core field and of the fields of the extensions
 * conegraph reads, required fields, ranges, enumerations, index references in range, the
 * asset version, and required extensions. Every message names the file and the JSON path
 * of the field, e.g. "scene.gltf: materials[0].pbrMetallicRoughness.metallicFactor: expected
 * a number in [0, 1], found the string "0"".
 *
 * What needs the buffers (accessor data, alignment against bufferViews, images) is checked
 * in gltf_adapter.cpp once tinygltf has fetched them. */
#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/error.h"
#include "scene_internal.h"

typedef struct checker {
    const char *file;
    cg_error *err;
    json_t *root;
    json_t *used;     /* extensionsUsed, or NULL */
    json_t *lights;   /* extensions.KHR_lights_punctual.lights, or NULL */
    const json_t *animation; /* the animation whose channels are being checked */
    long long glb_bin;       /* a .glb's BIN chunk size (0: none), -1 for a .gltf */
    char path[1024];  /* the JSON path of the object being checked, "" at the root */
    size_t len;
} checker;

/* ------------------------------------------------------------------ paths and messages */

static size_t
enter_key(checker *c, const char *key)
{
    size_t mark = c->len;
    int n = snprintf(c->path + c->len, sizeof c->path - c->len, "%s%s", c->len ? "." : "", key);
    if (n > 0)
        c->len = c->len + (size_t)n < sizeof c->path ? c->len + (size_t)n : sizeof c->path - 1;
    return mark;
}

static size_t
enter_index(checker *c, size_t i)
{
    size_t mark = c->len;
    int n = snprintf(c->path + c->len, sizeof c->path - c->len, "[%zu]", i);
    if (n > 0)
        c->len = c->len + (size_t)n < sizeof c->path ? c->len + (size_t)n : sizeof c->path - 1;
    return mark;
}

static void
leave(checker *c, size_t mark)
{
    c->len = mark;
    c->path[mark] = '\0';
}

/* "FILE: PATH.NAME: message" (name may be NULL: the current object itself). */
static bool
bad(checker *c, cg_status status, const char *name, const char *fmt, ...) __attribute__((format(printf, 4, 5)));

static bool
bad(checker *c, cg_status status, const char *name, const char *fmt, ...)
{
    char what[768];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    const char *sep = c->len && name && name[0] != '[' ? "." : "";
    if (!c->len && !name)
        return cg_fail(c->err, status, "%s: %s", c->file, what);
    return cg_fail(c->err, status, "%s: %s%s%s: %s", c->file, c->path, sep, name ? name : "", what);
}

/* What a value is, for "found ...". */
static const char *
found(const json_t *v, char *buf, size_t size)
{
    switch (json_typeof(v)) {
    case JSON_OBJECT: return "an object";
    case JSON_ARRAY: return "an array";
    case JSON_STRING: {
        const char *s = json_string_value(v);
        snprintf(buf, size, "the string \"%.40s%s\"", s, strlen(s) > 40 ? "..." : "");
        return buf;
    }
    case JSON_INTEGER: snprintf(buf, size, "%lld", (long long)json_integer_value(v)); return buf;
    case JSON_REAL: /* with a point, so that 0.0 does not read as the integer 0 */
        snprintf(buf, size, "%.17g", json_real_value(v));
        if (!strpbrk(buf, ".e"))
            snprintf(buf + strlen(buf), size - strlen(buf), ".0");
        return buf;
    case JSON_TRUE: return "true";
    case JSON_FALSE: return "false";
    case JSON_NULL: return "null";
    }
    return "an unknown value";
}

static bool
type_error(checker *c, const char *name, const json_t *v, const char *expected)
{
    char buf[96];
    return bad(c, CG_ERR_GLTF_SCHEMA, name, "expected %s, found %s", expected, found(v, buf, sizeof buf));
}

static bool
missing(checker *c, const char *name, const char *expected)
{
    return bad(c, CG_ERR_GLTF_SCHEMA, name, "required %s is missing", expected);
}

/* ------------------------------------------------------------------ typed fields
 *
 * Each getter looks up `name` in object `o`: absent is fine unless `req` (then an error);
 * present, it must be of the type and in the range asked for. A member whose value is null
 * is present and of the wrong type, as the validator treats it. */

/* An integer: a JSON number without fraction or exponent (tinygltf reads 1.0 or 1e0 where an
 * integer belongs as absent, so such a value would silently become the default). */
static bool
is_int(const json_t *v)
{
    return json_is_integer(v);
}

static bool
get_uint(checker *c, const json_t *o, const char *name, bool req, long long min, long long max,
         long long *out)
{
    json_t *v = json_object_get(o, name);
    if (!v)
        return !req || missing(c, name, "integer");
    if (!is_int(v))
        return type_error(c, name, v, "an integer (written without fraction or exponent)");
    long long x = json_integer_value(v);
    if (x < min || x > max)
        return bad(c, CG_ERR_GLTF_SCHEMA, name, "%lld is out of range (expected %lld..%lld)", x, min, max);
    if (out)
        *out = x;
    return true;
}

static bool
get_enum_int(checker *c, const json_t *o, const char *name, bool req, const int *list, int n, const char *names,
             long long *out)
{
    json_t *v = json_object_get(o, name);
    if (!v)
        return !req || missing(c, name, "integer");
    if (!is_int(v))
        return type_error(c, name, v, "an integer");
    for (int i = 0; i < n; i++)
        if (json_integer_value(v) == list[i]) {
            if (out)
                *out = list[i];
            return true;
        }
    return bad(c, CG_ERR_GLTF_SCHEMA, name, "%lld is not one of %s", (long long)json_integer_value(v), names);
}

/* An index into the top-level array `target` (or into `array` when given). */
static bool
check_index_value(checker *c, const char *name, const json_t *v, const char *target, const json_t *array,
                  long long *out)
{
    if (!is_int(v))
        return type_error(c, name, v, "an index (a non-negative integer)");
    long long i = json_integer_value(v);
    if (i < 0)
        return bad(c, CG_ERR_GLTF_SCHEMA, name, "expected an index (a non-negative integer), found %lld", i);
    if (!array)
        array = json_object_get(c->root, target);
    size_t n = json_is_array(array) ? json_array_size(array) : 0;
    if ((size_t)i >= n && n == 0)
        return bad(c, CG_ERR_GLTF_INDEX_RANGE, name, "refers to %s[%lld], but there are no %s", target, i, target);
    if ((size_t)i >= n)
        return bad(c, CG_ERR_GLTF_INDEX_RANGE, name, "refers to %s[%lld], but %s has %zu entr%s", target, i, target, n,
                   n == 1 ? "y" : "ies");
    if (out)
        *out = i;
    return true;
}

static bool
get_index(checker *c, const json_t *o, const char *name, bool req, const char *target, long long *out)
{
    if (out)
        *out = -1;
    json_t *v = json_object_get(o, name);
    if (!v)
        return !req || missing(c, name, "index");
    return check_index_value(c, name, v, target, NULL, out);
}

/* A number in [min, max], also above excl_min when `excl` (the bounds the validator uses). */
static bool
get_number(checker *c, const json_t *o, const char *name, bool req, double min, double max, bool excl_min,
           double *out)
{
    json_t *v = json_object_get(o, name);
    if (!v)
        return !req || missing(c, name, "number");
    if (!json_is_number(v))
        return type_error(c, name, v, "a number");
    double x = json_number_value(v);
    if (x < min || x > max || (excl_min && x <= min)) {
        char range[96];
        if (max == INFINITY)
            snprintf(range, sizeof range, "%s %g", excl_min ? "above" : "at least", min);
        else
            snprintf(range, sizeof range, "in %s%g, %g]", excl_min ? "(" : "[", min, max);
        return bad(c, CG_ERR_GLTF_SCHEMA, name, "%.17g is out of range (expected a number %s)", x, range);
    }
    if (out)
        *out = x;
    return true;
}

static bool
get_string(checker *c, const json_t *o, const char *name, bool req, const char **out)
{
    if (out)
        *out = NULL;
    json_t *v = json_object_get(o, name);
    if (!v)
        return !req || missing(c, name, "string");
    if (!json_is_string(v))
        return type_error(c, name, v, "a string");
    if (out)
        *out = json_string_value(v);
    return true;
}

static bool
get_enum_string(checker *c, const json_t *o, const char *name, bool req, const char *const *list, int n,
                const char **out)
{
    const char *s;
    if (!get_string(c, o, name, req, &s))
        return false;
    if (out)
        *out = NULL;
    if (!s)
        return true;
    char names[256] = "";
    for (int i = 0; i < n; i++) {
        if (!strcmp(s, list[i])) {
            if (out)
                *out = list[i];
            return true;
        }
        snprintf(names + strlen(names), sizeof names - strlen(names), "%s\"%s\"", i ? ", " : "", list[i]);
    }
    char buf[96];
    return bad(c, CG_ERR_GLTF_SCHEMA, name, "expected one of %s, found %s", names, found(json_object_get(o, name), buf, sizeof buf));
}

static bool
get_bool(checker *c, const json_t *o, const char *name)
{
    json_t *v = json_object_get(o, name);
    return !v || json_is_boolean(v) || type_error(c, name, v, "true or false");
}

/* An array of `length` numbers (any non-zero length when 0), each in [min, max] and finite. */
static bool
get_numbers(checker *c, const json_t *o, const char *name, bool req, size_t length, double min, double max,
            double *out)
{
    json_t *v = json_object_get(o, name);
    if (!v)
        return !req || missing(c, name, "array");
    if (!json_is_array(v))
        return type_error(c, name, v, length ? "an array of numbers" : "a non-empty array of numbers");
    size_t n = json_array_size(v);
    if (n == 0 || (length && n != length)) {
        if (length)
            return bad(c, CG_ERR_GLTF_SCHEMA, name, "expected %zu numbers, found %zu", length, n);
        return bad(c, CG_ERR_GLTF_SCHEMA, name, "expected a non-empty array, found an empty one");
    }
    for (size_t i = 0; i < n; i++) {
        json_t *x = json_array_get(v, i);
        size_t mark = enter_key(c, name);
        char item[32];
        snprintf(item, sizeof item, "[%zu]", i);
        bool ok = true;
        if (!json_is_number(x)) {
            char buf[96];
            ok = cg_fail(c->err, CG_ERR_GLTF_SCHEMA, "%s: %s%s: expected a number, found %s", c->file, c->path,
                         item, found(x, buf, sizeof buf));
        } else if (!(json_number_value(x) >= min && json_number_value(x) <= max)) {
            ok = cg_fail(c->err, CG_ERR_GLTF_SCHEMA, "%s: %s%s: %.17g is out of range (expected [%g, %g])", c->file,
                         c->path, item, json_number_value(x), min, max);
        }
        leave(c, mark);
        if (!ok)
            return false;
        if (out)
            out[i] = json_number_value(x);
    }
    return true;
}

/* A non-empty array of distinct indices into `target`. */
static bool
get_index_list(checker *c, const json_t *o, const char *name, bool req, const char *target)
{
    json_t *v = json_object_get(o, name);
    if (!v)
        return !req || missing(c, name, "array of indices");
    if (!json_is_array(v))
        return type_error(c, name, v, "an array of indices");
    size_t n = json_array_size(v);
    if (n == 0)
        return bad(c, CG_ERR_GLTF_SCHEMA, name, "expected a non-empty array of indices, found an empty one");
    size_t mark = enter_key(c, name);
    bool ok = true;
    for (size_t i = 0; i < n && ok; i++) {
        char item[32];
        snprintf(item, sizeof item, "[%zu]", i);
        ok = check_index_value(c, item, json_array_get(v, i), target, NULL, NULL);
        for (size_t k = 0; k < i && ok; k++)
            if (json_integer_value(json_array_get(v, k)) == json_integer_value(json_array_get(v, i)))
                ok = cg_fail(c->err, CG_ERR_GLTF_SCHEMA, "%s: %s%s: %lld appears twice in the list", c->file, c->path,
                             item, (long long)json_integer_value(json_array_get(v, i)));
    }
    leave(c, mark);
    return ok;
}

/* The extensions conegraph reads, each on the objects it belongs to. */
static const char *const read_extensions[] = { "KHR_lights_punctual",        "KHR_materials_emissive_strength",
                                               "KHR_materials_ior",          "KHR_materials_specular",
                                               "KHR_materials_transmission", "KHR_materials_volume",
                                               "KHR_texture_transform" };

/* Whether `key` is one of the space-separated names of `list` (NULL: none). */
static bool
listed(const char *list, const char *key)
{
    size_t n = strlen(key);
    for (const char *p = list; p && *p;) {
        const char *end = strchr(p, ' ');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        if (len == n && !strncmp(p, key, n))
            return true;
        p = end ? end + 1 : p + len;
    }
    return false;
}

/* The members every glTF object may have: "extensions" (an object whose keys are declared in
 * extensionsUsed, each an object; those listed in `allowed` (space-separated) are the ones
 * conegraph reads here, checked by the caller; one that conegraph reads elsewhere may not
 * appear) and "extras" (anything). */
static bool
check_extensions(checker *c, const json_t *o, const char *allowed)
{
    json_t *ext = json_object_get(o, "extensions");
    if (!ext)
        return true;
    if (!json_is_object(ext))
        return type_error(c, "extensions", ext, "an object");
    const char *key;
    json_t *value;
    size_t mark = enter_key(c, "extensions");
    bool ok = true;
    json_object_foreach(ext, key, value) {
        bool declared = false;
        size_t i;
        json_t *u;
        json_array_foreach(c->used, i, u) declared = declared || !strcmp(json_string_value(u), key);
        if (!declared) {
            ok = bad(c, CG_ERR_GLTF_SCHEMA, key, "extension not declared in extensionsUsed");
            break;
        }
        if (!json_is_object(value)) {
            ok = type_error(c, key, value, "an object");
            break;
        }
        bool ours = false;
        for (size_t r = 0; r < sizeof read_extensions / sizeof *read_extensions; r++)
            ours = ours || !strcmp(key, read_extensions[r]);
        if (ours && !listed(allowed, key)) {
            ok = bad(c, CG_ERR_GLTF_SCHEMA, key, "this extension does not belong here");
            break;
        }
    }
    leave(c, mark);
    return ok;
}

/* An optional member that must be an object; *out is NULL when absent. */
static bool
get_object(checker *c, const json_t *o, const char *name, bool req, json_t **out)
{
    *out = json_object_get(o, name);
    if (!*out)
        return !req || missing(c, name, "object");
    return json_is_object(*out) || type_error(c, name, *out, "an object");
}

/* A top-level array of objects, each checked by `fn`; absent is fine, empty is not. */
typedef bool (*check_fn)(checker *c, const json_t *o);

static bool
check_array_of(checker *c, const json_t *parent, const char *name, check_fn fn)
{
    json_t *a = json_object_get(parent, name);
    if (!a)
        return true;
    if (!json_is_array(a))
        return type_error(c, name, a, "an array");
    if (json_array_size(a) == 0)
        return bad(c, CG_ERR_GLTF_SCHEMA, name, "expected a non-empty array (leave it out instead), found an empty one");
    size_t mark = enter_key(c, name);
    bool ok = true;
    for (size_t i = 0; i < json_array_size(a) && ok; i++) {
        json_t *o = json_array_get(a, i);
        size_t m = enter_index(c, i);
        ok = json_is_object(o) ? fn(c, o) : type_error(c, NULL, o, "an object");
        leave(c, m);
    }
    leave(c, mark);
    return ok;
}

/* ------------------------------------------------------------------ the objects */

/* Byte counts up to 2^53 (beyond, JSON numbers lose integers in most readers); sums of two
 * cannot overflow. */
#define MAX_BYTES (1LL << 53)

enum { GL_BYTE = 5120, GL_UBYTE = 5121, GL_SHORT = 5122, GL_USHORT = 5123, GL_UINT = 5125, GL_FLOAT = 5126 };
static const int component_types[] = { GL_BYTE, GL_UBYTE, GL_SHORT, GL_USHORT, GL_UINT, GL_FLOAT };
static const char component_type_names[] = "5120 (BYTE), 5121 (UNSIGNED_BYTE), 5122 (SHORT), 5123 (UNSIGNED_SHORT), "
                                           "5125 (UNSIGNED_INT), 5126 (FLOAT)";
static const char *const accessor_types[] = { "SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4" };
static const int accessor_type_components[] = { 1, 2, 3, 4, 4, 9, 16 };

static bool
int_range(int component_type, double *lo, double *hi)
{
    switch (component_type) {
    case GL_BYTE: *lo = -128, *hi = 127; return true;
    case GL_UBYTE: *lo = 0, *hi = 255; return true;
    case GL_SHORT: *lo = -32768, *hi = 32767; return true;
    case GL_USHORT: *lo = 0, *hi = 65535; return true;
    case GL_UINT: *lo = 0, *hi = 4294967295.0; return true;
    default: return false;
    }
}

/* accessor.min / max: one value per component; integers within the component type for
 * integer accessors. */
static bool
check_bounds(checker *c, const json_t *o, const char *name, int components, int component_type)
{
    json_t *v = json_object_get(o, name);
    if (!v)
        return true;
    double lo = -INFINITY, hi = INFINITY;
    bool integer = int_range(component_type, &lo, &hi);
    if (!get_numbers(c, o, name, false, (size_t)components, integer ? lo : -HUGE_VAL, integer ? hi : HUGE_VAL, NULL))
        return false;
    if (integer)
        for (size_t i = 0; i < json_array_size(v); i++)
            if (!is_int(json_array_get(v, i))) {
                char item[64];
                snprintf(item, sizeof item, "%s[%zu]", name, i);
                return type_error(c, item, json_array_get(v, i), "an integer (the accessor's components are integers)");
            }
    return true;
}

static bool
check_accessor(checker *c, const json_t *o)
{
    long long view, component_type, count, offset = 0;
    const char *type;
    if (!get_index(c, o, "bufferView", false, "bufferViews", &view) ||
        !get_enum_int(c, o, "componentType", true, component_types, 6, component_type_names, &component_type) ||
        !get_uint(c, o, "count", true, 1, INT32_MAX, &count) ||
        !get_enum_string(c, o, "type", true, accessor_types, 7, &type) || !get_bool(c, o, "normalized") ||
        !get_string(c, o, "name", false, NULL) || !check_extensions(c, o, NULL))
        return false;
    if (json_object_get(o, "byteOffset")) {
        if (view < 0)
            return bad(c, CG_ERR_GLTF_SCHEMA, "byteOffset", "given without a bufferView");
        if (!get_uint(c, o, "byteOffset", false, 0, INT32_MAX, &offset))
            return false;
    }
    if (json_is_true(json_object_get(o, "normalized")) && (component_type == GL_FLOAT || component_type == GL_UINT))
        return bad(c, CG_ERR_GLTF_SCHEMA, "normalized", "only BYTE, UNSIGNED_BYTE, SHORT and UNSIGNED_SHORT accessors can be normalized");
    int components = 0;
    for (int i = 0; i < 7; i++)
        if (!strcmp(type, accessor_types[i]))
            components = accessor_type_components[i];
    if (type[0] == 'M' && offset % 4 != 0)
        return bad(c, CG_ERR_GLTF_SCHEMA, "byteOffset", "%lld: matrix accessors must be aligned to 4 bytes", offset);
    if (!check_bounds(c, o, "min", components, (int)component_type) ||
        !check_bounds(c, o, "max", components, (int)component_type))
        return false;
    json_t *sparse;
    if (!get_object(c, o, "sparse", false, &sparse))
        return false;
    if (!sparse)
        return true;
    size_t mark = enter_key(c, "sparse");
    json_t *indices, *values;
    long long sparse_count;
    static const int index_types[] = { GL_UBYTE, GL_USHORT, GL_UINT };
    bool ok = get_uint(c, sparse, "count", true, 1, INT32_MAX, &sparse_count) && check_extensions(c, sparse, NULL) &&
              get_object(c, sparse, "indices", true, &indices) && get_object(c, sparse, "values", true, &values);
    if (ok && sparse_count > count)
        ok = bad(c, CG_ERR_GLTF_SCHEMA, "count", "%lld overrides more elements than the accessor's %lld", sparse_count, count);
    if (ok) {
        size_t m = enter_key(c, "indices");
        ok = get_index(c, indices, "bufferView", true, "bufferViews", NULL) &&
             get_uint(c, indices, "byteOffset", false, 0, INT32_MAX, NULL) &&
             get_enum_int(c, indices, "componentType", true, index_types, 3,
                          "5121 (UNSIGNED_BYTE), 5123 (UNSIGNED_SHORT), 5125 (UNSIGNED_INT)", NULL) &&
             check_extensions(c, indices, NULL);
        leave(c, m);
    }
    if (ok) {
        size_t m = enter_key(c, "values");
        ok = get_index(c, values, "bufferView", true, "bufferViews", NULL) &&
             get_uint(c, values, "byteOffset", false, 0, INT32_MAX, NULL) && check_extensions(c, values, NULL);
        leave(c, m);
    }
    leave(c, mark);
    return ok;
}

static bool
check_buffer(checker *c, const json_t *o)
{
    const char *uri;
    if (!get_string(c, o, "uri", false, &uri) || !get_uint(c, o, "byteLength", true, 1, MAX_BYTES, NULL) ||
        !get_string(c, o, "name", false, NULL) || !check_extensions(c, o, NULL))
        return false;
    if (uri && !strncmp(uri, "data:", 5) && strncmp(uri, "data:application/octet-stream;base64,", 37) &&
        strncmp(uri, "data:application/gltf-buffer;base64,", 36))
        return bad(c, CG_ERR_GLTF_SCHEMA, "uri",
                   "a data URI must be 'data:application/octet-stream;base64,...' or "
                   "'data:application/gltf-buffer;base64,...'");
    return true;
}

static bool
check_buffer_view(checker *c, const json_t *o)
{
    static const int targets[] = { 34962, 34963 };
    long long buffer, offset = 0, length, stride = 0;
    if (!get_index(c, o, "buffer", true, "buffers", &buffer) ||
        !get_uint(c, o, "byteOffset", false, 0, MAX_BYTES, &offset) ||
        !get_uint(c, o, "byteLength", true, 1, MAX_BYTES, &length) ||
        !get_uint(c, o, "byteStride", false, 4, 252, &stride) ||
        !get_enum_int(c, o, "target", false, targets, 2, "34962 (ARRAY_BUFFER), 34963 (ELEMENT_ARRAY_BUFFER)", NULL) ||
        !get_string(c, o, "name", false, NULL) || !check_extensions(c, o, NULL))
        return false;
    if (stride % 4)
        return bad(c, CG_ERR_GLTF_SCHEMA, "byteStride", "%lld is not a multiple of 4", stride);
    if (stride > length)
        return bad(c, CG_ERR_GLTF_SCHEMA, "byteStride", "%lld is greater than byteLength %lld", stride, length);
    long long buffer_length = json_integer_value(
        json_object_get(json_array_get(json_object_get(c->root, "buffers"), (size_t)buffer), "byteLength"));
    if (offset + length > buffer_length)
        return bad(c, CG_ERR_GLTF_BUFFER, NULL, "bytes %lld..%lld do not fit buffers[%lld] (byteLength %lld)", offset,
                   offset + length, buffer, buffer_length);
    return true;
}

/* KHR_texture_transform on a textureInfo: offset and scale two numbers each, rotation a number
 * (radians), texCoord a set index. */
static bool
check_texture_transform(checker *c, const json_t *t)
{
    json_t *ext = json_object_get(json_object_get(t, "extensions"), "KHR_texture_transform");
    if (!ext)
        return true;
    size_t mark = enter_key(c, "extensions.KHR_texture_transform");
    bool ok = get_numbers(c, ext, "offset", false, 2, -HUGE_VAL, HUGE_VAL, NULL) &&
              get_number(c, ext, "rotation", false, -HUGE_VAL, HUGE_VAL, false, NULL) &&
              get_numbers(c, ext, "scale", false, 2, -HUGE_VAL, HUGE_VAL, NULL) &&
              get_uint(c, ext, "texCoord", false, 0, INT32_MAX, NULL) && check_extensions(c, ext, NULL);
    leave(c, mark);
    return ok;
}

static bool
check_texture_info(checker *c, const json_t *o, const char *name, bool normal, bool occlusion)
{
    json_t *t;
    if (!get_object(c, o, name, false, &t))
        return false;
    if (!t)
        return true;
    size_t mark = enter_key(c, name);
    bool ok = get_index(c, t, "index", true, "textures", NULL) &&
              get_uint(c, t, "texCoord", false, 0, INT32_MAX, NULL) &&
              (!normal || get_number(c, t, "scale", false, -INFINITY, INFINITY, false, NULL)) &&
              (!occlusion || get_number(c, t, "strength", false, 0, 1, false, NULL)) &&
              check_extensions(c, t, "KHR_texture_transform") && check_texture_transform(c, t);
    leave(c, mark);
    return ok;
}

/* The material extensions conegraph reads (their schemas' types and ranges). */
static bool
check_material_extensions(checker *c, const json_t *o)
{
    json_t *exts = json_object_get(o, "extensions");
    json_t *e;
    bool ok = true;
    size_t mark;
    if (ok && (e = json_object_get(exts, "KHR_materials_emissive_strength"))) {
        mark = enter_key(c, "extensions.KHR_materials_emissive_strength");
        ok = get_number(c, e, "emissiveStrength", false, 0, INFINITY, false, NULL);
        leave(c, mark);
    }
    if (ok && (e = json_object_get(exts, "KHR_materials_ior"))) {
        mark = enter_key(c, "extensions.KHR_materials_ior");
        double ior = 1.5;
        ok = get_number(c, e, "ior", false, 0, INFINITY, false, &ior);
        /* KHR_materials_ior: "ior": at least 1, or exactly 0 (an infinite ior). */
        if (ok && ior != 0 && ior < 1)
            ok = bad(c, CG_ERR_GLTF_SCHEMA, "ior", "%.17g is out of range (expected 0 or a number at least 1)", ior);
        leave(c, mark);
    }
    if (ok && (e = json_object_get(exts, "KHR_materials_specular"))) {
        mark = enter_key(c, "extensions.KHR_materials_specular");
        ok = get_number(c, e, "specularFactor", false, 0, 1, false, NULL) &&
             check_texture_info(c, e, "specularTexture", false, false) &&
             get_numbers(c, e, "specularColorFactor", false, 3, 0, HUGE_VAL, NULL) &&
             check_texture_info(c, e, "specularColorTexture", false, false);
        leave(c, mark);
    }
    if (ok && (e = json_object_get(exts, "KHR_materials_transmission"))) {
        mark = enter_key(c, "extensions.KHR_materials_transmission");
        ok = get_number(c, e, "transmissionFactor", false, 0, 1, false, NULL) &&
             check_texture_info(c, e, "transmissionTexture", false, false);
        leave(c, mark);
    }
    if (ok && (e = json_object_get(exts, "KHR_materials_volume"))) {
        mark = enter_key(c, "extensions.KHR_materials_volume");
        ok = get_number(c, e, "thicknessFactor", false, 0, INFINITY, false, NULL) &&
             check_texture_info(c, e, "thicknessTexture", false, false) &&
             get_number(c, e, "attenuationDistance", false, 0, INFINITY, true, NULL) &&
             get_numbers(c, e, "attenuationColor", false, 3, 0, 1, NULL);
        leave(c, mark);
    }
    return ok;
}

static bool
check_material(checker *c, const json_t *o)
{
    static const char *const modes[] = { "OPAQUE", "MASK", "BLEND" };
    json_t *pbr;
    if (!get_string(c, o, "name", false, NULL) || !get_object(c, o, "pbrMetallicRoughness", false, &pbr) ||
        !check_texture_info(c, o, "normalTexture", true, false) ||
        !check_texture_info(c, o, "occlusionTexture", false, true) ||
        !check_texture_info(c, o, "emissiveTexture", false, false) ||
        !get_numbers(c, o, "emissiveFactor", false, 3, 0, 1, NULL) ||
        !get_enum_string(c, o, "alphaMode", false, modes, 3, NULL) ||
        !get_number(c, o, "alphaCutoff", false, 0, INFINITY, false, NULL) || !get_bool(c, o, "doubleSided") ||
        !check_extensions(c, o,
                          "KHR_materials_emissive_strength KHR_materials_ior KHR_materials_specular "
                          "KHR_materials_transmission KHR_materials_volume"))
        return false;
    if (pbr) {
        size_t mark = enter_key(c, "pbrMetallicRoughness");
        bool ok = get_numbers(c, pbr, "baseColorFactor", false, 4, 0, 1, NULL) &&
                  check_texture_info(c, pbr, "baseColorTexture", false, false) &&
                  get_number(c, pbr, "metallicFactor", false, 0, 1, false, NULL) &&
                  get_number(c, pbr, "roughnessFactor", false, 0, 1, false, NULL) &&
                  check_texture_info(c, pbr, "metallicRoughnessTexture", false, false) &&
                  check_extensions(c, pbr, NULL);
        leave(c, mark);
        if (!ok)
            return false;
    }
    return check_material_extensions(c, o);
}

/* TEXCOORD_0, COLOR_1, ...: the set name and a decimal index without leading zeros. */
static int
semantic_index(const char *key, const char *set)
{
    size_t n = strlen(set);
    if (strncmp(key, set, n) || !key[n] || (key[n] == '0' && key[n + 1]))
        return -1;
    long index = 0;
    for (const char *p = key + n; *p; p++) {
        if (*p < '0' || *p > '9' || index > 100000)
            return -1;
        index = index * 10 + (*p - '0');
    }
    return (int)index;
}

static bool
check_attributes(checker *c, const json_t *a, bool target)
{
    static const char *const sets[] = { "TEXCOORD_", "COLOR_", "JOINTS_", "WEIGHTS_" };
    int count[4] = { 0 }, max[4] = { -1, -1, -1, -1 };
    const char *key;
    json_t *v;
    json_object_foreach((json_t *)a, key, v) {
        if (!check_index_value(c, key, v, "accessors", NULL, NULL))
            return false;
        if (key[0] == '_' || !strcmp(key, "POSITION") || !strcmp(key, "NORMAL") || !strcmp(key, "TANGENT"))
            continue;
        bool known = false;
        for (int s = 0; s < 4; s++) {
            int index = semantic_index(key, sets[s]);
            if (index >= 0) {
                known = true;
                count[s]++;
                max[s] = index > max[s] ? index : max[s];
            }
        }
        if (!known)
            return bad(c, CG_ERR_GLTF_SCHEMA, key, "not a glTF attribute name (POSITION, NORMAL, TANGENT, TEXCOORD_n, "
                                                   "COLOR_n, JOINTS_n, WEIGHTS_n, or _CUSTOM)");
    }
    for (int s = 0; s < 4 && !target; s++)
        if (count[s] != max[s] + 1)
            return bad(c, CG_ERR_GLTF_SCHEMA, NULL, "%sn attributes must be numbered from 0 without gaps", sets[s]);
    return true;
}

static bool
check_primitive(checker *c, const json_t *o)
{
    json_t *a;
    if (!get_object(c, o, "attributes", true, &a) || !get_index(c, o, "indices", false, "accessors", NULL) ||
        !get_index(c, o, "material", false, "materials", NULL) || !get_uint(c, o, "mode", false, 0, 6, NULL) ||
        !check_extensions(c, o, NULL))
        return false;
    if (json_object_size(a) == 0)
        return bad(c, CG_ERR_GLTF_SCHEMA, "attributes", "expected at least one attribute, found none");
    size_t mark = enter_key(c, "attributes");
    bool ok = check_attributes(c, a, false);
    leave(c, mark);
    json_t *targets = json_object_get(o, "targets");
    if (ok && targets) {
        if (!json_is_array(targets) || json_array_size(targets) == 0)
            return type_error(c, "targets", targets, "a non-empty array of objects");
        mark = enter_key(c, "targets");
        for (size_t i = 0; i < json_array_size(targets) && ok; i++) {
            json_t *t = json_array_get(targets, i);
            size_t m = enter_index(c, i);
            ok = json_is_object(t) ? check_attributes(c, t, true) : type_error(c, NULL, t, "an object");
            leave(c, m);
        }
        leave(c, mark);
    }
    return ok;
}

static bool
check_mesh(checker *c, const json_t *o)
{
    if (!get_string(c, o, "name", false, NULL) || !get_numbers(c, o, "weights", false, 0, -HUGE_VAL, HUGE_VAL, NULL) ||
        !check_extensions(c, o, NULL))
        return false;
    if (!json_object_get(o, "primitives"))
        return missing(c, "primitives", "array");
    return check_array_of(c, o, "primitives", check_primitive);
}

/* glTF-Validator's NODE_MATRIX_NON_TRS test: the last row is (0, 0, 0, 1), the determinant is
 * not 0, and recomposing translation, rotation and scale gives back a matrix of the same
 * infinity norm (within 5e-5). */
static bool
matrix_is_trs(const double m[16])
{
    if (m[3] != 0 || m[7] != 0 || m[11] != 0 || m[15] != 1)
        return false;
    double det = m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
                 m[8] * (m[1] * m[6] - m[5] * m[2]);
    if (det == 0 || !isfinite(det))
        return false;
    double s[3], r[9];
    for (int col = 0; col < 3; col++) {
        s[col] = sqrt(m[4 * col] * m[4 * col] + m[4 * col + 1] * m[4 * col + 1] + m[4 * col + 2] * m[4 * col + 2]);
        if (col == 0 && det < 0)
            s[0] = -s[0];
        for (int row = 0; row < 3; row++)
            r[3 * col + row] = m[4 * col + row] / s[col];
    }
    /* Rotation matrix -> unit quaternion -> rotation matrix (what a TRS node can hold). */
    double q[4], t = r[0] + r[4] + r[8];
    if (t > 0) {
        double k = 0.5 / sqrt(t + 1);
        q[3] = 0.25 / k, q[0] = (r[5] - r[7]) * k, q[1] = (r[6] - r[2]) * k, q[2] = (r[1] - r[3]) * k;
    } else if (r[0] > r[4] && r[0] > r[8]) {
        double k = 2 * sqrt(1 + r[0] - r[4] - r[8]);
        q[3] = (r[5] - r[7]) / k, q[0] = 0.25 * k, q[1] = (r[3] + r[1]) / k, q[2] = (r[6] + r[2]) / k;
    } else if (r[4] > r[8]) {
        double k = 2 * sqrt(1 + r[4] - r[0] - r[8]);
        q[3] = (r[6] - r[2]) / k, q[0] = (r[3] + r[1]) / k, q[1] = 0.25 * k, q[2] = (r[7] + r[5]) / k;
    } else {
        double k = 2 * sqrt(1 + r[8] - r[0] - r[4]);
        q[3] = (r[1] - r[3]) / k, q[0] = (r[6] + r[2]) / k, q[1] = (r[7] + r[5]) / k, q[2] = 0.25 * k;
    }
    double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    double x = q[0] / len, y = q[1] / len, z = q[2] / len, w = q[3] / len;
    double rr[9] = { 1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
                     2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                     2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y) };
    double back[16] = { 0 };
    for (int col = 0; col < 3; col++)
        for (int row = 0; row < 3; row++)
            back[4 * col + row] = rr[3 * col + row] * s[col];
    back[12] = m[12], back[13] = m[13], back[14] = m[14], back[15] = 1;
    double norm_m = 0, norm_back = 0;
    for (int col = 0; col < 4; col++) {
        double a = 0, b = 0;
        for (int row = 0; row < 4; row++)
            a += fabs(m[4 * col + row]), b += fabs(back[4 * col + row]);
        norm_m = a > norm_m ? a : norm_m;
        norm_back = b > norm_back ? b : norm_back;
    }
    return fabs(norm_m - norm_back) < 5e-5;
}

static bool
check_node(checker *c, const json_t *o)
{
    double matrix[16], rotation[4];
    long long mesh;
    if (!get_index(c, o, "camera", false, "cameras", NULL) ||
        !get_index_list(c, o, "children", false, "nodes") || !get_index(c, o, "skin", false, "skins", NULL) ||
        !get_numbers(c, o, "matrix", false, 16, -HUGE_VAL, HUGE_VAL, matrix) ||
        !get_index(c, o, "mesh", false, "meshes", &mesh) ||
        !get_numbers(c, o, "rotation", false, 4, -1, 1, rotation) ||
        !get_numbers(c, o, "scale", false, 3, -HUGE_VAL, HUGE_VAL, NULL) ||
        !get_numbers(c, o, "translation", false, 3, -HUGE_VAL, HUGE_VAL, NULL) ||
        !get_numbers(c, o, "weights", false, 0, -HUGE_VAL, HUGE_VAL, NULL) || !get_string(c, o, "name", false, NULL) ||
        !check_extensions(c, o, "KHR_lights_punctual"))
        return false;
    if (mesh < 0 && (json_object_get(o, "skin") || json_object_get(o, "weights")))
        return bad(c, CG_ERR_GLTF_SCHEMA, json_object_get(o, "skin") ? "skin" : "weights", "given without a mesh");
    bool trs = json_object_get(o, "translation") || json_object_get(o, "rotation") || json_object_get(o, "scale");
    if (json_object_get(o, "matrix")) {
        if (trs)
            return bad(c, CG_ERR_GLTF_SCHEMA, "matrix", "a node has either a matrix or translation/rotation/scale, not both");
        if (!matrix_is_trs(matrix))
            return bad(c, CG_ERR_GLTF_SCHEMA, "matrix", "not decomposable into translation, rotation and scale");
    }
    if (json_object_get(o, "rotation")) {
        double len = sqrt(rotation[0] * rotation[0] + rotation[1] * rotation[1] + rotation[2] * rotation[2] +
                          rotation[3] * rotation[3]);
        if (fabs(len - 1) > 0.00769) /* the validator's tolerance for unit 4-vectors */
            return bad(c, CG_ERR_GLTF_SCHEMA, "rotation", "not a unit quaternion (length %.9g)", len);
    }
    json_t *ext = json_object_get(json_object_get(o, "extensions"), "KHR_lights_punctual");
    if (ext) {
        size_t mark = enter_key(c, "extensions.KHR_lights_punctual");
        bool ok = true;
        json_t *v = json_object_get(ext, "light");
        if (!v)
            ok = missing(c, "light", "index");
        else
            ok = check_index_value(c, "light", v, "extensions.KHR_lights_punctual.lights", c->lights, NULL);
        leave(c, mark);
        return ok;
    }
    return true;
}

static bool
check_scene(checker *c, const json_t *o)
{
    return get_index_list(c, o, "nodes", false, "nodes") && get_string(c, o, "name", false, NULL) &&
           check_extensions(c, o, NULL);
}

static bool
check_camera(checker *c, const json_t *o)
{
    static const char *const types[] = { "perspective", "orthographic" };
    const char *type;
    if (!get_enum_string(c, o, "type", true, types, 2, &type) || !get_string(c, o, "name", false, NULL) ||
        !check_extensions(c, o, NULL))
        return false;
    const char *other = !strcmp(type, "perspective") ? "orthographic" : "perspective";
    if (json_object_get(o, other))
        return bad(c, CG_ERR_GLTF_SCHEMA, other, "given for a camera of type \"%s\"", type);
    json_t *p;
    if (!get_object(c, o, type, true, &p))
        return false;
    size_t mark = enter_key(c, type);
    double znear = 0, zfar = INFINITY, xmag = 1, ymag = 1;
    bool ok;
    if (!strcmp(type, "perspective")) {
        ok = get_number(c, p, "aspectRatio", false, 0, INFINITY, true, NULL) &&
             get_number(c, p, "yfov", true, 0, INFINITY, true, NULL) &&
             get_number(c, p, "zfar", false, 0, INFINITY, true, &zfar) &&
             get_number(c, p, "znear", true, 0, INFINITY, true, &znear);
    } else {
        ok = get_number(c, p, "xmag", true, -INFINITY, INFINITY, false, &xmag) &&
             get_number(c, p, "ymag", true, -INFINITY, INFINITY, false, &ymag) &&
             get_number(c, p, "zfar", true, 0, INFINITY, true, &zfar) &&
             get_number(c, p, "znear", true, 0, INFINITY, false, &znear);
        if (ok && (xmag == 0 || ymag == 0))
            ok = bad(c, CG_ERR_GLTF_SCHEMA, xmag == 0 ? "xmag" : "ymag", "must not be 0");
    }
    if (ok && zfar <= znear)
        ok = bad(c, CG_ERR_GLTF_SCHEMA, "zfar", "%.17g is not greater than znear %.17g", zfar, znear);
    ok = ok && check_extensions(c, p, NULL);
    leave(c, mark);
    return ok;
}

static bool
check_image(checker *c, const json_t *o)
{
    static const char *const mimes[] = { "image/jpeg", "image/png" };
    json_t *uri = json_object_get(o, "uri"), *view = json_object_get(o, "bufferView");
    if (!get_string(c, o, "uri", false, NULL) || !get_index(c, o, "bufferView", false, "bufferViews", NULL) ||
        !get_enum_string(c, o, "mimeType", false, mimes, 2, NULL) || !get_string(c, o, "name", false, NULL) ||
        !check_extensions(c, o, NULL))
        return false;
    if ((uri != NULL) == (view != NULL))
        return bad(c, CG_ERR_GLTF_SCHEMA, NULL, "exactly one of uri and bufferView must be given");
    if (view && !json_object_get(o, "mimeType"))
        return missing(c, "mimeType", "string (the image is in a bufferView)");
    return true;
}

static bool
check_texture(checker *c, const json_t *o)
{
    return get_index(c, o, "sampler", false, "samplers", NULL) && get_index(c, o, "source", false, "images", NULL) &&
           get_string(c, o, "name", false, NULL) && check_extensions(c, o, NULL);
}

static bool
check_sampler(checker *c, const json_t *o)
{
    static const int mag[] = { 9728, 9729 }, min[] = { 9728, 9729, 9984, 9985, 9986, 9987 },
                     wrap[] = { 33071, 33648, 10497 };
    return get_enum_int(c, o, "magFilter", false, mag, 2, "9728 (NEAREST), 9729 (LINEAR)", NULL) &&
           get_enum_int(c, o, "minFilter", false, min, 6, "9728, 9729, 9984, 9985, 9986, 9987", NULL) &&
           get_enum_int(c, o, "wrapS", false, wrap, 3, "33071, 33648, 10497", NULL) &&
           get_enum_int(c, o, "wrapT", false, wrap, 3, "33071, 33648, 10497", NULL) &&
           get_string(c, o, "name", false, NULL) && check_extensions(c, o, NULL);
}

static bool
check_skin(checker *c, const json_t *o)
{
    return get_index(c, o, "inverseBindMatrices", false, "accessors", NULL) &&
           get_index_list(c, o, "joints", true, "nodes") && get_index(c, o, "skeleton", false, "nodes", NULL) &&
           get_string(c, o, "name", false, NULL) && check_extensions(c, o, NULL);
}

/* Animations: the references, and what the Khronos glTF-Validator checks on the accessors a
 * sampler names (their JSON): an input is SCALAR of FLOAT with min and max, CUBICSPLINE has
 * two keys at least, no byteStride on an input's or output's bufferView, and per channel the
 * output's format for its path and its count (keys, three values a key for CUBICSPLINE),
 * no animated node with a matrix, no two channels of an animation on the same target. The
 * data (times increasing, unit rotations, min/max) is checked in gltf_adapter.cpp. Channels
 * on morph target weights are not read; only their references are checked. */

static json_t *
accessor_json(const checker *c, long long index)
{
    return json_array_get(json_object_get(c->root, "accessors"), (size_t)index);
}

/* "VEC3 of FLOAT", "VEC4 of normalized SHORT" */
static void
accessor_format(const json_t *a, char *buf, size_t size)
{
    static const int types[] = { GL_BYTE, GL_UBYTE, GL_SHORT, GL_USHORT, GL_UINT, GL_FLOAT };
    static const char *const names[] = { "BYTE", "UNSIGNED_BYTE", "SHORT", "UNSIGNED_SHORT", "UNSIGNED_INT", "FLOAT" };
    long long ct = json_integer_value(json_object_get(a, "componentType"));
    const char *name = "an unknown component type";
    for (int i = 0; i < 6; i++)
        if (ct == types[i])
            name = names[i];
    snprintf(buf, size, "%s of %s%s", json_string_value(json_object_get(a, "type")),
             json_is_true(json_object_get(a, "normalized")) ? "normalized " : "", name);
}

static bool
accessor_is(const json_t *a, const char *type, int component_type, bool normalized)
{
    return !strcmp(json_string_value(json_object_get(a, "type")), type) &&
           json_integer_value(json_object_get(a, "componentType")) == component_type &&
           json_is_true(json_object_get(a, "normalized")) == normalized;
}

/* An animation sampler's accessor must lie in a bufferView without byteStride. */
static bool
check_unstrided(checker *c, const char *name, long long index)
{
    json_t *view = json_object_get(accessor_json(c, index), "bufferView");
    if (!view)
        return true;
    json_t *bv = json_array_get(json_object_get(c->root, "bufferViews"), (size_t)json_integer_value(view));
    if (json_object_get(bv, "byteStride"))
        return bad(c, CG_ERR_GLTF_BUFFER, name,
                   "accessors[%lld] lies in bufferViews[%lld], which has a byteStride; the data of animation "
                   "samplers is tightly packed", index, (long long)json_integer_value(view));
    return true;
}

static bool
check_animation_sampler(checker *c, const json_t *o)
{
    static const char *const modes[] = { "LINEAR", "STEP", "CUBICSPLINE" };
    long long input, output;
    const char *mode;
    if (!get_index(c, o, "input", true, "accessors", &input) || !get_index(c, o, "output", true, "accessors", &output) ||
        !get_enum_string(c, o, "interpolation", false, modes, 3, &mode) || !check_extensions(c, o, NULL))
        return false;
    json_t *in = accessor_json(c, input);
    char format[96];
    accessor_format(in, format, sizeof format);
    if (!accessor_is(in, "SCALAR", GL_FLOAT, false))
        return bad(c, CG_ERR_GLTF_ACCESSOR, "input", "accessors[%lld] is %s; an animation input must be SCALAR of FLOAT",
                   input, format);
    if (!json_object_get(in, "min") || !json_object_get(in, "max"))
        return bad(c, CG_ERR_GLTF_ACCESSOR, "input", "accessors[%lld] must declare min and max (an animation input)",
                   input);
    long long keys = json_integer_value(json_object_get(in, "count"));
    if (mode && !strcmp(mode, "CUBICSPLINE") && keys < 2)
        return bad(c, CG_ERR_GLTF_ACCESSOR, "input", "accessors[%lld] has %lld key; CUBICSPLINE needs 2 at least",
                   input, keys);
    return check_unstrided(c, "input", input) && check_unstrided(c, "output", output);
}

static bool
check_animation_channel(checker *c, const json_t *o)
{
    static const char *const paths[] = { "translation", "rotation", "scale", "weights" };
    json_t *target, *s = json_object_get(o, "sampler");
    json_t *samplers = json_object_get(c->animation, "samplers");
    long long sampler, node;
    const char *path;
    if (!s)
        return missing(c, "sampler", "index");
    if (!check_index_value(c, "sampler", s, "samplers of this animation", samplers, &sampler) ||
        !get_object(c, o, "target", true, &target) || !check_extensions(c, o, NULL))
        return false;
    size_t mark = enter_key(c, "target");
    bool ok = get_index(c, target, "node", false, "nodes", &node) &&
              get_enum_string(c, target, "path", true, paths, 4, &path) && check_extensions(c, target, NULL);
    leave(c, mark);
    if (!ok || node < 0)
        return ok; /* without a node the channel is ignored (glTF 2.0, 3.11) */
    /* Two channels of one animation on the same node and path. */
    json_t *channels = json_object_get(c->animation, "channels");
    for (size_t k = 0; k < json_array_size(channels) && json_array_get(channels, k) != o; k++) {
        json_t *other = json_object_get(json_array_get(channels, k), "target");
        json_t *other_node = json_object_get(other, "node");
        if (other_node && json_integer_value(other_node) == node &&
            !strcmp(json_string_value(json_object_get(other, "path")), path))
            return bad(c, CG_ERR_GLTF_SCHEMA, "target", "the same node and path as channels[%zu]", k);
    }
    if (!strcmp(path, "weights"))
        return true;
    if (json_object_get(json_array_get(json_object_get(c->root, "nodes"), (size_t)node), "matrix"))
        return bad(c, CG_ERR_GLTF_SCHEMA, "target.node",
                   "nodes[%lld] has a matrix; only a node's translation, rotation and scale can be animated", node);
    json_t *so = json_array_get(samplers, (size_t)sampler);
    long long input = json_integer_value(json_object_get(so, "input"));
    long long output = json_integer_value(json_object_get(so, "output"));
    const char *mode = json_string_value(json_object_get(so, "interpolation"));
    json_t *out = accessor_json(c, output);
    bool rotation = !strcmp(path, "rotation");
    bool format_ok = rotation ? accessor_is(out, "VEC4", GL_FLOAT, false) || accessor_is(out, "VEC4", GL_BYTE, true) ||
                                    accessor_is(out, "VEC4", GL_UBYTE, true) || accessor_is(out, "VEC4", GL_SHORT, true) ||
                                    accessor_is(out, "VEC4", GL_USHORT, true)
                              : accessor_is(out, "VEC3", GL_FLOAT, false);
    char format[96];
    accessor_format(out, format, sizeof format);
    if (!format_ok)
        return bad(c, CG_ERR_GLTF_ACCESSOR, "sampler",
                   "its output accessors[%lld] is %s; a %s output must be %s", output, format, path,
                   rotation ? "VEC4 of FLOAT or of normalized BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT"
                            : "VEC3 of FLOAT");
    long long keys = json_integer_value(json_object_get(accessor_json(c, input), "count"));
    long long expected = keys * (mode && !strcmp(mode, "CUBICSPLINE") ? 3 : 1);
    long long count = json_integer_value(json_object_get(out, "count"));
    if (count != expected)
        return bad(c, CG_ERR_GLTF_ACCESSOR, "sampler",
                   "its output accessors[%lld] has %lld elements; %lld keys of %s need %lld", output, count, keys,
                   mode ? mode : "LINEAR", expected);
    return true;
}

static bool
check_animation(checker *c, const json_t *o)
{
    c->animation = o;
    if (!json_object_get(o, "channels"))
        return missing(c, "channels", "array");
    if (!json_object_get(o, "samplers"))
        return missing(c, "samplers", "array");
    return check_array_of(c, o, "samplers", check_animation_sampler) &&
           check_array_of(c, o, "channels", check_animation_channel) && get_string(c, o, "name", false, NULL) &&
           check_extensions(c, o, NULL);
}

static bool
check_light(checker *c, const json_t *o)
{
    static const char *const types[] = { "directional", "point", "spot" };
    const char *type;
    if (!get_enum_string(c, o, "type", true, types, 3, &type) || !get_numbers(c, o, "color", false, 3, 0, 1, NULL) ||
        !get_number(c, o, "intensity", false, 0, INFINITY, false, NULL) ||
        !get_number(c, o, "range", false, 0, INFINITY, true, NULL) || !get_string(c, o, "name", false, NULL) ||
        !check_extensions(c, o, NULL))
        return false;
    /* conegraph's own extra: a directional light's angular diameter, radians (cg/scene.h). */
    json_t *extras = json_object_get(o, "extras");
    if (json_is_object(extras) && json_object_get(extras, "conegraph_angular_diameter")) {
        size_t mark = enter_key(c, "extras");
        bool ok = get_number(c, extras, "conegraph_angular_diameter", false, 0, M_PI / 2, false, NULL);
        leave(c, mark);
        if (!ok)
            return false;
    }
    json_t *spot = json_object_get(o, "spot");
    if (!strcmp(type, "spot") && !spot)
        return missing(c, "spot", "object (the light is a spot light)");
    if (strcmp(type, "spot") && spot)
        return bad(c, CG_ERR_GLTF_SCHEMA, "spot", "given for a light of type \"%s\"", type);
    if (!spot)
        return true;
    if (!json_is_object(spot))
        return type_error(c, "spot", spot, "an object");
    size_t mark = enter_key(c, "spot");
    double inner = 0, outer = M_PI / 4;
    bool ok = get_number(c, spot, "innerConeAngle", false, 0, M_PI / 2, false, &inner) &&
              get_number(c, spot, "outerConeAngle", false, 0, M_PI / 2, true, &outer);
    if (ok && outer <= inner)
        ok = bad(c, CG_ERR_GLTF_SCHEMA, "outerConeAngle", "%.17g is not greater than innerConeAngle %.17g", outer, inner);
    ok = ok && check_extensions(c, spot, NULL);
    leave(c, mark);
    return ok;
}

/* ------------------------------------------------------------------ the whole file */

/* What extensionsRequired may name: the extensions conegraph implements (gltf_adapter.cpp keeps
 * the same list). */
#define supported_extensions read_extensions

static bool
check_string_list(checker *c, const char *name)
{
    json_t *v = json_object_get(c->root, name);
    if (!v)
        return true;
    if (!json_is_array(v) || json_array_size(v) == 0)
        return type_error(c, name, v, "a non-empty array of extension names");
    for (size_t i = 0; i < json_array_size(v); i++) {
        json_t *s = json_array_get(v, i);
        char item[64];
        snprintf(item, sizeof item, "%s[%zu]", name, i);
        if (!json_is_string(s))
            return type_error(c, item, s, "a string");
        for (size_t k = 0; k < i; k++)
            if (!strcmp(json_string_value(json_array_get(v, k)), json_string_value(s)))
                return bad(c, CG_ERR_GLTF_SCHEMA, item, "\"%s\" appears twice", json_string_value(s));
    }
    return true;
}

/* glTF 1.0 has no asset.version "2.x", keeps its objects in dictionaries keyed by name and
 * may leave the asset out: recognised here so that the user is told the version, not a type. */
static bool
looks_like_gltf1(const json_t *root)
{
    static const char *const dictionaries[] = { "meshes", "nodes", "scenes", "accessors", "buffers", "materials" };
    for (size_t i = 0; i < sizeof dictionaries / sizeof *dictionaries; i++)
        if (json_is_object(json_object_get(root, dictionaries[i])))
            return true;
    return json_is_string(json_object_get(root, "scene"));
}

static bool
check_asset(checker *c)
{
    json_t *asset = json_object_get(c->root, "asset");
    const char *version = NULL;
    if (json_is_object(asset))
        version = json_string_value(json_object_get(asset, "version"));
    if ((!version && looks_like_gltf1(c->root)) || (version && version[0] == '1' && version[1] == '.'))
        return cg_fail(c->err, CG_ERR_GLTF_VERSION,
                       "%s: glTF 1.0 is not supported (conegraph reads glTF 2.0; converters such as "
                       "gltf-pipeline or Blender turn 1.0 files into 2.0)", c->file);
    if (!asset)
        return missing(c, "asset", "object");
    if (!json_is_object(asset))
        return type_error(c, "asset", asset, "an object");
    size_t mark = enter_key(c, "asset");
    const char *min_version;
    bool ok = get_string(c, asset, "version", true, &version) && get_string(c, asset, "minVersion", false, &min_version) &&
              get_string(c, asset, "generator", false, NULL) && get_string(c, asset, "copyright", false, NULL);
    unsigned major = 0, minor = 0, min_major = 0, min_minor = 0;
    int end = 0;
    if (ok && (sscanf(version, "%u.%u%n", &major, &minor, &end) != 2 || version[end] || version[0] < '0' ||
               version[0] > '9' || strchr(version, '+') || strchr(version, '-') || strchr(version, ' ')))
        ok = cg_fail(c->err, CG_ERR_GLTF_VERSION, "%s: asset.version: \"%s\" is not a version MAJOR.MINOR (glTF 2.0 "
                                                  "files say \"2.0\")", c->file, version);
    else if (ok && major != 2)
        ok = cg_fail(c->err, CG_ERR_GLTF_VERSION, "%s: asset.version: glTF %s is not supported (conegraph reads glTF 2.x)",
                     c->file, version);
    end = 0;
    if (ok && min_version &&
        (sscanf(min_version, "%u.%u%n", &min_major, &min_minor, &end) != 2 || min_version[end] || min_version[0] < '0' ||
         min_version[0] > '9' || strchr(min_version, '+') || strchr(min_version, '-') || strchr(min_version, ' ')))
        ok = cg_fail(c->err, CG_ERR_GLTF_VERSION, "%s: asset.minVersion: \"%s\" is not a version MAJOR.MINOR", c->file,
                     min_version);
    else if (ok && min_version && (min_major > major || (min_major == major && min_minor > minor)))
        ok = cg_fail(c->err, CG_ERR_GLTF_VERSION, "%s: asset.minVersion: %s is greater than version %s", c->file,
                     min_version, version);
    else if (ok && min_version && (min_major != 2 || min_minor > 0))
        ok = cg_fail(c->err, CG_ERR_GLTF_VERSION, "%s: asset.minVersion: glTF %s is needed to read this file; conegraph "
                                                  "reads glTF 2.0", c->file, min_version);
    ok = ok && check_extensions(c, asset, NULL);
    leave(c, mark);
    return ok;
}

static bool
check_required_extensions(checker *c)
{
    if (!check_string_list(c, "extensionsUsed") || !check_string_list(c, "extensionsRequired"))
        return false;
    c->used = json_object_get(c->root, "extensionsUsed");
    json_t *required = json_object_get(c->root, "extensionsRequired");
    size_t i;
    json_t *e;
    json_array_foreach(required, i, e) {
        const char *name = json_string_value(e);
        bool used = false, known = false;
        size_t k;
        json_t *u;
        json_array_foreach(c->used, k, u) used = used || !strcmp(json_string_value(u), name);
        for (size_t s = 0; s < sizeof supported_extensions / sizeof *supported_extensions; s++)
            known = known || !strcmp(name, supported_extensions[s]);
        char item[64];
        snprintf(item, sizeof item, "extensionsRequired[%zu]", i);
        if (!used)
            return bad(c, CG_ERR_GLTF_SCHEMA, item, "\"%s\" is required but not listed in extensionsUsed", name);
        if (!known) {
            char list[512] = "";
            for (size_t s = 0; s < sizeof supported_extensions / sizeof *supported_extensions; s++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", s ? ", " : "", supported_extensions[s]);
            return cg_fail(c->err, CG_ERR_GLTF_EXTENSION,
                           "%s: requires extension '%s', which conegraph does not support (supported: %s)", c->file,
                           name, list);
        }
    }
    return true;
}

static bool
check_root(checker *c)
{
    json_t *root = c->root;
    if (!check_asset(c) || !check_required_extensions(c) || !check_extensions(c, root, "KHR_lights_punctual"))
        return false;
    json_t *lights = json_object_get(json_object_get(root, "extensions"), "KHR_lights_punctual");
    if (lights) {
        size_t mark = enter_key(c, "extensions.KHR_lights_punctual");
        json_t *list = json_object_get(lights, "lights");
        bool ok = list ? check_array_of(c, lights, "lights", check_light) : missing(c, "lights", "array");
        leave(c, mark);
        if (!ok)
            return false;
        c->lights = list;
    }
    static const struct {
        const char *name;
        check_fn fn;
    } arrays[] = {
        { "buffers", check_buffer },     { "bufferViews", check_buffer_view }, { "accessors", check_accessor },
        { "images", check_image },       { "samplers", check_sampler },        { "textures", check_texture },
        { "materials", check_material }, { "meshes", check_mesh },             { "cameras", check_camera },
        { "skins", check_skin },         { "nodes", check_node },              { "scenes", check_scene },
        { "animations", check_animation },
    };
    for (size_t i = 0; i < sizeof arrays / sizeof *arrays; i++)
        if (!check_array_of(c, root, arrays[i].name, arrays[i].fn))
            return false;
    /* A buffer without uri is the GLB's BIN chunk: only buffer 0 of a .glb that has one. */
    json_t *buffers = json_object_get(root, "buffers");
    for (size_t i = 0; i < json_array_size(buffers); i++) {
        json_t *b = json_array_get(buffers, i);
        if (json_object_get(b, "uri"))
            continue;
        if (i > 0 || c->glb_bin <= 0)
            return cg_fail(c->err, CG_ERR_GLTF_BUFFER, "%s: buffers[%zu]: no uri, and %s", c->file, i,
                           c->glb_bin < 0 ? "a .gltf file has no binary chunk to hold the buffer"
                           : i > 0      ? "only buffer 0 can be the GLB's binary chunk"
                                        : "the GLB has no binary (BIN) chunk");
        long long length = json_integer_value(json_object_get(b, "byteLength"));
        if (c->glb_bin < length)
            return cg_fail(c->err, CG_ERR_GLTF_BUFFER, "%s: buffers[0]: byteLength %lld, but the GLB's binary chunk "
                           "holds %lld bytes", c->file, length, c->glb_bin);
    }
    return get_index(c, root, "scene", false, "scenes", NULL);
}

bool
cg_gltf_check_json(const char *file, const char *json, size_t size, long long glb_bin, cg_error *err)
{
    if (size >= 3 && !memcmp(json, "\xEF\xBB\xBF", 3))
        return cg_fail(err, CG_ERR_GLTF_PARSE, "%s: the JSON starts with a UTF-8 byte order mark, which glTF forbids",
                       file);
    json_error_t jerr;
    /* Duplicate keys are refused: readers disagree on which one wins. */
    json_t *root = json_loadb(json, size, JSON_REJECT_DUPLICATES, &jerr);
    if (!root)
        return cg_fail(err, CG_ERR_GLTF_PARSE, "%s: invalid JSON at line %d, column %d: %s", file, jerr.line,
                       jerr.column, jerr.text);
    bool ok;
    if (!json_is_object(root)) {
        char buf[96];
        ok = cg_fail(err, CG_ERR_GLTF_PARSE, "%s: expected a JSON object at the top, found %s", file,
                     found(root, buf, sizeof buf));
    } else {
        checker c = { .file = file, .err = err, .root = root, .glb_bin = glb_bin };
        ok = check_root(&c);
    }
    json_decref(root);
    return ok;
}
