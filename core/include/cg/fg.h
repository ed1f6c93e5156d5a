/* cg/fg.h: the frame graph: pass types, their parameters and resources, compile and execute.
 *
 * Declares:
 *   pass types   FG_ABI_VERSION, fg_param_type, fg_param_stage, fg_param_stage_name, fg_param_values,
 *                FG_PARAM_VALUES, fg_param_bound, fg_param_desc, fg_pass_type
 *   resources    fg_resource_kind, fg_access, fg_resource_desc, fg_resource_bytes
 *   registry     fg_registry, fg_registry_create, fg_registry_destroy, fg_registry_add,
 *                fg_registry_find, fg_registry_count, fg_registry_at, fg_param_values_text,
 *                fg_param_dependency_text, fg_registry_load_plugin,
 *                fg_registry_load_plugin_dirs, fg_plugin_register_fn
 *   declare      fg_declare, fg_declare_input, fg_declare_output, fg_declare_nothing_to_do
 *   pass access  fg_pass, fg_pass_name, fg_pass_type_of, fg_pass_frame, fg_param_int,
 *                fg_param_float, fg_param_bool, fg_param_enum, fg_param_string,
 *                fg_param_active, fg_pass_check_params, fg_slot, FG_NO_SLOT, fg_pass_slot,
 *                fg_pass_slot_if_declared, fg_slot_present, fg_slot_texture, fg_slot_buffer,
 *                fg_slot_resource, fg_input_present, fg_texture, fg_buffer, fg_resource,
 *                fg_pass_report_rebuilt, fg_pass_rebuilt, FG_READS_COUNTER, fg_pass_report_reads,
 *                fg_pass_reads, fg_pass_reads_text
 *   graph        fg_graph, fg_source_loc, fg_graph_create, fg_graph_destroy, fg_graph_add_pass,
 *                fg_graph_set_param, fg_graph_connect, fg_graph_mark_output, fg_graph_compile,
 *                fg_graph_prepare, fg_graph_prepare_pass, fg_graph_execute, introspection and
 *                report functions
 *
 * A pass type is static data plus four callbacks. A pass instance (fg_pass) is a node of
 * a graph with parameter values. declare() states the instance's inputs and outputs for
 * the current parameters and scene; the graph validates, culls, orders, allocates and
 * inserts memory barriers; prepare() compiles shaders once; execute() runs every frame.
 * Built-in passes and plugins register through the same fg_registry_add().
 */
#ifndef CG_FG_H
#define CG_FG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <glad/gl.h>

#include "cg/camera.h"
#include "cg/error.h"
#include "cg/gpu_scene.h"
#include "cg/scene.h"

/* Bumped whenever fg_pass_type or any function a pass calls changes incompatibly.
 * 2: fg_param_desc gained its constraints (allowed values, power of two, step hints,
 *    dependencies between parameters).
 * 3: cg_gpu_scene lost its no-shadow fallback and cg_gpu_scene_bind_shadow (now the pass SDK's,
 *    sdk/shadow.h).
 * 4: fg_param_desc gained its stage. */
#define FG_ABI_VERSION 5u

/* ---------------------------------------------------------------- parameters */

/* What a change of a parameter's value redoes, so that an interface (the demo) redoes no more:
 * FG_STAGE_GRAPH     the graph is compiled and prepared again (declare reads it: slots, formats,
 *                    sizes; the default, always safe), which drops every pass's kept work;
 * FG_STAGE_PREPARE   the pass's prepare alone runs again (its programs, its state: prepare reads
 *                    it), the graph's storage and the other passes' work kept
 *                    (fg_graph_prepare_pass);
 * FG_STAGE_FRAME     nothing: execute reads it every frame, so the next frame has it. */
typedef enum fg_param_stage {
    FG_STAGE_GRAPH = 0,
    FG_STAGE_PREPARE,
    FG_STAGE_FRAME
} fg_param_stage;

/* "graph", "prepare" or "frame". */
const char *fg_param_stage_name(fg_param_stage stage);

typedef enum fg_param_type {
    FG_PARAM_INT,
    FG_PARAM_FLOAT,
    FG_PARAM_BOOL,
    FG_PARAM_ENUM,          /* one of `choices`, "a|b|c"; the value is the index */
    FG_PARAM_STRING
} fg_param_type;

/* A list of numbers: the only values an int or float parameter takes. */
typedef struct fg_param_values {
    const double *values;   /* strictly increasing */
    int count;
} fg_param_values;

/* `.allowed = FG_PARAM_VALUES(1, 6, 9, 16)` in a table at file scope (where a compound
 * literal has static storage); in a function, point `values` at a static array instead. */
#define FG_PARAM_VALUES(...)                                                              \
    { (const double[]){ __VA_ARGS__ },                                                    \
      (int)(sizeof((const double[]){ __VA_ARGS__ }) / sizeof(double)) }

/* A bound that another parameter of the same pass sets: strictly beyond scale x its value. */
typedef struct fg_param_bound {
    const char *param;      /* an int or float parameter of the same table; NULL: no bound */
    double scale;           /* 0: 1 */
} fg_param_bound;

/* One parameter of a pass type. Every field past `doc` may stay zero (no constraint, the
 * default stepping), so that a table lists only what it needs:
 *     { .name = "cones", .type = FG_PARAM_INT, .default_value = 6, .min = 1, .max = 16,
 *       .allowed = FG_PARAM_VALUES(1, 6, 9, 16), .doc = "diffuse cones" },
 * fg_registry_add checks the table (defaults allowed, bounds powers of two, names that
 * dependencies refer to exist, ...). Values are validated where they are set
 * (fg_graph_set_param: range, allowed values, power of two), dependencies between values
 * once at fg_graph_compile before any declare(); `conegraph passes`, docs/pass-parameters.md
 * and the demo's controls print and step the same data. */
typedef struct fg_param_desc {
    const char *name;
    fg_param_type type;
    double default_value;   /* int, float, bool (0 or 1), enum (index) */
    double min, max;        /* int and float: inclusive range, checked on every assignment */
    const char *choices;    /* enum: "a|b|c"; string: the default value */
    const char *doc;        /* one line, shown by `conegraph passes`, docs and the demo */

    /* Values (int and float), checked on every assignment. */
    fg_param_values allowed; /* the only values taken, within [min, max]; count 0: any in range */
    bool power_of_two;      /* int: powers of two only (then min and max are powers of two) */

    /* How an interface steps the value (int and float; the demo's Left/Right, a slider).
     * Allowed values and powers of two step to their neighbours; otherwise: */
    double step;            /* added per step; 0: 1 for an int; for a float the 1, 2 or 5 x 10^k
                             * below 1/50 of the range, or below a quarter of the value's
                             * magnitude (at least 1) when the range is wider than 1000 */
    bool step_doubles;      /* multiply or divide by 2 per step (sizes, sample counts; min > 0) */

    /* Dependencies on other parameters of the same pass, checked at compile. */
    const char *active_when; /* "PARAM": the parameter matters only while bool PARAM is true;
                              * "PARAM=A|B": only while PARAM (enum, bool or int) is A or B;
                              * NULL: always. The bounds below are checked only while active. */
    fg_param_bound greater_than; /* value > scale x that parameter's value */
    fg_param_bound less_than;    /* value < scale x that parameter's value */

    fg_param_stage stage;   /* what a change redoes (above); 0: the graph */

    /* The value an interactive application (the demo) gives the parameter where neither the graph
     * file nor --set does (fg_graph_apply_interactive), as a graph file writes it; NULL: the
     * default. For a setting that costs less a frame and shows the default's image wherever
     * nothing moves (the gathers' `temporal`), which a single-frame render cannot use. */
    const char *interactive;
} fg_param_desc;

/* ---------------------------------------------------------------- resources */

typedef enum fg_resource_kind {
    FG_TEXTURE_2D,
    FG_TEXTURE_3D,
    FG_TEXTURE_2D_ARRAY,
    FG_BUFFER
} fg_resource_kind;

/* How a pass touches a resource; the graph derives glMemoryBarrier bits from the
 * writer's and the reader's access. Bits may be combined. */
typedef enum fg_access {
    FG_ACCESS_SAMPLED     = 1 << 0, /* texture()/texelFetch() */
    FG_ACCESS_IMAGE_LOAD  = 1 << 1, /* imageLoad */
    FG_ACCESS_IMAGE_STORE = 1 << 2, /* imageStore / imageAtomic* */
    FG_ACCESS_ATTACHMENT  = 1 << 3, /* framebuffer colour or depth attachment */
    FG_ACCESS_STORAGE     = 1 << 4, /* SSBO read or write */
    FG_ACCESS_UNIFORM     = 1 << 5, /* UBO */
    FG_ACCESS_TRANSFER    = 1 << 6  /* glTexSubImage, glClearTexImage, glGenerateMipmap, glGetTexImage */
} fg_access;

typedef struct fg_resource_desc {
    fg_resource_kind kind;
    GLenum format;          /* sized internal format (GL_RGBA16F, GL_DEPTH_COMPONENT32F, ...); 0 for buffers */
    int width, height;      /* texels */
    int depth;              /* 3D: depth; 2D array: layers; else 1 */
    int levels;             /* mip levels, >= 1 */
    size_t buffer_bytes;    /* buffers */
    bool persistent;        /* kept across frames (never pooled) */
    bool gi;                /* counts towards the GI memory metric (lightmaps, volumes, tables) */
} fg_resource_desc;

/* Bytes a resource occupies, mip chain included. */
size_t fg_resource_bytes(const fg_resource_desc *desc);
/* Full mip chain length for a size. */
int fg_mip_levels(int width, int height, int depth);

/* ---------------------------------------------------------------- pass types */

typedef struct fg_pass fg_pass;
typedef struct fg_declare fg_declare;

/* What every pass sees of the frame. */
typedef struct fg_frame {
    const cg_scene *scene;
    const cg_gpu_scene *gpu_scene;  /* NULL when compiling without GL */
    cg_view view;                   /* camera for the output image */
    int width, height;              /* output image size */
    uint64_t index;                 /* frame number, from 0 */
} fg_frame;

typedef struct fg_pass_type {
    uint32_t abi_version;           /* FG_ABI_VERSION at the pass's build */
    const char *name;
    const char *doc;                /* one paragraph; cite the paper and equation */
    const fg_param_desc *params;
    int param_count;
    bool side_effect;               /* never culled (e.g. writes a file) */
    /* Required. States inputs and outputs via fg_declare_*; may read parameters and fg_pass_frame(). */
    bool (*declare)(fg_pass *pass, fg_declare *decl, cg_error *err);
    /* Optional. GL is current: compile programs, allocate private state. Called once after compile. */
    bool (*prepare)(fg_pass *pass, void **state, cg_error *err);
    /* Required. Runs the pass for fg_pass_frame(pass). */
    bool (*execute)(fg_pass *pass, void *state, cg_error *err);
    /* Optional. Frees what prepare made; GL is current. */
    void (*destroy)(void *state);
} fg_pass_type;

/* Declares an input slot. `kind` is what the pass accepts; the graph checks the connected output against it.
 * Returns the connected resource's descriptor, or NULL when unconnected or absent. */
const fg_resource_desc *fg_declare_input(fg_declare *decl, const char *name, fg_resource_kind kind,
                                         unsigned access, bool required);
/* Declares an output; `access` is how this pass writes it. */
void fg_declare_output(fg_declare *decl, const char *name, const fg_resource_desc *desc, unsigned access);
/* The pass has nothing to do for this scene and parameters (e.g. no height-field mesh):
 * it is culled and its outputs are absent. */
void fg_declare_nothing_to_do(fg_declare *decl, const char *why);

const char *fg_pass_name(const fg_pass *pass);
const fg_pass_type *fg_pass_type_of(const fg_pass *pass);
const fg_frame *fg_pass_frame(const fg_pass *pass);

/* Parameter values of this instance (defaults, file values, --set overrides). Asking for a
 * name the pass type does not declare is a programming error: it aborts with a message. */
int fg_param_int(const fg_pass *pass, const char *name);
float fg_param_float(const fg_pass *pass, const char *name);
bool fg_param_bool(const fg_pass *pass, const char *name);
int fg_param_enum(const fg_pass *pass, const char *name);
const char *fg_param_string(const fg_pass *pass, const char *name);
/* Whether the parameter matters for this instance's values (its desc->active_when holds). */
bool fg_param_active(const fg_pass *pass, const fg_param_desc *desc);
/* Checks the dependencies between this instance's values (greater_than, less_than of the
 * active parameters); the error points at where the values were set. fg_graph_compile
 * calls it for every pass before any declare(); an interface may call it after a change. */
bool fg_pass_check_params(const fg_pass *pass, cg_error *err);

/* A slot of a pass instance: one of the inputs and outputs its declare() stated, found by name once
 * in prepare() and kept in the pass's state; execute() binds through it:
 *     s->normal = fg_pass_slot(pass, "normal");                       (prepare)
 *     glBindTextureUnit(1, fg_slot_texture(pass, s->normal));          (execute)
 * A name the pass did not declare is an error, not an absent slot: fg_graph_prepare (or
 * fg_graph_execute, for a lookup there) fails after the callback with "pass 'P' (type T) looks up
 * slot 'S', which it does not declare (its slots: ...)". A declared optional input that is not
 * connected, or whose writer had nothing to do, is a slot whose resource is absent. A handle is
 * valid until the next fg_graph_compile, which releases every state. */
typedef struct fg_slot {
    int index;              /* private: 0 is no slot */
} fg_slot;
#define FG_NO_SLOT ((fg_slot){ 0 })

fg_slot fg_pass_slot(const fg_pass *pass, const char *name);
/* For a slot that declare() states only for some parameter values or scenes: FG_NO_SLOT when it
 * did not this time (not an error). Use the same name constant in declare() and here. */
fg_slot fg_pass_slot_if_declared(const fg_pass *pass, const char *name);
/* The slot's resource is there (connected and not absent); false for FG_NO_SLOT. */
bool fg_slot_present(const fg_pass *pass, fg_slot slot);
GLuint fg_slot_texture(const fg_pass *pass, fg_slot slot);  /* 0 when absent or a buffer */
GLuint fg_slot_buffer(const fg_pass *pass, fg_slot slot);   /* 0 when absent or a texture */
const fg_resource_desc *fg_slot_resource(const fg_pass *pass, fg_slot slot); /* NULL when absent */

/* The same by slot name, found on every call (a plugin's or a test's shortcut): an undeclared name
 * fails the graph as above. */
bool fg_input_present(const fg_pass *pass, const char *name);
GLuint fg_texture(const fg_pass *pass, const char *name);   /* 0 when absent */
GLuint fg_buffer(const fg_pass *pass, const char *name);    /* 0 when absent */
const fg_resource_desc *fg_resource(const fg_pass *pass, const char *name); /* NULL when absent */

/* What the pass rebuilt this frame, in a few words for a person ("geometry kept; light 262144
 * texels"), printf-style, at most FG_REBUILT_MAX - 1 bytes (longer text is cut). A pass that
 * keeps work across frames says here what it redid and what it kept, so that a cache can be
 * watched at work (`render --report`, the per-frame lines, the demo's pass list). The graph
 * clears it before each execute(): a pass that says nothing reports "". Call it during
 * execute(). */
#define FG_REBUILT_MAX 160
void fg_pass_report_rebuilt(fg_pass *pass, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* The last execute's text ("" when the pass said nothing or has not run). */
const char *fg_pass_rebuilt(const fg_pass *pass);

/* What the pass read this frame, in counts that do not depend on the machine's speed or load:
 * its shaders' texture reads (textureLod and texelFetch calls, each one read whatever filter it
 * takes) and the items they were made for (a gather: the pixels whose diffuse cones it traced;
 * voxel_light: the voxels that traced). A GPU's cost of the pass can be estimated from them, and
 * two settings compared on a loaded machine (`render --report`, `--pass-costs`, bench, the demo).
 * `item` names the items ("pixel", "voxel"), a string that outlives the graph.
 *
 * The shaders count into `buffer` (FG_READS_COUNTER, 16 bytes at offset 0: reads, low and high
 * 32 bits, then items, then 0: common/reads.glsl's layout), which the pass clears before its
 * dispatches. Call it during execute(), after them. The graph copies the counter when the pass
 * ends and reads the copy when it reads the pass's time: at once with FG_TIMING_SYNC and
 * FG_TIMING_NONE (the read waits for the pass), a frame late with FG_TIMING_QUERIES (nothing
 * waits). A pass
 * that does not call it has no counts (fg_pass_reads is false). */
#define FG_READS_COUNTER 16
void fg_pass_report_reads(fg_pass *pass, GLuint buffer, const char *item);
/* The counts of the last frame read back (queries: the frame before): false when the pass
 * reported none. `reads` and `items` may be NULL. */
bool fg_pass_reads(const fg_pass *pass, double *reads, double *items, const char **item);
/* The counts for a person: "48.21 M, 3347 a pixel" (reads in millions, then per item), "0 M, no
 * voxel" when nothing was traced, "-" when the pass reported none. Returns buf. */
const char *fg_pass_reads_text(const fg_pass *pass, char *buf, size_t size);

/* ---------------------------------------------------------------- registry and plugins */

typedef struct fg_registry fg_registry;

/* The one symbol a plugin exports: `bool conegraph_plugin_register(fg_registry *, uint32_t host_abi, cg_error *)`.
 * A plugin must refuse (CG_ERR_PLUGIN_ABI) when host_abi differs from its FG_ABI_VERSION. */
typedef bool (*fg_plugin_register_fn)(fg_registry *registry, uint32_t host_abi, cg_error *err);
#define FG_PLUGIN_ENTRY "conegraph_plugin_register"

fg_registry *fg_registry_create(void);
void fg_registry_destroy(fg_registry *registry);
/* Checks the descriptor (ABI version, unique name, parameter table sane, callbacks present). */
bool fg_registry_add(fg_registry *registry, const fg_pass_type *type, cg_error *err);
const fg_pass_type *fg_registry_find(const fg_registry *registry, const char *name);
int fg_registry_count(const fg_registry *registry);
const fg_pass_type *fg_registry_at(const fg_registry *registry, int index);
/* The values a parameter takes, as `conegraph passes` prints them: "1, 6, 9, 16",
 * "16..512, power of two", "0.05..4", "true|false", "none|reinhard|aces", "any text". */
void fg_param_values_text(const fg_param_desc *desc, char *buf, size_t size);
/* Its dependencies and its interactive value, "" when none: "only with region = explicit; greater
 * than min_x", "less than 0.25 x resolution", "4 in interactive applications unless set". */
void fg_param_dependency_text(const fg_param_desc *desc, char *buf, size_t size);
/* dlopen()s a shared object and calls its entry point. */
bool fg_registry_load_plugin(fg_registry *registry, const char *path, cg_error *err);
/* Loads every *.so in each directory of a ':'-separated list (e.g. $CONEGRAPH_PLUGIN_PATH). */
bool fg_registry_load_plugin_dirs(fg_registry *registry, const char *dirs, cg_error *err);

/* ---------------------------------------------------------------- graphs */

typedef struct fg_graph fg_graph;

/* Where a graph element came from, for error messages; file NULL for graphs built in code.
 * line 0: `file` is a place without lines, quoted as is. fg_graph_apply_override sets a
 * value at { "--set PASS.PARAM=VALUE", 0, 0 }: that text already names the pass, the
 * parameter and the value, so messages about the value say only what was expected. */
typedef struct fg_source_loc {
    const char *file;
    int line, column;
} fg_source_loc;

fg_graph *fg_graph_create(const fg_registry *registry);
void fg_graph_destroy(fg_graph *graph);

/* Adds a pass instance; names are unique. loc may be NULL. */
bool fg_graph_add_pass(fg_graph *graph, const char *name, const char *type,
                       const fg_source_loc *loc, cg_error *err);
/* Sets a parameter from text ("9", "0.5", "true", "anisotropic"), validated against the
 * table: type, range, allowed values, power of two (CG_ERR_GRAPH_PARAM_TYPE, _RANGE). The
 * error starts at loc and says what was expected: "g.json:7:24: gather.cones = 7; expected
 * one of 1, 6, 9, 16", or "--set gather.cones=7: expected one of 1, 6, 9, 16". */
bool fg_graph_set_param(fg_graph *graph, const char *pass, const char *param, const char *value,
                        const fg_source_loc *loc, cg_error *err);
/* Sets every parameter that has an interactive value (fg_param_desc.interactive), that neither
 * the graph file nor an override set and that matters (fg_param_active), for an interactive
 * application; lists what it set
 * in `applied` ("gather.temporal=4", comma-separated; "" for none). Call it after the file and
 * the overrides. */
bool fg_graph_apply_interactive(fg_graph *graph, char *applied, size_t size, cg_error *err);
/* Connects input slot `input` of `pass` to `source`: "pass.output", or "pass" for the
 * output of the same name as the input, or that pass's only output. A source ending in
 * "@previous" reads the value of the previous frame (the one edge a cycle may go through). */
bool fg_graph_connect(fg_graph *graph, const char *pass, const char *input, const char *source,
                      const fg_source_loc *loc, cg_error *err);
/* Marks "pass.output" as a graph output (kept, never pooled, readable after execute). */
bool fg_graph_mark_output(fg_graph *graph, const char *source, const fg_source_loc *loc, cg_error *err);

typedef enum fg_timing_mode {
    FG_TIMING_NONE,
    FG_TIMING_QUERIES,      /* GL_TIMESTAMP queries read back a frame late (GPUs) */
    FG_TIMING_SYNC          /* glFinish + CPU clock around each pass (llvmpipe) */
} fg_timing_mode;

typedef struct fg_compile_options {
    bool no_pool;               /* give every transient resource its own texture (for measurement) */
    size_t max_gpu_memory;      /* bytes; 0 = no limit */
    int max_texture_size_2d;    /* 0 = ask GL (or no check without GL) */
    int max_texture_size_3d;
} fg_compile_options;

/* Declares, validates, culls, orders, computes lifetimes, assigns pooled storage and
 * barriers. Needs no GL (frame->gpu_scene may be NULL). Errors name the pass, the field
 * and the file location when known. Can be called again after parameter changes. */
bool fg_graph_compile(fg_graph *graph, const fg_frame *frame, const fg_compile_options *options,
                      cg_error *err);
/* Creates GL storage and calls each live pass's prepare(). GL must be current. */
bool fg_graph_prepare(fg_graph *graph, cg_error *err);
/* Prepares one live pass again (destroy, then prepare) in a prepared graph, its storage and the
 * other passes as they are: what a change of a FG_STAGE_PREPARE parameter needs. GL current. */
bool fg_graph_prepare_pass(fg_graph *graph, const char *pass, cg_error *err);
/* Runs one frame: per live pass, its barrier, a timestamp, execute(), a timestamp. */
bool fg_graph_execute(fg_graph *graph, const fg_frame *frame, fg_timing_mode timing, cg_error *err);

/* ------------------------------------------------ introspection and report (after compile) */

int fg_graph_pass_count(const fg_graph *graph);
fg_pass *fg_graph_pass_at(const fg_graph *graph, int index);       /* file order */
fg_pass *fg_graph_find_pass(const fg_graph *graph, const char *name);
bool fg_pass_is_culled(const fg_pass *pass);
const char *fg_pass_cull_reason(const fg_pass *pass);              /* NULL when live */
/* The resource ("pass.output") input slot `input` of `pass` reads, as the last compile resolved
 * the file's shorthand ("gbuf" for "gbuf.albedo") and in-place versions; NULL when the pass
 * declares no such input or it is unconnected or absent. An app that reads a pass's inputs
 * back (bench: the final composite's direct light) finds them by it. */
const char *fg_pass_input_source(const fg_pass *pass, const char *input);
/* Execution order: number of live passes; order[i] is an index into file order. */
int fg_graph_order(const fg_graph *graph, const int **order);
/* Memory barrier bits issued before this pass. */
GLbitfield fg_pass_barrier_bits(const fg_pass *pass);

typedef struct fg_resource_info {
    const char *name;           /* "pass.output" */
    fg_resource_desc desc;
    bool absent;                /* writer culled or had nothing to do */
    int writer;                 /* pass index (file order) */
    int first_use, last_use;    /* positions in the execution order */
    int storage;                /* physical storage slot; equal slots share one GL object */
    size_t bytes;
} fg_resource_info;

int fg_graph_resource_count(const fg_graph *graph);
const fg_resource_info *fg_graph_resource_at(const fg_graph *graph, int index);
/* GL object of a resource by "pass.output", 0 if absent (after prepare). */
GLuint fg_graph_texture(const fg_graph *graph, const char *source);
const fg_resource_info *fg_graph_find_resource(const fg_graph *graph, const char *source);
int fg_graph_output_count(const fg_graph *graph);
const char *fg_graph_output_at(const fg_graph *graph, int index);

typedef struct fg_memory_report {
    size_t resource_bytes;      /* sum over live resources, as if none were pooled */
    size_t allocated_bytes;     /* sum over physical storage slots (what the pool allocates) */
    size_t peak_bytes;          /* largest sum of simultaneously live storage during a frame */
    size_t gi_bytes;            /* resources flagged gi: the papers' memory metric */
} fg_memory_report;

void fg_graph_memory_report(const fg_graph *graph, fg_memory_report *out);
/* Milliseconds of the last timed frame (queries: the frame before); -1 when not measured. */
double fg_pass_milliseconds(const fg_pass *pass);

/* Human-readable table of per-pass times, texture reads and resource bytes. */
void fg_graph_print_report(const fg_graph *graph, FILE *out);
/* Every live pass that counted, in execution order: "light 0 M, no voxel; gather 1.754 M, 1082 a
 * pixel" ("" when none did). Returns buf. */
const char *fg_graph_reads_text(const fg_graph *graph, char *buf, size_t size);

/* The same as JSON, written atomically. */
bool fg_graph_write_report_json(const fg_graph *graph, const char *path, cg_error *err);
/* Graphviz DOT of the compiled graph: culled passes dashed, resource sizes on the edges. */
void fg_graph_write_dot(const fg_graph *graph, FILE *out);

#endif
