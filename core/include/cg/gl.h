/* cg/gl.h: GL 4.5 core contexts (EGL surfaceless, OSMesa, GLFW window) and GL debug reporting.
 *
 * Declares: cg_context_backend, cg_context_desc, cg_context, cg_context_create,
 *           cg_context_destroy, cg_context_backend_name, cg_context_backend_parse,
 *           cg_context_gl_error_count, cg_context_reset_gl_error_count, cg_context_version,
 *           cg_context_renderer, cg_context_window, cg_context_swap.
 *
 * The GL loader is glad, generated at build time; include this header, never <GL/gl.h>.
 * Every KHR_debug message goes to the log; messages of type ERROR are also counted
 * so that tests can fail on any GL error.
 */
#ifndef CG_GL_H
#define CG_GL_H

#include <stdbool.h>
#include <glad/gl.h>

#include "cg/error.h"

typedef enum cg_context_backend {
    CG_CONTEXT_AUTO,   /* CONEGRAPH_CONTEXT env var, else EGL, then OSMesa */
    CG_CONTEXT_EGL,    /* surfaceless EGL: the headless default */
    CG_CONTEXT_OSMESA,
    CG_CONTEXT_GLFW    /* a visible window: needs a display */
} cg_context_backend;

typedef struct cg_context_desc {
    cg_context_backend backend; /* 0 = CG_CONTEXT_AUTO */
    int width, height;          /* window size for GLFW; 0 = 1280x720. Headless contexts have no default framebuffer. */
    const char *title;          /* window title; NULL = "conegraph" */
    bool debug;                 /* request a debug context (synchronous KHR_debug output) */
} cg_context_desc;

typedef struct cg_context cg_context;

/* Creates and makes current a GL 4.5 core context. With CG_CONTEXT_AUTO, tries each
 * headless backend in turn; on failure the error names every backend tried and why it failed. */
bool cg_context_create(const cg_context_desc *desc, cg_context **out, cg_error *err);
void cg_context_destroy(cg_context *ctx);

const char *cg_context_backend_name(cg_context_backend backend);
/* "egl", "osmesa", "glfw", "auto"; false for anything else. */
bool cg_context_backend_parse(const char *name, cg_context_backend *out);
cg_context_backend cg_context_get_backend(const cg_context *ctx);

/* GL_VERSION and GL_RENDERER strings of the current context. */
const char *cg_context_version(const cg_context *ctx);
const char *cg_context_renderer(const cg_context *ctx);

/* KHR_debug messages of type GL_DEBUG_TYPE_ERROR seen since creation or the last reset. */
int cg_context_gl_error_count(const cg_context *ctx);
void cg_context_reset_gl_error_count(cg_context *ctx);

/* GLFW only: the GLFWwindow* (as void*, so this header does not pull in GLFW) and buffer swap. */
void *cg_context_window(const cg_context *ctx);
void cg_context_swap(cg_context *ctx);

#endif
