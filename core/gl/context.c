/* GL 4.5 core contexts: EGL surfaceless, OSMesa and a GLFW window, with KHR_debug
 * messages routed to the log and GL errors counted per context.
 *
 * GL entry points are loaded by glad through each backend's own GetProcAddress:
 * linking libOSMesa directly misses the DSA entry points (Mesa 22 on Debian 12: its libOSMesa exports only the GL 1.x-3.x symbols).
 */
#include "cg/gl.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
/* glad/gl.h (through cg/gl.h) defines the guards of <GL/gl.h>, so osmesa.h uses glad's types. */
#include <GL/osmesa.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "cg/log.h"

struct cg_context {
    cg_context_backend backend;
    int gl_error_count;          /* KHR_debug messages of type ERROR; see debug_callback */
    char version[256];
    char renderer[256];

    EGLDisplay egl_display;
    EGLContext egl_context;

    OSMesaContext osmesa;
    unsigned char osmesa_buffer[4]; /* 1x1 RGBA: OSMesaMakeCurrent needs a buffer; we render to FBOs */

    GLFWwindow *window;
    bool glfw_initialised;
};

/* Why one backend failed, gathered into the CG_ERR_GL_CONTEXT message under AUTO. */
typedef struct backend_failure {
    char reason[512];
} backend_failure;

static bool
failed(backend_failure *why, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static bool
failed(backend_failure *why, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why->reason, sizeof why->reason, fmt, ap);
    va_end(ap);
    return false;
}

const char *
cg_context_backend_name(cg_context_backend backend)
{
    switch (backend) {
    case CG_CONTEXT_AUTO: return "auto";
    case CG_CONTEXT_EGL: return "egl";
    case CG_CONTEXT_OSMESA: return "osmesa";
    case CG_CONTEXT_GLFW: return "glfw";
    }
    return "unknown";
}

bool
cg_context_backend_parse(const char *name, cg_context_backend *out)
{
    static const cg_context_backend all[] = { CG_CONTEXT_AUTO, CG_CONTEXT_EGL, CG_CONTEXT_OSMESA,
                                              CG_CONTEXT_GLFW };
    if (!name)
        return false;
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) {
        if (!strcmp(name, cg_context_backend_name(all[i]))) {
            *out = all[i];
            return true;
        }
    }
    return false;
}

cg_context_backend
cg_context_get_backend(const cg_context *ctx)
{
    return ctx->backend;
}

/* ---- KHR_debug ---------------------------------------------------------------------- */

static const char *
debug_source_name(GLenum source)
{
    switch (source) {
    case GL_DEBUG_SOURCE_API: return "api";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window system";
    case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader compiler";
    case GL_DEBUG_SOURCE_THIRD_PARTY: return "third party";
    case GL_DEBUG_SOURCE_APPLICATION: return "application";
    default: return "other";
    }
}

static const char *
debug_type_name(GLenum type)
{
    switch (type) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behaviour";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    case GL_DEBUG_TYPE_MARKER: return "marker";
    case GL_DEBUG_TYPE_PUSH_GROUP: return "push group";
    case GL_DEBUG_TYPE_POP_GROUP: return "pop group";
    default: return "other";
    }
}

static void GLAD_API_PTR
debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
               const GLchar *message, const void *user)
{
    /* userParam is the context itself: the count lives with the GL state it describes. */
    cg_context *ctx = (cg_context *)user;
    (void)length;
    if (type == GL_DEBUG_TYPE_ERROR && source == GL_DEBUG_SOURCE_SHADER_COMPILER) {
        /* Mesa repeats each failed compile's log here as an ERROR. It is not a GL API
         * error: cg_program_* reports it through cg_error, with the driver's source-string
         * numbers rewritten to file names, so it is neither counted nor shown twice. */
        cg_log_debug("GL %s: %s", debug_source_name(source), message);
    } else if (type == GL_DEBUG_TYPE_ERROR) {
        ctx->gl_error_count++;
        cg_log_error("GL %s error %u: %s", debug_source_name(source), id, message);
    } else if (type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR && severity == GL_DEBUG_SEVERITY_HIGH) {
        cg_log_warn("GL %s %s %u: %s", debug_source_name(source), debug_type_name(type), id, message);
    } else {
        cg_log_debug("GL %s %s %u: %s", debug_source_name(source), debug_type_name(type), id, message);
    }
}

/* Synchronous output always, not only for debug contexts: an error is then reported (and
 * counted) inside the GL call that caused it, so a test's count after a call is exact
 * and a breakpoint in debug_callback shows the culprit. llvmpipe executes GL calls on
 * the calling thread anyway, so this costs nothing measurable there. */
static void
install_debug_output(cg_context *ctx)
{
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debug_callback, ctx);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, NULL, GL_TRUE);
}

/* ---- common GL checks after a backend made a context current --------------------- */

static bool
load_and_check_gl(cg_context *ctx, GLADloadfunc load, backend_failure *why)
{
    int glad_version = gladLoadGL(load);
    if (!glad_version)
        return failed(why, "the GL loader could not load GL entry points through %s",
                      cg_context_backend_name(ctx->backend));
    const char *version = (const char *)glGetString(GL_VERSION);
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    if (major * 10 + minor < 45)
        return failed(why, "GL 4.5 required, the context reports %d.%d (\"%s\")", major, minor,
                      version ? version : "?");
    if (!(profile & GL_CONTEXT_CORE_PROFILE_BIT))
        return failed(why, "GL core profile required, the context reports profile mask 0x%x", profile);
    if (!glDebugMessageCallback || !glDispatchCompute || !glCreateTextures)
        return failed(why, "GL %d.%d context lacks KHR_debug, compute or DSA entry points", major,
                      minor);
    snprintf(ctx->version, sizeof ctx->version, "%s", version ? version : "");
    snprintf(ctx->renderer, sizeof ctx->renderer, "%s", renderer ? renderer : "");
    install_debug_output(ctx);
    return true;
}

/* ---- EGL surfaceless ---------------------------------------------------------------- */

static const char *
egl_error_name(EGLint e)
{
    switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "unknown EGL error";
    }
}

static bool
has_extension(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)); p += n) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return true;
    }
    return false;
}

static GLADapiproc
egl_load(const char *name)
{
    return (GLADapiproc)eglGetProcAddress(name);
}

static void
egl_release(cg_context *ctx)
{
    if (ctx->egl_display == EGL_NO_DISPLAY)
        return;
    eglMakeCurrent(ctx->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (ctx->egl_context != EGL_NO_CONTEXT)
        eglDestroyContext(ctx->egl_display, ctx->egl_context);
    /* The surfaceless display is one per process; terminating it also invalidates any
     * other EGL context on it, so cg contexts must not overlap in time (they are made
     * current on creation and never switched, so they cannot be used together anyway). */
    eglTerminate(ctx->egl_display);
    eglReleaseThread();
    ctx->egl_display = EGL_NO_DISPLAY;
    ctx->egl_context = EGL_NO_CONTEXT;
}

static bool
egl_create(cg_context *ctx, const cg_context_desc *desc, backend_failure *why)
{
    const char *client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!has_extension(client_ext, "EGL_MESA_platform_surfaceless"))
        return failed(why, "EGL client extension EGL_MESA_platform_surfaceless missing");

    /* eglGetPlatformDisplay is EGL 1.5; the EXT form covers 1.4 libraries. */
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplay");
    if (!get_platform_display)
        get_platform_display =
            (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_platform_display)
        return failed(why, "neither eglGetPlatformDisplay nor eglGetPlatformDisplayEXT is available");

    ctx->egl_display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (ctx->egl_display == EGL_NO_DISPLAY)
        return failed(why, "eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA) failed: %s",
                      egl_error_name(eglGetError()));
    EGLint major = 0, minor = 0;
    if (!eglInitialize(ctx->egl_display, &major, &minor)) {
        EGLint e = eglGetError();
        ctx->egl_display = EGL_NO_DISPLAY;
        return failed(why, "eglInitialize on the surfaceless display failed: %s", egl_error_name(e));
    }
    const char *dpy_ext = eglQueryString(ctx->egl_display, EGL_EXTENSIONS);
    if (!has_extension(dpy_ext, "EGL_KHR_surfaceless_context"))
        return failed(why, "EGL %d.%d display lacks EGL_KHR_surfaceless_context", major, minor);
    if (!eglBindAPI(EGL_OPENGL_API))
        return failed(why, "eglBindAPI(EGL_OPENGL_API) failed: %s", egl_error_name(eglGetError()));

    EGLConfig config = (EGLConfig)0; /* EGL_NO_CONFIG_KHR */
    if (!has_extension(dpy_ext, "EGL_KHR_no_config_context")) {
        const EGLint config_attribs[] = { EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0,
                                          EGL_NONE };
        EGLint n = 0;
        if (!eglChooseConfig(ctx->egl_display, config_attribs, &config, 1, &n) || n < 1)
            return failed(why, "no EGL config renders OpenGL: %s", egl_error_name(eglGetError()));
    }
    /* EGL_CONTEXT_OPENGL_DEBUG is an EGL 1.5 attribute; ask for it only there. */
    bool debug_attrib = desc->debug && (major > 1 || minor >= 5);
    const EGLint context_attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4,
        EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        debug_attrib ? EGL_CONTEXT_OPENGL_DEBUG : EGL_NONE, EGL_TRUE,
        EGL_NONE
    };
    ctx->egl_context = eglCreateContext(ctx->egl_display, config, EGL_NO_CONTEXT, context_attribs);
    if (ctx->egl_context == EGL_NO_CONTEXT)
        return failed(why, "eglCreateContext(GL 4.5 core) failed: %s", egl_error_name(eglGetError()));
    if (!eglMakeCurrent(ctx->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx->egl_context))
        return failed(why, "eglMakeCurrent(EGL_NO_SURFACE) failed: %s", egl_error_name(eglGetError()));
    return load_and_check_gl(ctx, egl_load, why);
}

/* ---- OSMesa --------------------------------------------------------------------------- */

static GLADapiproc
osmesa_load(const char *name)
{
    return (GLADapiproc)OSMesaGetProcAddress(name);
}

static void
osmesa_release(cg_context *ctx)
{
    if (!ctx->osmesa)
        return;
    OSMesaDestroyContext(ctx->osmesa);
    ctx->osmesa = NULL;
}

static bool
osmesa_create(cg_context *ctx, const cg_context_desc *desc, backend_failure *why)
{
    (void)desc; /* OSMesa has no debug-context attribute; KHR_debug output is enabled below anyway */
    const int attribs[] = {
        OSMESA_FORMAT, OSMESA_RGBA,
        OSMESA_DEPTH_BITS, 0,
        OSMESA_STENCIL_BITS, 0,
        OSMESA_ACCUM_BITS, 0,
        OSMESA_PROFILE, OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION, 4,
        OSMESA_CONTEXT_MINOR_VERSION, 5,
        0
    };
    ctx->osmesa = OSMesaCreateContextAttribs(attribs, NULL);
    if (!ctx->osmesa)
        return failed(why, "OSMesaCreateContextAttribs(GL 4.5 core) returned NULL");
    if (!OSMesaMakeCurrent(ctx->osmesa, ctx->osmesa_buffer, GL_UNSIGNED_BYTE, 1, 1))
        return failed(why, "OSMesaMakeCurrent on a 1x1 RGBA buffer failed");
    return load_and_check_gl(ctx, osmesa_load, why);
}

/* ---- GLFW window ---------------------------------------------------------------------- */

static const char *
glfw_last_error(void)
{
    const char *description = NULL;
    glfwGetError(&description);
    return description ? description : "no description";
}

static GLADapiproc
glfw_load(const char *name)
{
    return (GLADapiproc)glfwGetProcAddress(name);
}

static void
glfw_release(cg_context *ctx)
{
    if (ctx->window)
        glfwDestroyWindow(ctx->window);
    ctx->window = NULL;
    if (ctx->glfw_initialised)
        glfwTerminate();
    ctx->glfw_initialised = false;
}

static bool
glfw_create(cg_context *ctx, const cg_context_desc *desc, backend_failure *why)
{
    /* glfwInit would fail too, but say plainly what is missing. */
    const char *display = getenv("DISPLAY");
    const char *wayland = getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland))
        return failed(why, "no display: DISPLAY is not set (run under xvfb-run for a virtual one)");
    if (!glfwInit())
        return failed(why, "glfwInit failed: %s", glfw_last_error());
    ctx->glfw_initialised = true;
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, desc->debug ? GLFW_TRUE : GLFW_FALSE);
    int width = desc->width > 0 ? desc->width : 1280;
    int height = desc->height > 0 ? desc->height : 720;
    ctx->window = glfwCreateWindow(width, height, desc->title ? desc->title : "conegraph", NULL, NULL);
    if (!ctx->window)
        return failed(why, "glfwCreateWindow(%dx%d, GL 4.5 core) failed: %s", width, height,
                      glfw_last_error());
    glfwMakeContextCurrent(ctx->window);
    return load_and_check_gl(ctx, glfw_load, why);
}

/* ---- public ------------------------------------------------------------------------- */

static void
release(cg_context *ctx)
{
    switch (ctx->backend) {
    case CG_CONTEXT_EGL: egl_release(ctx); break;
    case CG_CONTEXT_OSMESA: osmesa_release(ctx); break;
    case CG_CONTEXT_GLFW: glfw_release(ctx); break;
    case CG_CONTEXT_AUTO: break;
    }
}

static bool
try_backend(cg_context *ctx, cg_context_backend backend, const cg_context_desc *desc,
            backend_failure *why)
{
    ctx->backend = backend;
    bool ok = false;
    switch (backend) {
    case CG_CONTEXT_EGL: ok = egl_create(ctx, desc, why); break;
    case CG_CONTEXT_OSMESA: ok = osmesa_create(ctx, desc, why); break;
    case CG_CONTEXT_GLFW: ok = glfw_create(ctx, desc, why); break;
    case CG_CONTEXT_AUTO: ok = failed(why, "AUTO is not a backend"); break;
    }
    if (!ok) {
        release(ctx);
        ctx->gl_error_count = 0;
    }
    return ok;
}

bool
cg_context_create(const cg_context_desc *desc, cg_context **out, cg_error *err)
{
    static const cg_context_desc defaults = { 0 };
    if (!desc)
        desc = &defaults;
    *out = NULL;

    cg_context_backend order[2] = { desc->backend, CG_CONTEXT_AUTO };
    int count = 1;
    const char *origin = "requested";
    if (desc->backend == CG_CONTEXT_AUTO) {
        const char *env = getenv("CONEGRAPH_CONTEXT");
        if (env && *env) {
            if (!cg_context_backend_parse(env, &order[0]))
                return cg_fail(err, CG_ERR_GL_CONTEXT,
                               "CONEGRAPH_CONTEXT=%s: expected egl, osmesa, glfw or auto", env);
            origin = "CONEGRAPH_CONTEXT";
        }
        if (order[0] == CG_CONTEXT_AUTO) {
            order[0] = CG_CONTEXT_EGL;
            order[1] = CG_CONTEXT_OSMESA;
            count = 2;
            origin = "auto";
        }
    } else if (desc->backend != CG_CONTEXT_EGL && desc->backend != CG_CONTEXT_OSMESA &&
               desc->backend != CG_CONTEXT_GLFW) {
        return cg_fail(err, CG_ERR_GL_CONTEXT, "unknown context backend %d", (int)desc->backend);
    }

    cg_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory allocating a GL context");
    ctx->egl_display = EGL_NO_DISPLAY;
    ctx->egl_context = EGL_NO_CONTEXT;

    backend_failure why[2];
    for (int i = 0; i < count; i++) {
        if (try_backend(ctx, order[i], desc, &why[i])) {
            cg_log_debug("GL context: %s, GL %s, %s", cg_context_backend_name(ctx->backend),
                         ctx->version, ctx->renderer);
            *out = ctx;
            return true;
        }
        cg_log_debug("GL context backend %s failed: %s", cg_context_backend_name(order[i]),
                     why[i].reason);
    }
    free(ctx);
    if (count == 1)
        return cg_fail(err, CG_ERR_GL_CONTEXT, "no GL 4.5 core context (%s backend): %s: %s", origin,
                       cg_context_backend_name(order[0]), why[0].reason);
    return cg_fail(err, CG_ERR_GL_CONTEXT, "no GL 4.5 core context; tried %s: %s; %s: %s",
                   cg_context_backend_name(order[0]), why[0].reason,
                   cg_context_backend_name(order[1]), why[1].reason);
}

void
cg_context_destroy(cg_context *ctx)
{
    if (!ctx)
        return;
    /* The callback's userParam is about to dangle: detach it while the context is current. */
    glDebugMessageCallback(NULL, NULL);
    release(ctx);
    free(ctx);
}

const char *
cg_context_version(const cg_context *ctx)
{
    return ctx->version;
}

const char *
cg_context_renderer(const cg_context *ctx)
{
    return ctx->renderer;
}

int
cg_context_gl_error_count(const cg_context *ctx)
{
    return ctx->gl_error_count;
}

void
cg_context_reset_gl_error_count(cg_context *ctx)
{
    ctx->gl_error_count = 0;
}

void *
cg_context_window(const cg_context *ctx)
{
    return ctx->window;
}

void
cg_context_swap(cg_context *ctx)
{
    if (ctx->window)
        glfwSwapBuffers(ctx->window);
}
