/* Prepare and execute: GL storage from descriptors, pass states, barriers and timings. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fg_internal.h"

/* ---------------------------------------------------------------- resource lookup */

GLuint
fg_graph_texture(const fg_graph *graph, const char *source)
{
    int index = fg_graph_find_resource_index(graph, source);
    if (index < 0 || graph->resources[index].info.absent)
        return 0;
    const fg_storage *s = fg_resource_storage(graph, index, false);
    return s ? s->object : 0;
}

/* ---------------------------------------------------------------- storage */

static GLenum
texture_target(fg_resource_kind kind)
{
    switch (kind) {
    case FG_TEXTURE_3D: return GL_TEXTURE_3D;
    case FG_TEXTURE_2D_ARRAY: return GL_TEXTURE_2D_ARRAY;
    default: return GL_TEXTURE_2D;
    }
}

/* A pixel format and type that glClearTexImage accepts for an internal format. */
static void
clear_format(GLenum internal, GLenum *format, GLenum *type)
{
    const fg_format_info *info = fg_format_find(internal);
    *format = GL_RGBA;
    *type = GL_FLOAT;
    if (!info)
        return;
    size_t len = strlen(info->name);
    if (internal == GL_DEPTH24_STENCIL8) {
        *format = GL_DEPTH_STENCIL;
        *type = GL_UNSIGNED_INT_24_8;
    } else if (internal == GL_DEPTH32F_STENCIL8) {
        *format = GL_DEPTH_STENCIL;
        *type = GL_FLOAT_32_UNSIGNED_INT_24_8_REV;
    } else if (internal == GL_STENCIL_INDEX8) {
        *format = GL_STENCIL_INDEX;
        *type = GL_UNSIGNED_BYTE;
    } else if (info->depth) {
        *format = GL_DEPTH_COMPONENT;
    } else if (len > 2 && !strcmp(info->name + len - 2, "UI")) {
        *format = GL_RGBA_INTEGER;
        *type = GL_UNSIGNED_INT;
    } else if (info->name[len - 1] == 'I' && internal != GL_RGB10_A2UI) {
        *format = GL_RGBA_INTEGER;
        *type = GL_INT;
    }
}

static bool
create_storage(fg_graph *graph, int index, cg_error *err)
{
    fg_storage *s = &graph->storage[index];
    const fg_resource_desc *d = &s->desc;
    /* Name the GL object after the first resource it holds, for debuggers and KHR_debug. */
    const char *label = "fg storage";
    for (int i = 0; i < graph->resource_count; i++)
        if (graph->resources[i].info.storage == index || graph->resources[i].storage2 == index) {
            label = graph->resources[i].name;
            break;
        }
    while (glGetError() != GL_NO_ERROR)
        ;
    if (d->kind == FG_BUFFER) {
        glCreateBuffers(1, &s->object);
        glNamedBufferStorage(s->object, (GLsizeiptr)d->buffer_bytes, NULL, GL_DYNAMIC_STORAGE_BIT);
        if (s->clear_on_create)
            glClearNamedBufferData(s->object, GL_R8, GL_RED, GL_UNSIGNED_BYTE, NULL);
        glObjectLabel(GL_BUFFER, s->object, -1, label);
    } else {
        glCreateTextures(texture_target(d->kind), 1, &s->object);
        if (d->kind == FG_TEXTURE_2D)
            glTextureStorage2D(s->object, d->levels, d->format, d->width, d->height);
        else
            glTextureStorage3D(s->object, d->levels, d->format, d->width, d->height, d->depth);
        if (s->clear_on_create) {
            GLenum format, type;
            clear_format(d->format, &format, &type);
            for (int level = 0; level < d->levels; level++)
                glClearTexImage(s->object, level, format, type, NULL);
        }
        glObjectLabel(GL_TEXTURE, s->object, -1, label);
    }
    GLenum error = glGetError();
    if (error != GL_NO_ERROR)
        return cg_fail(err, error == GL_OUT_OF_MEMORY ? CG_ERR_OUT_OF_MEMORY : CG_ERR_GL,
                       "creating storage for '%s' (%zu bytes): GL error 0x%04x", label, s->bytes,
                       (unsigned)error);
    return true;
}

void
fg_graph_release_gl(fg_graph *graph)
{
    if (!graph->prepared)
        return;
    for (int k = graph->order_count - 1; k >= 0; k--) {
        fg_pass *pass = graph->passes[graph->order[k]];
        if (pass->prepared && pass->type->destroy)
            pass->type->destroy(pass->state);
        pass->prepared = false;
        pass->state = NULL;
    }
    for (int p = 0; p < graph->pass_count; p++) {
        fg_pass *pass = graph->passes[p];
        for (int slot = 0; slot < FG_QUERY_RING; slot++) {
            if (pass->queries[slot][0])
                glDeleteQueries(2, pass->queries[slot]);
            pass->queries[slot][0] = pass->queries[slot][1] = 0;
            pass->query_issued[slot] = false;
            if (pass->reads_copy[slot])
                glDeleteBuffers(1, &pass->reads_copy[slot]);
            pass->reads_copy[slot] = 0;
            pass->reads_copy_item[slot] = NULL;
        }
        pass->reads_known = false;
    }
    for (int i = 0; i < graph->storage_count; i++) {
        fg_storage *s = &graph->storage[i];
        if (!s->object)
            continue;
        if (s->desc.kind == FG_BUFFER)
            glDeleteBuffers(1, &s->object);
        else
            glDeleteTextures(1, &s->object);
        s->object = 0;
    }
    graph->prepared = false;
}

bool
fg_graph_prepare(fg_graph *graph, cg_error *err)
{
    if (!graph->compiled)
        return cg_fail(err, CG_ERR_USAGE, "fg_graph_prepare: the graph is not compiled");
    fg_graph_release_gl(graph);
    graph->prepared = true; /* from here on, release_gl undoes whatever was made */
    graph->frames_executed = 0;
    graph->frame_parity = 0;
    for (int i = 0; i < graph->storage_count; i++)
        if (!create_storage(graph, i, err))
            return false;
    for (int k = 0; k < graph->order_count; k++) {
        fg_pass *pass = graph->passes[graph->order[k]];
        pass->ms = -1;
        pass->rebuilt[0] = '\0';
        pass->undeclared_slot[0] = '\0';
        if (!pass->type->prepare) {
            pass->prepared = true;
            continue;
        }
        cg_error local = { 0 };
        bool prepared = pass->type->prepare(pass, &pass->state, &local);
        pass->prepared = prepared;  /* a state made is released with the graph's */
        if (!fg_pass_slots_check(pass, err))
            return false;           /* a misspelt slot, whatever prepare() said */
        if (!prepared) {
            if (local.status == CG_OK)
                return cg_fail(err, CG_ERR_PASS, "pass '%s' (type %s): prepare failed without a reason",
                               pass->name, pass->type->name);
            return cg_fail(err, local.status, "pass '%s' (type %s): %s", pass->name, pass->type->name,
                           local.message);
        }
        pass->prepared = true;
    }
    return true;
}

bool
fg_graph_prepare_pass(fg_graph *graph, const char *pass_name, cg_error *err)
{
    if (!graph->prepared)
        return cg_fail(err, CG_ERR_USAGE, "fg_graph_prepare_pass: the graph is not prepared");
    fg_pass *pass = fg_graph_find_pass(graph, pass_name);
    if (!pass)
        return cg_fail(err, CG_ERR_USAGE, "fg_graph_prepare_pass: no pass '%s'", pass_name);
    if (!pass->prepared)
        return true;    /* culled: nothing made, nothing to make */
    if (pass->type->destroy)
        pass->type->destroy(pass->state);
    pass->state = NULL;
    pass->prepared = false;
    pass->rebuilt[0] = '\0';
    pass->undeclared_slot[0] = '\0';
    if (!pass->type->prepare) {
        pass->prepared = true;
        return true;
    }
    cg_error local = { 0 };
    bool prepared = pass->type->prepare(pass, &pass->state, &local);
    pass->prepared = prepared;
    if (!fg_pass_slots_check(pass, err))
        return false;
    if (!prepared) {
        if (local.status == CG_OK)
            return cg_fail(err, CG_ERR_PASS, "pass '%s' (type %s): prepare failed without a reason", pass->name,
                           pass->type->name);
        return cg_fail(err, local.status, "pass '%s' (type %s): %s", pass->name, pass->type->name, local.message);
    }
    pass->prepared = true;
    return true;
}

/* ---------------------------------------------------------------- execute */

static double
now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* Reads the counts of ring slot `slot` (a frame's fg_pass_report_reads) into the pass. */
static void
read_reads(fg_pass *pass, int slot)
{
    pass->reads_known = pass->reads_copy_item[slot] != NULL;
    if (!pass->reads_known)
        return;
    GLuint counter[FG_READS_COUNTER / 4] = { 0 };
    glGetNamedBufferSubData(pass->reads_copy[slot], 0, FG_READS_COUNTER, counter);
    pass->reads = (double)counter[0] + 4294967296.0 * (double)counter[1];
    pass->reads_items = (double)counter[2];
    pass->reads_item = pass->reads_copy_item[slot];
    pass->reads_copy_item[slot] = NULL;
}

/* After the pass's execute: copies the counter it reported, if any, into ring slot `slot`
 * (the copy waits for its dispatches on the GPU, not on the CPU). */
static void
copy_reads(fg_pass *pass, int slot)
{
    pass->reads_copy_item[slot] = NULL;
    if (!pass->reads_source)
        return;
    if (!pass->reads_copy[slot]) {
        glCreateBuffers(1, &pass->reads_copy[slot]);
        glNamedBufferStorage(pass->reads_copy[slot], FG_READS_COUNTER, NULL, 0);
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  /* the shaders' atomics, before the copy */
    glCopyNamedBufferSubData(pass->reads_source, pass->reads_copy[slot], 0, 0, FG_READS_COUNTER);
    pass->reads_copy_item[slot] = pass->reads_source_item;
}

/* Reads the timestamps of ring slot `slot`; waits for them only when `wait`. */
static void
read_queries(fg_graph *graph, int slot, bool wait)
{
    for (int k = 0; k < graph->order_count; k++) {
        fg_pass *pass = graph->passes[graph->order[k]];
        if (!pass->query_issued[slot])
            continue;
        GLuint available = 0;
        if (!wait)
            glGetQueryObjectuiv(pass->queries[slot][1], GL_QUERY_RESULT_AVAILABLE, &available);
        if (!wait && !available)
            continue;
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(pass->queries[slot][0], GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(pass->queries[slot][1], GL_QUERY_RESULT, &t1);
        pass->ms = t1 >= t0 ? (double)(t1 - t0) * 1e-6 : 0.0;
        pass->query_issued[slot] = false;
        read_reads(pass, slot);
    }
}

bool
fg_graph_execute(fg_graph *graph, const fg_frame *frame, fg_timing_mode timing, cg_error *err)
{
    if (!graph->prepared)
        return cg_fail(err, CG_ERR_USAGE, "fg_graph_execute: the graph is not prepared");
    if (frame->width != graph->frame.width || frame->height != graph->frame.height)
        return cg_fail(err, CG_ERR_USAGE,
                       "fg_graph_execute: the frame is %dx%d but the graph was compiled for %dx%d; "
                       "compile and prepare it again", frame->width, frame->height, graph->frame.width,
                       graph->frame.height);
    graph->frame = *frame;
    graph->frame_parity = (int)(graph->frames_executed & 1);
    int slot = (int)(graph->frames_executed % FG_QUERY_RING);
    if (timing == FG_TIMING_QUERIES)
        read_queries(graph, slot, true); /* a slot reused after FG_QUERY_RING frames */
    for (int k = 0; k < graph->order_count; k++) {
        fg_pass *pass = graph->passes[graph->order[k]];
        if (pass->barrier_bits)
            glMemoryBarrier(pass->barrier_bits);
        double t0 = 0;
        if (timing == FG_TIMING_SYNC) {
            glFinish();
            t0 = now_ms();
        } else if (timing == FG_TIMING_QUERIES) {
            if (!pass->queries[slot][0])
                glCreateQueries(GL_TIMESTAMP, 2, pass->queries[slot]);
            glQueryCounter(pass->queries[slot][0], GL_TIMESTAMP);
        }
        cg_error local = { 0 };
        pass->rebuilt[0] = '\0';
        pass->undeclared_slot[0] = '\0';
        pass->reads_source = 0;
        bool executed = pass->type->execute(pass, pass->state, &local);
        if (!fg_pass_slots_check(pass, err))
            return false;
        if (!executed) {
            if (local.status == CG_OK)
                return cg_fail(err, CG_ERR_PASS, "pass '%s' (type %s): execute failed without a reason",
                               pass->name, pass->type->name);
            return cg_fail(err, local.status, "pass '%s' (type %s): %s", pass->name, pass->type->name,
                           local.message);
        }
        if (timing == FG_TIMING_SYNC) {
            glFinish();
            pass->ms = now_ms() - t0;
        } else if (timing == FG_TIMING_QUERIES) {
            glQueryCounter(pass->queries[slot][1], GL_TIMESTAMP);
            pass->query_issued[slot] = true;
        }
        copy_reads(pass, slot);
        if (timing != FG_TIMING_QUERIES)
            read_reads(pass, slot);
    }
    /* Timestamps of the frame before are ready by now on any sane driver: read them without
     * stalling (a result not available yet is read when its slot comes round again). */
    if (timing == FG_TIMING_QUERIES && graph->frames_executed > 0)
        read_queries(graph, (int)((graph->frames_executed - 1) % FG_QUERY_RING), false);
    graph->frames_executed++;
    return true;
}

double
fg_pass_milliseconds(const fg_pass *pass)
{
    return pass->ms;
}
