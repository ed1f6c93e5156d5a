/* cg/error.h: the project's error record and the one table of named errors.
 *
 * Declares: cg_status (enum), cg_error (struct), cg_fail, cg_error_clear,
 *           cg_status_name, cg_status_exit_code.
 *
 * Every function that can fail returns bool (true = success) and fills a
 * cg_error whose message is fit for a user: file, line, what was expected.
 * Tests assert on cg_error.status, not on message text.
 */
#ifndef CG_ERROR_H
#define CG_ERROR_H

#include <stdbool.h>

/* X(name, exit_code, summary). Exit code 2 = bad input or usage, 1 = failed while running. */
#define CG_STATUS_TABLE(X)                                                          \
    X(CG_OK,                       0, "no error")                                   \
    X(CG_ERR_USAGE,                2, "bad command-line usage")                     \
    X(CG_ERR_FILE_NOT_FOUND,       2, "input file not found or unreadable")         \
    X(CG_ERR_IO,                   1, "input/output failure")                       \
    X(CG_ERR_OUTPUT_PATH,          2, "output file cannot be written where it was asked") \
    X(CG_ERR_OUT_OF_MEMORY,        1, "out of memory")                              \
    X(CG_ERR_SCENE_UNKNOWN,        2, "unknown scene name")                         \
    X(CG_ERR_SCENE_PARAM,          2, "bad built-in scene parameter")               \
    X(CG_ERR_GLTF_PARSE,           2, "not a valid glTF file")                      \
    X(CG_ERR_GLTF_VERSION,         2, "unsupported glTF version")                   \
    X(CG_ERR_GLTF_SCHEMA,          2, "glTF field missing, of the wrong type or against the specification") \
    X(CG_ERR_GLTF_BUFFER,          2, "glTF buffer missing or too short")           \
    X(CG_ERR_GLTF_ACCESSOR,        2, "glTF accessor of the wrong type or count")   \
    X(CG_ERR_GLTF_INDEX_RANGE,     2, "glTF index out of range")                    \
    X(CG_ERR_GLTF_NONFINITE,       2, "glTF position is NaN or infinite")           \
    X(CG_ERR_GLTF_NODE_CYCLE,      2, "glTF node graph has a cycle")                \
    X(CG_ERR_GLTF_NO_TRIANGLES,    2, "glTF scene has no triangles")                \
    X(CG_ERR_GLTF_EXTENSION,       2, "glTF requires an unsupported extension")     \
    X(CG_ERR_IMAGE_FORMAT,         2, "unsupported image format or size")           \
    X(CG_ERR_GL_CONTEXT,           1, "no GL 4.5 core context could be created")    \
    X(CG_ERR_GL,                   1, "GL error")                                   \
    X(CG_ERR_SHADER_NOT_FOUND,     1, "shader file not found")                      \
    X(CG_ERR_SHADER_COMPILE,       1, "shader failed to compile or link")           \
    X(CG_ERR_GRAPH_SYNTAX,         2, "graph file is not valid JSON")               \
    X(CG_ERR_GRAPH_SCHEMA,         2, "graph file field missing or of wrong type")  \
    X(CG_ERR_GRAPH_VERSION,        2, "unsupported graph file version")             \
    X(CG_ERR_GRAPH_UNKNOWN_TYPE,   2, "unknown pass type")                          \
    X(CG_ERR_GRAPH_UNKNOWN_PARAM,  2, "unknown pass parameter")                     \
    X(CG_ERR_GRAPH_PARAM_TYPE,     2, "parameter value of the wrong type")          \
    X(CG_ERR_GRAPH_PARAM_RANGE,    2, "parameter value out of range")               \
    X(CG_ERR_GRAPH_DUPLICATE,      2, "duplicate name")                             \
    X(CG_ERR_GRAPH_DANGLING,       2, "reference to a pass, input or output that does not exist") \
    X(CG_ERR_GRAPH_MISSING_INPUT,  2, "required input not connected")               \
    X(CG_ERR_GRAPH_CYCLE,          2, "graph has a cycle")                          \
    X(CG_ERR_GRAPH_NO_OUTPUT,      2, "graph marks no output")                      \
    X(CG_ERR_GRAPH_INCOMPATIBLE,   2, "connected resources of incompatible kind or format") \
    X(CG_ERR_GRAPH_TOO_LARGE,      2, "resource beyond the GL limits")              \
    X(CG_ERR_GRAPH_MEMORY_BUDGET,  2, "graph needs more GPU memory than allowed")   \
    X(CG_ERR_PLUGIN_LOAD,          2, "plugin cannot be loaded")                    \
    X(CG_ERR_PLUGIN_ABI,           2, "plugin ABI version mismatch")                \
    X(CG_ERR_PASS,                 1, "pass failed while running")

typedef enum cg_status {
#define CG_X_ENUM(name, code, summary) name,
    CG_STATUS_TABLE(CG_X_ENUM)
#undef CG_X_ENUM
    CG_STATUS_COUNT
} cg_status;

typedef struct cg_error {
    cg_status status;
    char message[2048];
} cg_error;

/* Records the first failure (a later one does not overwrite it) and returns false,
 * so that callers can write `return cg_fail(err, CG_ERR_IO, "%s: ...", path);`.
 * err may be NULL. */
bool cg_fail(cg_error *err, cg_status status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

void cg_error_clear(cg_error *err);

const char *cg_status_name(cg_status status);
const char *cg_status_summary(cg_status status);
int cg_status_exit_code(cg_status status);

#endif
