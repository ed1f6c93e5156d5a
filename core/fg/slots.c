/* A pass's slots at prepare and execute: handles found once by name, the GL objects behind them,
 * and the by-name lookups, which refuse a name the pass did not declare.
 *
 * A handle is the slot's place among what the pass's declare() stated at the last compile: input i
 * is i + 1, output o is -(o + 1), 0 is no slot. A compile releases every pass state (states hold the
 * handles) before it declares again, so a handle never outlives the declaration it indexes. */
#include <stdio.h>
#include <string.h>

#include "fg_internal.h"

/* The storage behind resource `resource` this frame (`previous`: last frame's, for a
 * double-buffered resource), NULL where none; here, below the slots and execute that both read it. */
const fg_storage *
fg_resource_storage(const fg_graph *graph, int resource, bool previous)
{
    if (resource < 0 || resource >= graph->resource_count)
        return NULL;
    const fg_res *r = &graph->resources[resource];
    if (r->info.storage < 0)
        return NULL;
    if (!r->double_buffered)
        return &graph->storage[r->info.storage];
    /* Even frames write the first storage and read last frame's value from the second;
     * odd frames the other way round. */
    bool second = (graph->frame_parity != 0) != previous;
    return &graph->storage[second ? r->storage2 : r->info.storage];
}

static fg_slot
find_slot(const fg_pass *pass, const char *name)
{
    /* An input shadows an output of the same name: both are then one in-place resource. */
    for (int i = 0; i < pass->input_count; i++)
        if (!strcmp(pass->inputs[i].name, name))
            return (fg_slot){ i + 1 };
    for (int o = 0; o < pass->output_count; o++)
        if (!strcmp(pass->outputs[o].name, name))
            return (fg_slot){ -(o + 1) };
    return FG_NO_SLOT;
}

/* Records the first undeclared name; the graph reports it once the callback returns. A pass sees
 * itself as const at execute, but every fg_pass is the graph's own mutable object. */
static void
record_undeclared(const fg_pass *pass, const char *name)
{
    fg_pass *p = (fg_pass *)pass;
    if (!p->undeclared_slot[0])
        snprintf(p->undeclared_slot, sizeof p->undeclared_slot, "%s", name && *name ? name : "(empty)");
}

static fg_slot
find_declared(const fg_pass *pass, const char *name)
{
    fg_slot slot = name ? find_slot(pass, name) : FG_NO_SLOT;
    if (!slot.index)
        record_undeclared(pass, name);
    return slot;
}

fg_slot
fg_pass_slot(const fg_pass *pass, const char *name)
{
    return find_declared(pass, name);
}

fg_slot
fg_pass_slot_if_declared(const fg_pass *pass, const char *name)
{
    return name ? find_slot(pass, name) : FG_NO_SLOT;
}

bool
fg_pass_slots_check(fg_pass *pass, cg_error *err)
{
    if (!pass->undeclared_slot[0])
        return true;
    char at[512], names[512];
    size_t len = 0;
    names[0] = '\0';
    for (int i = 0; i < pass->input_count + pass->output_count && len < sizeof names; i++) {
        const char *name = i < pass->input_count ? pass->inputs[i].name : pass->outputs[i - pass->input_count].name;
        int k = snprintf(names + len, sizeof names - len, "%s%s", i ? ", " : "", name);
        if (k > 0)
            len += (size_t)k;
    }
    cg_fail(err, CG_ERR_PASS, "%spass '%s' (type %s) looks up slot '%s', which it does not declare (its slots: %s)",
            fg_loc_prefix(&pass->loc, at, sizeof at), pass->name, pass->type->name, pass->undeclared_slot,
            len ? names : "none");
    pass->undeclared_slot[0] = '\0';
    return false;
}

/* The storage behind a slot and its resource's descriptor; NULL when absent (an optional input not
 * connected, a writer with nothing to do) or no slot. */
static const fg_storage *
slot_storage(const fg_pass *pass, fg_slot slot, const fg_resource_desc **desc)
{
    const fg_graph *graph = pass->graph;
    int resource = -1;
    bool previous = false;
    if (slot.index > 0 && slot.index <= pass->input_count) {
        int i = slot.index - 1;
        const fg_input *in = &pass->inputs[i];
        resource = in->resource;
        previous = in->previous;
        for (int o = 0; o < pass->output_count; o++)
            if (pass->outputs[o].in_place_input == i) {
                resource = pass->outputs[o].resource;
                previous = false;
            }
    } else if (slot.index < 0 && -slot.index <= pass->output_count) {
        resource = pass->outputs[-slot.index - 1].resource;
    }
    if (resource < 0)
        return NULL;
    if (desc)
        *desc = &graph->resources[resource].info.desc;
    return fg_resource_storage(graph, resource, previous);
}

bool
fg_slot_present(const fg_pass *pass, fg_slot slot)
{
    return slot_storage(pass, slot, NULL) != NULL;
}

GLuint
fg_slot_texture(const fg_pass *pass, fg_slot slot)
{
    const fg_storage *s = slot_storage(pass, slot, NULL);
    return s && s->desc.kind != FG_BUFFER ? s->object : 0;
}

GLuint
fg_slot_buffer(const fg_pass *pass, fg_slot slot)
{
    const fg_storage *s = slot_storage(pass, slot, NULL);
    return s && s->desc.kind == FG_BUFFER ? s->object : 0;
}

const fg_resource_desc *
fg_slot_resource(const fg_pass *pass, fg_slot slot)
{
    const fg_resource_desc *desc = NULL;
    return slot_storage(pass, slot, &desc) ? desc : NULL;
}

bool
fg_input_present(const fg_pass *pass, const char *name)
{
    fg_slot slot = find_declared(pass, name);
    return slot.index > 0 && pass->inputs[slot.index - 1].resource >= 0;
}

GLuint
fg_texture(const fg_pass *pass, const char *name)
{
    return fg_slot_texture(pass, find_declared(pass, name));
}

GLuint
fg_buffer(const fg_pass *pass, const char *name)
{
    return fg_slot_buffer(pass, find_declared(pass, name));
}

const fg_resource_desc *
fg_resource(const fg_pass *pass, const char *name)
{
    return fg_slot_resource(pass, find_declared(pass, name));
}
