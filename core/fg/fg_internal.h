/* core/fg/fg_internal.h: the frame graph's private data, shared by the fg_*.c files.
 *
 * Declares: fg_format_info, fg_format_find, fg_format_name, fg_kind_name, fg_access_names,
 *           fg_barrier_bits_for, fg_bytes_text, fg_loc_prefix, fg_strdup, fg_grow,
 *           fg_split_source, fg_param_value,
 *           fg_connection, fg_input, fg_output, fg_res, fg_storage, struct fg_pass,
 *           struct fg_graph, struct fg_declare, struct fg_registry, fg_graph_free, fg_graph_release_gl,
 *           fg_graph_reset_compile, fg_pass_slots_check, fg_is_identifier, fg_param_find,
 *           fg_param_choice_count, fg_param_choice, fg_param_table_check, fg_param_parse, fg_param_accepts,
 *           fg_param_expected, fg_loc_is_assignment, fg_param_lead, fg_param_active_in.
 *
 * Nothing here is part of the public interface: passes see only cg/fg.h.
 */
#ifndef CG_FG_INTERNAL_H
#define CG_FG_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cg/fg.h"

/* Frames of timestamp queries in flight: results are read a frame late, so two would do;
 * a third slot keeps a slow driver from stalling the CPU on a result not yet available. */
#define FG_QUERY_RING 3

/* ---------------------------------------------------------------- formats */

typedef struct fg_format_info {
    GLenum format;
    const char *name;       /* "RGBA16F" */
    int bytes;              /* nominal bytes per texel (components x component size) */
    bool image_unit;        /* usable with imageLoad/imageStore (GL 4.5 table 8.26) */
    bool depth;             /* depth or stencil: attachment or sampled only */
} fg_format_info;

const fg_format_info *fg_format_find(GLenum format);
/* "RGBA16F", or "0x8881" for a format not in the table (static buffer for unknown ones). */
const char *fg_format_name(GLenum format, char *buf, size_t size);
const char *fg_kind_name(fg_resource_kind kind);
/* "sampled|image_load", into buf. */
const char *fg_access_names(unsigned access, char *buf, size_t size);
/* glMemoryBarrier bits needed between a write with `writer` access and a read with `reader` access. */
GLbitfield fg_barrier_bits_for(unsigned writer, unsigned reader, fg_resource_kind kind);

/* ---------------------------------------------------------------- helpers (helpers.c) */

/* "12.5 MiB", "3.0 KiB", "17 B". */
const char *fg_bytes_text(size_t bytes, char *buf, size_t size);

/* "file:line:column: " for a location with a file, "file: " for one without lines
 * (line 0, e.g. "--set p.n=1: "), "" otherwise. */
const char *fg_loc_prefix(const fg_source_loc *loc, char *buf, size_t size);
char *fg_strdup(const char *s);
/* Grows *items to hold at least `need` elements of `size` bytes; false when out of memory. */
bool fg_grow(void **items, int *cap, int need, size_t size);
/* A "pass.output" reference: copies the pass's name, what stands before the first '.' (all of
 * `source` without one), into `pass` (cut at `size`) and returns what follows the '.', or NULL
 * when there is no '.'. */
const char *fg_split_source(const char *source, char *pass, size_t size);

/* ---------------------------------------------------------------- registry */

struct fg_registry {
    const fg_pass_type **types;
    int count, cap;
    void **plugins;         /* dlopen handles, closed when the registry is destroyed */
    int plugin_count, plugin_cap;
};

/* ---------------------------------------------------------------- parameter tables (params.c) */

/* Letters, digits, '_' and '-': pass, parameter and choice names appear in "pass.param=value"
 * overrides and in "pass.output" references, so they may not contain '.', '=', '@' or '|'. */
bool fg_is_identifier(const char *s);
const fg_param_desc *fg_param_find(const fg_pass_type *type, const char *name, int *index);
int fg_param_choice_count(const char *choices);
/* Copies choice `index` of "a|b|c" into buf; false when out of range. */
bool fg_param_choice(const char *choices, int index, char *buf, size_t size);
/* The table checks of fg_registry_add: each entry sane, dependencies naming other entries,
 * defaults that satisfy every constraint. */
bool fg_param_table_check(const fg_pass_type *type, cg_error *err);
/* Reads all of `text` as a value of the parameter's type (a decimal number, an integer,
 * true/false, a choice's name; any text for strings): the number (enum: index). */
bool fg_param_parse(const fg_param_desc *p, const char *text, double *out);
/* Whether a parsed value meets the table: range, allowed values, power of two. */
bool fg_param_accepts(const fg_param_desc *p, double value);
/* What the parameter takes, after "expected ": "one of 1, 6, 9, 16", "a power of two in
 * 16..512", "an integer in 0..16", "a number in 0.05..4", "true or false", "one of a, b". */
void fg_param_expected(const fg_param_desc *p, char *buf, size_t size);
/* Whether loc is a place without lines that spells the assignment ("--set p.n=1"). */
bool fg_loc_is_assignment(const fg_source_loc *loc);
/* The start of a message about a value: "g.json:7:24: p.n = 7; ", "p.n = 7; " without a
 * location, or "--set p.n=7: " for an assignment (which names pass, parameter and value). */
void fg_param_lead(const fg_source_loc *loc, const char *pass, const char *param, const char *value,
                   char *buf, size_t size);

/* ---------------------------------------------------------------- graphs */

typedef struct fg_param_value {
    double number;          /* int, float, bool, enum index */
    char *text;             /* string parameters */
    bool set;               /* given by a file or an override (not the default) */
    fg_source_loc loc;
} fg_param_value;

/* Whether p's active_when holds for `values` (one per entry of type->params). */
bool fg_param_active_in(const fg_pass_type *type, const fg_param_desc *p, const fg_param_value *values);

/* An edge of the graph as written in the file: input slot <- source. */
typedef struct fg_connection {
    char *input;
    char *source_pass;
    char *source_output;    /* NULL: the output named like the input, or the only output */
    bool previous;          /* "@previous": last frame's value */
    fg_source_loc loc;
    int source_index;       /* pass index, resolved at compile */
    bool matched;           /* a declared input slot took it */
} fg_connection;

typedef struct fg_input {
    char *name;
    fg_resource_kind kind;
    unsigned access;
    bool required;
    int connection;         /* index into pass->connections, -1 when unconnected */
    int source_pass;        /* writer's pass index, -1 when unconnected */
    int source_output;      /* index into the writer's outputs, -1 when unconnected or absent */
    int resource;           /* -1 when unconnected or absent */
    bool previous;
    bool absent;            /* connected, but its writer had nothing to do or was culled for it */
    bool pending;           /* a previous-frame source not declared yet (first declare round) */
} fg_input;

typedef struct fg_output {
    char *name;
    fg_resource_desc desc;
    unsigned access;
    int resource;
    int in_place_input;     /* index of the input of the same name it updates, -1 for a new resource */
} fg_output;

struct fg_pass {
    fg_graph *graph;
    int index;              /* file order */
    char *name;
    const fg_pass_type *type;
    fg_source_loc loc;
    fg_param_value *values; /* type->param_count */
    fg_connection *connections;
    int connection_count, connection_cap;

    /* compile */
    fg_input *inputs;
    int input_count, input_cap;
    fg_output *outputs;
    int output_count, output_cap;
    bool declared;
    /* What the previous declare round stated, for previous-frame inputs that read a pass
     * not declared again yet (a later pass, or the pass itself). */
    fg_output *saved_outputs;
    int saved_output_count;
    bool saved_absent;
    bool nothing_to_do;
    bool missing_input;     /* a required input is absent: culled, outputs absent */
    bool culled;
    char *cull_reason;
    int position;           /* in the execution order; -1 when culled */
    GLbitfield barrier_bits;

    /* execute */
    void *state;
    bool prepared;
    double ms;
    char rebuilt[FG_REBUILT_MAX]; /* fg_pass_report_rebuilt during the last execute */
    /* The first slot name the pass looked up without having declared it (fg_pass_slot, fg_texture,
     * ...), "" when none: fg_graph_prepare and fg_graph_execute fail with it after the callback. */
    char undeclared_slot[64];
    GLuint queries[FG_QUERY_RING][2];
    bool query_issued[FG_QUERY_RING];
    /* Texture reads (fg_pass_report_reads): the pass's counter during this execute (0: none), the
     * graph's copies of it, a ring slot a frame as the queries, and the last counts read back. */
    GLuint reads_source;
    const char *reads_source_item;
    GLuint reads_copy[FG_QUERY_RING];
    const char *reads_copy_item[FG_QUERY_RING];   /* NULL: the slot's frame reported none */
    bool reads_known;
    double reads, reads_items;
    const char *reads_item;
};

typedef struct fg_res {
    fg_resource_info info;
    char *name;             /* owns info.name */
    int output;             /* index into the writer's outputs */
    unsigned writer_access;
    int version_of;         /* resource this one updates in place (shares its storage), -1 if none */
    int updated_by;         /* the in-place version that replaces it, -1 if none */
    bool graph_output;
    bool read_previous;     /* some live pass reads it with "@previous" */
    bool double_buffered;   /* read "@previous" after its writer ran: two storages, swapped per frame */
    int storage2;           /* the second storage of a double-buffered resource */
} fg_res;

typedef struct fg_storage {
    fg_resource_desc desc;
    size_t bytes;
    int first_use, last_use;
    bool clear_on_create;   /* persistent and history storage starts at zero */
    GLuint object;
} fg_storage;

typedef struct fg_graph_output {
    char *source;
    fg_source_loc loc;
    int resource;
} fg_graph_output;

struct fg_graph {
    const fg_registry *registry;
    fg_pass **passes;
    int pass_count, pass_cap;
    char **files;           /* interned file names that source locations point to */
    int file_count, file_cap;
    fg_graph_output *outputs;
    int output_count, output_cap;
    /* The graph file's "sky": the scene's sky it asks for (cg/graphfile.h). */
    bool has_sky;
    cg_sky sky;

    /* compile */
    bool compiled;
    fg_frame frame;
    fg_compile_options options;
    int *order;
    int order_count;
    fg_res *resources;
    int resource_count, resource_cap;
    fg_storage *storage;
    int storage_count, storage_cap;

    /* execute */
    bool prepared;
    uint64_t frames_executed;
    int frame_parity;       /* which storage of a double-buffered resource this frame writes */
    int query_frame;        /* ring slot of the last frame issued with queries, -1 when none */
};

struct fg_declare {
    fg_graph *graph;
    fg_pass *pass;
    cg_error *err;
    bool failed;
};

/* Storage of a resource for the current frame (double-buffered ones alternate);
 * `previous` asks for the copy that holds last frame's value. */
const fg_storage *fg_resource_storage(const fg_graph *graph, int resource, bool previous);
/* Index of resource "pass.output", -1 when there is none. */
int fg_graph_find_resource_index(const fg_graph *graph, const char *source);
/* Frees the passes, their connections and values, and the graph itself: what graph.c built
 * (fg_graph_destroy releases GL state and compile's products first). */
void fg_graph_free(fg_graph *graph);
/* Drops GL objects and pass states (GL must be current when anything was prepared). */
void fg_graph_release_gl(fg_graph *graph);
/* After a pass's prepare() or execute(): false, with an error naming the pass and the slot, when it
 * looked up a slot it did not declare; clears the record. */
bool fg_pass_slots_check(fg_pass *pass, cg_error *err);
/* Forgets everything compile produced. */
void fg_graph_reset_compile(fg_graph *graph);

#endif
