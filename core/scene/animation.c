/* core/scene/animation.c: the kept node hierarchy, glTF 2.0 animation samplers and posing a
 * scene at a time (cg/scene.h, docs/gltf.md "Animation").
 *
 * Interpolation follows glTF 2.0, Appendix C ("Animation Sampler Interpolation Modes"):
 * STEP holds a key's value until the next key; LINEAR interpolates linearly, rotations by
 * spherical linear interpolation along the shorter arc; CUBICSPLINE is the cubic Hermite
 * spline p(t) = (2t^3 - 3t^2 + 1) v_k + (t^3 - 2t^2 + t) m_k + (-2t^3 + 3t^2) v_k+1
 * + (t^3 - t^2) m_k+1 with t in [0, 1] across the segment, m_k = (t_k+1 - t_k) x the
 * out-tangent of key k and m_k+1 = (t_k+1 - t_k) x the in-tangent of key k + 1. Rotations
 * are normalised after interpolation, as the specification asks. Before its first key a
 * channel holds its first value and after its last key its last value. Arithmetic is in
 * double precision; node world matrices stay in double down the hierarchy.
 *
 * Skins (glTF 2.0, 3.7.3) are applied here, on the CPU, when the scene is posed: a skinned
 * mesh's vertices become sum_i w_i x world(joint_i) x inverse_bind(joint_i) x bind position,
 * in world space. Why on the CPU and not in a vertex shader: every pass that reads geometry
 * (the rasterizing passes, voxelize's compute voxelizer that reads the vertex buffers itself,
 * the path tracer's BVH, the classification and the bounds) then sees one posed mesh, with no
 * skinning code in each of them; a pose costs one pass over the vertices when the joints move,
 * small beside a frame for the skinned meshes glTF files carry (thousands of vertices). */
#include "cg/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

/* ------------------------------------------------------------------ nodes and attachments */

cg_node
cg_node_default(const char *name)
{
    cg_node n = { .parent = -1, .rotation = { 0, 0, 0, 1 }, .scale = { 1, 1, 1 } };
    cg_copy_name(n.name, name);
    for (int i = 0; i < 4; i++)
        n.world[5 * i] = 1.0;
    return n;
}

void
cg_node_local(const cg_node *node, double m[16])
{
    if (node->has_matrix) {
        for (int i = 0; i < 16; i++)
            m[i] = node->matrix[i];
        return;
    }
    double x = node->rotation[0], y = node->rotation[1], z = node->rotation[2], w = node->rotation[3];
    double len = sqrt(x * x + y * y + z * z + w * w);
    if (len > 0) {
        x /= len, y /= len, z /= len, w /= len;
    } else {
        x = y = z = 0, w = 1;
    }
    /* glTF 2.0, 3.5.3: local = T x R x S, column-major. */
    double r[9] = { 1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
                    2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                    2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y) };
    for (int c = 0; c < 3; c++) {
        for (int row = 0; row < 3; row++)
            m[c * 4 + row] = r[c * 3 + row] * node->scale[c];
        m[c * 4 + 3] = 0;
    }
    m[12] = node->translation[0], m[13] = node->translation[1], m[14] = node->translation[2], m[15] = 1;
}

static bool
grow(void **array, int count, size_t size, cg_error *err, const char *what)
{
    void *bigger = realloc(*array, (size_t)(count + 1) * size);
    if (!bigger)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory adding a %s to the scene", what);
    *array = bigger;
    return true;
}

int
cg_scene_add_node(cg_scene *scene, const cg_node *node, cg_error *err)
{
    if (!grow((void **)&scene->nodes, scene->node_count, sizeof *node, err, "node"))
        return -1;
    scene->nodes[scene->node_count] = *node;
    return scene->node_count++;
}

int
cg_scene_attach(cg_scene *scene, cg_attachment_kind kind, int index, int node, cg_error *err)
{
    cg_attachment a = { .kind = kind, .index = index, .node = node };
    if (!grow((void **)&scene->attachments, scene->attachment_count, sizeof a, err, "node attachment"))
        return -1;
    scene->attachments[scene->attachment_count] = a;
    if (kind == CG_ATTACH_INSTANCE && index >= 0 && index < scene->instance_count)
        scene->instances[index].moving = true;
    return scene->attachment_count++;
}

/* ------------------------------------------------------------------ skins */

int
cg_scene_add_skin(cg_scene *scene, const char *name, int joint_count, int *joints, float *inverse_bind,
                  cg_error *err)
{
    if (!grow((void **)&scene->skins, scene->skin_count, sizeof *scene->skins, err, "skin")) {
        free(joints);
        free(inverse_bind);
        return -1;
    }
    cg_skin *s = &scene->skins[scene->skin_count];
    memset(s, 0, sizeof *s);
    cg_copy_name(s->name, name);
    s->joint_count = joint_count;
    s->joints = joints;
    s->inverse_bind = inverse_bind;
    return scene->skin_count++;
}

static float *
copy_floats(const float *src, size_t n)
{
    float *dst = malloc(sizeof *dst * (n ? n : 1));
    if (dst && src)
        memcpy(dst, src, sizeof *dst * n);
    return dst;
}

int
cg_scene_add_skinned_mesh(cg_scene *scene, int mesh, int instance, int skin, int influences, uint16_t *joints,
                          float *weights, cg_error *err)
{
    cg_skinned_mesh sk = { .mesh = mesh, .instance = instance, .skin = skin, .influences = influences,
                           .joints = joints, .weights = weights };
    const cg_mesh *m = &scene->meshes[mesh];
    int joint_count = scene->skins[skin].joint_count;
    size_t nv = m->vertex_count;
    sk.bind_positions = copy_floats(m->positions, nv * 3);
    sk.bind_normals = copy_floats(m->normals, nv * 3);
    sk.bind_tangents = m->tangents ? copy_floats(m->tangents, nv * 4) : NULL;
    sk.joint_bounds = malloc(sizeof *sk.joint_bounds * 6 * (size_t)joint_count);
    sk.posed_with = malloc(sizeof *sk.posed_with * 16 * (size_t)joint_count);
    if (!sk.bind_positions || !sk.bind_normals || (m->tangents && !sk.bind_tangents) || !sk.joint_bounds ||
        !sk.posed_with) {
        cg_skinned_mesh_free(&sk);
        cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory for skinned mesh '%s'", m->name);
        return -1;
    }
    if (!grow((void **)&scene->skinned, scene->skinned_count, sizeof sk, err, "skinned mesh")) {
        cg_skinned_mesh_free(&sk);
        return -1;
    }
    for (int j = 0; j < joint_count; j++) {
        for (int k = 0; k < 3; k++)
            sk.joint_bounds[6 * j + k] = INFINITY, sk.joint_bounds[6 * j + 3 + k] = -INFINITY;
        for (int k = 0; k < 16; k++)
            sk.posed_with[16 * j + k] = NAN;
    }
    for (size_t v = 0; v < nv; v++)
        for (int i = 0; i < influences; i++) {
            size_t at = v * (size_t)influences + (size_t)i;
            if (!(weights[at] > 0))
                continue;
            float *b = sk.joint_bounds + 6 * (size_t)joints[at];
            for (int k = 0; k < 3; k++) {
                b[k] = fminf(b[k], sk.bind_positions[3 * v + k]);
                b[3 + k] = fmaxf(b[3 + k], sk.bind_positions[3 * v + k]);
            }
        }
    cg_instance *inst = &scene->instances[instance];
    for (int i = 0; i < 16; i++)
        inst->world[i] = i % 5 == 0 ? 1.0f : 0.0f;
    scene->skinned[scene->skinned_count] = sk;
    return scene->skinned_count++;
}

/* ------------------------------------------------------------------ morph targets */

int
cg_scene_add_morphed_mesh(cg_scene *scene, const cg_morphed_mesh *morph, cg_error *err)
{
    cg_morphed_mesh mm = *morph;
    const cg_mesh *m = &scene->meshes[mm.mesh];
    size_t nv = m->vertex_count, n = (size_t)mm.target_count;
    mm.applied = malloc(sizeof *mm.applied * n);
    mm.base_positions = copy_floats(m->positions, nv * 3);
    mm.base_normals = copy_floats(m->normals, nv * 3);
    mm.base_tangents = m->tangents ? copy_floats(m->tangents, nv * 4) : NULL;
    mm.delta_bounds = malloc(sizeof *mm.delta_bounds * 6 * n);
    if (!mm.applied || !mm.base_positions || !mm.base_normals || (m->tangents && !mm.base_tangents) ||
        !mm.delta_bounds) {
        cg_morphed_mesh_free(&mm);
        cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory for the morph targets of mesh '%s'", m->name);
        return -1;
    }
    for (size_t t = 0; t < n; t++) {
        mm.applied[t] = NAN;
        for (int k = 0; k < 3; k++) {
            float lo = 0, hi = 0; /* a target's box holds 0: the base itself */
            for (size_t v = 0; mm.position_deltas && v < nv; v++) {
                float d = mm.position_deltas[(t * nv + v) * 3 + (size_t)k];
                lo = fminf(lo, d);
                hi = fmaxf(hi, d);
            }
            mm.delta_bounds[6 * t + (size_t)k] = lo;
            mm.delta_bounds[6 * t + 3 + (size_t)k] = hi;
        }
    }
    if (!grow((void **)&scene->morphed, scene->morphed_count, sizeof mm, err, "morphed mesh")) {
        cg_morphed_mesh_free(&mm);
        return -1;
    }
    scene->morphed[scene->morphed_count] = mm;
    return scene->morphed_count++;
}

/* ------------------------------------------------------------------ channels */

int
cg_anim_channel_components(const cg_anim_channel *channel)
{
    return channel->path == CG_ANIM_ROTATION ? 4 : channel->path == CG_ANIM_WEIGHTS ? channel->weight_count : 3;
}

int
cg_anim_channel_stride(const cg_anim_channel *channel)
{
    int n = cg_anim_channel_components(channel);
    return channel->interpolation == CG_INTERP_CUBICSPLINE ? 3 * n : n;
}

bool
cg_anim_channel_alloc(cg_anim_channel *channel, int key_count, cg_error *err)
{
    channel->key_count = key_count;
    channel->times = malloc(sizeof(float) * (size_t)(key_count > 0 ? key_count : 1));
    channel->values = malloc(sizeof(float) * (size_t)(key_count > 0 ? key_count : 1) *
                             (size_t)cg_anim_channel_stride(channel));
    if (!channel->times || !channel->values) {
        free(channel->times);
        free(channel->values);
        channel->times = channel->values = NULL;
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory for %d animation keys", key_count);
    }
    return true;
}

int
cg_scene_add_animation(cg_scene *scene, cg_animation *animation, cg_error *err)
{
    if (!grow((void **)&scene->animations, scene->animation_count, sizeof *animation, err, "animation")) {
        for (int c = 0; c < animation->channel_count; c++) {
            free(animation->channels[c].times);
            free(animation->channels[c].values);
        }
        free(animation->channels);
        memset(animation, 0, sizeof *animation);
        return -1;
    }
    scene->animations[scene->animation_count] = *animation;
    return scene->animation_count++;
}

static void
normalize4(double q[4])
{
    double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (len > 0)
        for (int k = 0; k < 4; k++)
            q[k] /= len;
    else
        q[0] = q[1] = q[2] = 0, q[3] = 1;
}

/* glTF 2.0, Appendix C, "Spherical Linear Interpolation": along the shorter arc. */
static void
slerp(const float *a, const float *b, double u, double out[4])
{
    double d = 0;
    for (int k = 0; k < 4; k++)
        d += (double)a[k] * b[k];
    double sign = d < 0 ? -1.0 : 1.0, ad = fabs(d);
    double wa, wb;
    if (ad > 1.0 - 1e-9) {
        /* (Nearly) the same rotation: sin(angle) vanishes, the linear blend is exact enough. */
        wa = 1.0 - u;
        wb = sign * u;
    } else {
        double angle = acos(ad), s = sin(angle);
        wa = sin((1.0 - u) * angle) / s;
        wb = sign * sin(u * angle) / s;
    }
    for (int k = 0; k < 4; k++)
        out[k] = wa * a[k] + wb * b[k];
    normalize4(out);
}

void
cg_anim_channel_sample(const cg_anim_channel *channel, double t, double *out)
{
    int n = cg_anim_channel_components(channel), stride = cg_anim_channel_stride(channel);
    bool cubic = channel->interpolation == CG_INTERP_CUBICSPLINE;
    int value = cubic ? n : 0; /* where a key's value starts: after the in-tangent */
    int keys = channel->key_count;
    const float *times = channel->times, *v = channel->values;
    if (n == 3)
        out[3] = 0;
    int k;
    if (keys <= 1 || !(t > times[0])) {
        k = 0;
    } else if (t >= times[keys - 1]) {
        k = keys - 1;
    } else {
        /* The segment [times[k], times[k + 1]) holding t. */
        int lo = 0, hi = keys - 1;
        while (hi - lo > 1) {
            int mid = lo + (hi - lo) / 2;
            if (times[mid] <= t)
                lo = mid;
            else
                hi = mid;
        }
        k = lo;
        double dt = (double)times[k + 1] - times[k], u = (t - times[k]) / dt;
        const float *a = v + (size_t)k * stride, *b = v + (size_t)(k + 1) * stride;
        switch (channel->interpolation) {
        case CG_INTERP_STEP:
            break;
        case CG_INTERP_LINEAR:
            if (channel->path == CG_ANIM_ROTATION) {
                slerp(a, b, u, out);
            } else {
                for (int c = 0; c < n; c++)
                    out[c] = (1.0 - u) * a[c] + u * b[c];
            }
            return;
        case CG_INTERP_CUBICSPLINE: {
            double u2 = u * u, u3 = u2 * u;
            double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
            for (int c = 0; c < n; c++)
                out[c] = h00 * a[n + c] + h10 * dt * a[2 * n + c] + h01 * b[n + c] + h11 * dt * b[c];
            if (channel->path == CG_ANIM_ROTATION)
                normalize4(out);
            return;
        }
        }
    }
    for (int c = 0; c < n; c++)
        out[c] = v[(size_t)k * stride + value + c];
    if (channel->path == CG_ANIM_ROTATION)
        normalize4(out);
}

bool
cg_scene_is_animated(const cg_scene *scene)
{
    for (int a = 0; a < scene->animation_count; a++)
        if (scene->animations[a].channel_count > 0)
            return true;
    return false;
}

void
cg_scene_animation_range(const cg_scene *scene, double *start, double *end)
{
    bool any = false;
    *start = *end = 0;
    for (int a = 0; a < scene->animation_count; a++)
        for (int c = 0; c < scene->animations[a].channel_count; c++) {
            const cg_anim_channel *ch = &scene->animations[a].channels[c];
            if (ch->key_count < 1)
                continue;
            double first = ch->times[0], last = ch->times[ch->key_count - 1];
            if (!any || first < *start)
                *start = first;
            if (!any || last > *end)
                *end = last;
            any = true;
        }
}

/* ------------------------------------------------------------------ posing */

static void
mat_mul(const double a[16], const double b[16], double out[16])
{
    double r[16];
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
    memcpy(out, r, sizeof r);
}

/* What follows a node, computed from its world matrix. */
static void
instance_world(const cg_node *n, float world[16])
{
    for (int i = 0; i < 16; i++)
        world[i] = (float)n->world[i];
}

static void
light_pose(const cg_node *n, float position[3], float direction[3])
{
    /* KHR_lights_punctual: the light sits at the node's origin and shines down its -Z. */
    const double *w = n->world;
    double d[3] = { -w[8], -w[9], -w[10] };
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; k++) {
        position[k] = (float)w[12 + k];
        direction[k] = len > 0 ? (float)(d[k] / len) : (k == 1 ? -1.0f : 0.0f);
    }
}

/* Joint j's skinning matrix, world(joint) x inverse_bind(joint) (glTF 2.0, 3.7.3.3). */
static void
skinning_matrix(const cg_scene *scene, const cg_skin *skin, int j, double out[16])
{
    double ibm[16];
    for (int k = 0; k < 16; k++)
        ibm[k] = skin->inverse_bind[16 * j + k];
    mat_mul(scene->nodes[skin->joints[j]].world, ibm, out);
}

static void
cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* The mesh's vertices posed by the skinning matrices in sk->posed_with: each vertex by the
 * weighted sum of its joints' matrices (linear blend skinning, what glTF 2.0 3.7.3.3 defines);
 * normals by that sum's inverse transpose (its cofactor matrix, times the sign of its
 * determinant), tangents by the sum itself, both normalised. */
static void
deform(cg_scene *scene, const cg_skinned_mesh *sk)
{
    cg_mesh *mesh = &scene->meshes[sk->mesh];
    int n = sk->influences;
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        double b[16] = { 0 };
        for (int i = 0; i < n; i++) {
            double w = sk->weights[v * (size_t)n + (size_t)i];
            if (w == 0)
                continue;
            const double *m = sk->posed_with + 16 * (size_t)sk->joints[v * (size_t)n + (size_t)i];
            for (int k = 0; k < 16; k++)
                b[k] += w * m[k];
        }
        const float *p = sk->bind_positions + 3 * v, *nb = sk->bind_normals + 3 * v;
        for (int r = 0; r < 3; r++)
            mesh->positions[3 * v + r] = (float)(b[r] * p[0] + b[4 + r] * p[1] + b[8 + r] * p[2] + b[12 + r]);
        double c0[3] = { b[0], b[1], b[2] }, c1[3] = { b[4], b[5], b[6] }, c2[3] = { b[8], b[9], b[10] };
        double x12[3], x20[3], x01[3];
        cross3(c1, c2, x12);
        cross3(c2, c0, x20);
        cross3(c0, c1, x01);
        double det = c0[0] * x12[0] + c0[1] * x12[1] + c0[2] * x12[2];
        double sign = det < 0 ? -1.0 : 1.0, nn[3], len = 0;
        for (int r = 0; r < 3; r++) {
            nn[r] = sign * (nb[0] * x12[r] + nb[1] * x20[r] + nb[2] * x01[r]);
            len += nn[r] * nn[r];
        }
        len = sqrt(len);
        for (int r = 0; r < 3; r++)
            mesh->normals[3 * v + r] = len > 0 ? (float)(nn[r] / len) : nb[r];
        if (mesh->tangents && sk->bind_tangents) {
            const float *tb = sk->bind_tangents + 4 * v;
            double t[3], tl = 0;
            for (int r = 0; r < 3; r++) {
                t[r] = b[r] * tb[0] + b[4 + r] * tb[1] + b[8 + r] * tb[2];
                tl += t[r] * t[r];
            }
            tl = sqrt(tl);
            for (int r = 0; r < 3; r++)
                mesh->tangents[4 * v + r] = tl > 0 ? (float)(t[r] / tl) : tb[r];
            mesh->tangents[4 * v + 3] = tb[3];
        }
    }
    cg_mesh_compute_bounds(mesh);
}

/* Poses the skinned meshes whose skinning matrices changed; with `changes`, stamps them. */
static void
pose_skins(cg_scene *scene, uint64_t stamp, cg_scene_changes *changes)
{
    for (int i = 0; i < scene->skinned_count; i++) {
        cg_skinned_mesh *sk = &scene->skinned[i];
        const cg_skin *skin = &scene->skins[sk->skin];
        bool moved = false;
        for (int j = 0; j < skin->joint_count; j++) {
            double m[16];
            skinning_matrix(scene, skin, j, m);
            /* memcmp, not ==: the NaN of a mesh never posed differs from everything. */
            if (memcmp(m, sk->posed_with + 16 * j, sizeof m)) {
                memcpy(sk->posed_with + 16 * j, m, sizeof m);
                moved = true;
            }
        }
        if (!moved)
            continue;
        deform(scene, sk);
        if (changes) {
            scene->meshes[sk->mesh].revision = stamp;
            scene->instances[sk->instance].revision = stamp;
            changes->instances_moved++;
            changes->meshes_deformed++;
        }
    }
}

/* The base plus the weighted targets (glTF 2.0, 3.7.2.2); normals and tangents normalised. */
static void
morph(cg_scene *scene, const cg_morphed_mesh *mm)
{
    cg_mesh *mesh = &scene->meshes[mm->mesh];
    size_t nv = mesh->vertex_count;
    for (size_t v = 0; v < nv; v++) {
        double p[3], n[3], tg[3];
        for (int k = 0; k < 3; k++) {
            p[k] = mm->base_positions[3 * v + (size_t)k];
            n[k] = mm->base_normals[3 * v + (size_t)k];
            tg[k] = mm->base_tangents ? mm->base_tangents[4 * v + (size_t)k] : 0;
        }
        for (int t = 0; t < mm->target_count; t++) {
            double w = mm->weights[t];
            if (w == 0)
                continue;
            size_t at = ((size_t)t * nv + v) * 3;
            for (int k = 0; k < 3; k++) {
                if (mm->position_deltas)
                    p[k] += w * mm->position_deltas[at + (size_t)k];
                if (mm->normal_deltas)
                    n[k] += w * mm->normal_deltas[at + (size_t)k];
                if (mm->tangent_deltas)
                    tg[k] += w * mm->tangent_deltas[at + (size_t)k];
            }
        }
        double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double tl = sqrt(tg[0] * tg[0] + tg[1] * tg[1] + tg[2] * tg[2]);
        for (int k = 0; k < 3; k++) {
            mesh->positions[3 * v + (size_t)k] = (float)p[k];
            mesh->normals[3 * v + (size_t)k] = nl > 0 ? (float)(n[k] / nl) : mm->base_normals[3 * v + (size_t)k];
            if (mesh->tangents && mm->base_tangents)
                mesh->tangents[4 * v + (size_t)k] = tl > 0 ? (float)(tg[k] / tl) : mm->base_tangents[4 * v + (size_t)k];
        }
    }
    cg_mesh_compute_bounds(mesh);
}

/* Morphs the meshes whose weights changed since they were last morphed; with `changes`, stamps
 * them. */
static void
pose_morphs(cg_scene *scene, uint64_t stamp, cg_scene_changes *changes)
{
    for (int i = 0; i < scene->morphed_count; i++) {
        cg_morphed_mesh *mm = &scene->morphed[i];
        /* memcmp, not ==: the NaN of a mesh never morphed differs from everything. */
        if (!memcmp(mm->weights, mm->applied, sizeof *mm->weights * (size_t)mm->target_count))
            continue;
        memcpy(mm->applied, mm->weights, sizeof *mm->weights * (size_t)mm->target_count);
        morph(scene, mm);
        if (changes) {
            cg_instance *inst = &scene->instances[mm->instance];
            scene->meshes[mm->mesh].revision = stamp;
            if (inst->revision != stamp) /* not counted yet (its node may have moved too) */
                changes->instances_moved++;
            inst->revision = stamp;
            changes->meshes_deformed++;
        }
    }
}

/* Poses everything; with `changes`, stamps what changed with revision `stamp`. Skinned and
 * morphed meshes are posed only with `skin` (the bounds' sampling bounds them by their joints
 * and their targets' boxes instead). */
static void
pose(cg_scene *scene, double t, uint64_t stamp, cg_scene_changes *changes, bool skin)
{
    for (int a = 0; a < scene->animation_count; a++)
        for (int c = 0; c < scene->animations[a].channel_count; c++) {
            const cg_anim_channel *ch = &scene->animations[a].channels[c];
            cg_node *n = &scene->nodes[ch->node];
            double v[CG_MAX_MORPH_TARGETS > 4 ? CG_MAX_MORPH_TARGETS : 4];
            cg_anim_channel_sample(ch, t, v);
            if (ch->path == CG_ANIM_WEIGHTS) {
                for (int k = 0; k < scene->morphed_count; k++) {
                    cg_morphed_mesh *mm = &scene->morphed[k];
                    for (int w = 0; mm->node == ch->node && w < mm->target_count && w < ch->weight_count; w++)
                        mm->weights[w] = (float)v[w];
                }
                continue;
            }
            float *dst = ch->path == CG_ANIM_TRANSLATION ? n->translation
                         : ch->path == CG_ANIM_ROTATION  ? n->rotation
                                                         : n->scale;
            for (int k = 0; k < cg_anim_channel_components(ch); k++)
                dst[k] = (float)v[k];
        }
    for (int i = 0; i < scene->node_count; i++) {
        cg_node *n = &scene->nodes[i];
        double local[16];
        cg_node_local(n, local);
        if (n->parent >= 0)
            mat_mul(scene->nodes[n->parent].world, local, n->world);
        else
            memcpy(n->world, local, sizeof local);
    }
    for (int i = 0; i < scene->attachment_count; i++) {
        const cg_attachment *at = &scene->attachments[i];
        const cg_node *n = &scene->nodes[at->node];
        if (at->kind == CG_ATTACH_INSTANCE) {
            cg_instance *inst = &scene->instances[at->index];
            float w[16];
            instance_world(n, w);
            if (memcmp(w, inst->world, sizeof w)) {
                memcpy(inst->world, w, sizeof w);
                if (changes) {
                    inst->revision = stamp;
                    changes->instances_moved++;
                }
            }
        } else if (at->kind == CG_ATTACH_LIGHT) {
            cg_light *l = &scene->lights[at->index];
            float p[3], d[3];
            light_pose(n, p, d);
            if (memcmp(p, l->position, sizeof p) || memcmp(d, l->direction, sizeof d)) {
                memcpy(l->position, p, sizeof p);
                memcpy(l->direction, d, sizeof d);
                if (changes)
                    changes->lights = true;
            }
        } else {
            cg_camera *cam = &scene->cameras[at->index];
            float w[16];
            instance_world(n, w);
            if (memcmp(w, cam->world, sizeof w)) {
                memcpy(cam->world, w, sizeof w);
                if (changes)
                    changes->cameras = true;
            }
        }
    }
    if (skin) {
        pose_morphs(scene, stamp, changes);
        pose_skins(scene, stamp, changes);
    }
    scene->time = t;
}

void
cg_scene_pose(cg_scene *scene, double t)
{
    pose(scene, t, 0, NULL, true);
}

void
cg_scene_evaluate(cg_scene *scene, double t, cg_scene_changes *changes)
{
    cg_scene_changes local = { 0 };
    uint64_t stamp = scene->revision + 1;
    pose(scene, t, stamp, &local, true);
    if (local.instances_moved || local.lights || local.cameras) {
        scene->revision = stamp;
        if (local.instances_moved)
            scene->instances_revision = stamp;
        if (local.lights)
            scene->lights_revision = stamp;
        if (local.cameras)
            scene->cameras_revision = stamp;
    }
    if (changes)
        *changes = local;
}

void
cg_scene_lights_changed(cg_scene *scene)
{
    scene->lights_revision = ++scene->revision;
}

/* ------------------------------------------------------------------ bounds over the animation */

static int
compare_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return x < y ? -1 : x > y;
}

/* The times the bounds are sampled at: every distinct key time and, between consecutive ones,
 * up to 15 more evenly spaced (16 segments), about MOTION_SAMPLES in all (fewer between keys
 * when there are many keys; MOTION_SAMPLES + 1 evenly spaced times when there are more distinct
 * keys than that). */
#define MOTION_SAMPLES 4096

static double *
motion_times(const cg_scene *scene, int *count)
{
    size_t keys = 0;
    for (int a = 0; a < scene->animation_count; a++)
        for (int c = 0; c < scene->animations[a].channel_count; c++)
            keys += (size_t)scene->animations[a].channels[c].key_count;
    float *all = malloc(sizeof *all * (keys ? keys : 1));
    if (!all)
        return NULL;
    size_t n = 0;
    for (int a = 0; a < scene->animation_count; a++)
        for (int c = 0; c < scene->animations[a].channel_count; c++) {
            const cg_anim_channel *ch = &scene->animations[a].channels[c];
            memcpy(all + n, ch->times, sizeof *all * (size_t)ch->key_count);
            n += (size_t)ch->key_count;
        }
    qsort(all, n, sizeof *all, compare_float);
    size_t distinct = 0;
    for (size_t i = 0; i < n; i++)
        if (distinct == 0 || all[i] != all[distinct - 1])
            all[distinct++] = all[i];
    double *times = malloc(sizeof *times * (MOTION_SAMPLES + 1));
    if (!times || distinct == 0) {
        free(all);
        free(times);
        return NULL;
    }
    int m = 0;
    if (distinct > MOTION_SAMPLES) {
        for (int i = 0; i <= MOTION_SAMPLES; i++)
            times[m++] = all[0] + ((double)all[distinct - 1] - all[0]) * i / MOTION_SAMPLES;
    } else {
        size_t segments = distinct - 1;
        int per = segments ? (int)(MOTION_SAMPLES / segments) : 1;
        per = per > 16 ? 16 : per < 1 ? 1 : per;
        for (size_t i = 0; i < distinct; i++) {
            times[m++] = all[i];
            for (int s = 1; i + 1 < distinct && s < per; s++)
                times[m++] = all[i] + ((double)all[i + 1] - all[i]) * s / per;
        }
    }
    free(all);
    *count = m;
    return times;
}

static void
box_add(const float world[16], const cg_mesh *mesh, double lo[3], double hi[3])
{
    for (int c = 0; c < 8; c++) {
        double p[3] = { (c & 1) ? mesh->bounds_max[0] : mesh->bounds_min[0],
                        (c & 2) ? mesh->bounds_max[1] : mesh->bounds_min[1],
                        (c & 4) ? mesh->bounds_max[2] : mesh->bounds_min[2] };
        for (int r = 0; r < 3; r++) {
            double w = (double)world[r] * p[0] + (double)world[4 + r] * p[1] + (double)world[8 + r] * p[2] +
                       world[12 + r];
            lo[r] = fmin(lo[r], w);
            hi[r] = fmax(hi[r], w);
        }
    }
}

/* A box holding a skinned mesh as posed now, without posing its vertices: each posed vertex is
 * a weighted mean (weights >= 0, summing to 1) of its joints' images of it, so it lies in the
 * box of the joints' images of their own boxes of the vertices they weigh. */
static void
skinned_box_add(const cg_scene *scene, const cg_skinned_mesh *sk, double lo[3], double hi[3])
{
    const cg_skin *skin = &scene->skins[sk->skin];
    for (int j = 0; j < skin->joint_count; j++) {
        const float *jb = sk->joint_bounds + 6 * j;
        if (!(jb[0] <= jb[3]))
            continue;
        double m[16];
        skinning_matrix(scene, skin, j, m);
        for (int c = 0; c < 8; c++) {
            double p[3] = { jb[(c & 1) ? 3 : 0], jb[(c & 2) ? 4 : 1], jb[(c & 4) ? 5 : 2] };
            for (int r = 0; r < 3; r++) {
                double w = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
                lo[r] = fmin(lo[r], w);
                hi[r] = fmax(hi[r], w);
            }
        }
    }
}

/* A box holding a morphed mesh at the weights of the current pose, without morphing it: the
 * base's box plus, per target, its displacements' box scaled by the weight. */
static void
morphed_box_add(const cg_scene *scene, const cg_morphed_mesh *mm, double lo[3], double hi[3])
{
    float blo[3], bhi[3];
    for (int k = 0; k < 3; k++)
        blo[k] = INFINITY, bhi[k] = -INFINITY;
    for (size_t v = 0; v < scene->meshes[mm->mesh].vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            blo[k] = fminf(blo[k], mm->base_positions[3 * v + (size_t)k]);
            bhi[k] = fmaxf(bhi[k], mm->base_positions[3 * v + (size_t)k]);
        }
    for (int t = 0; t < mm->target_count; t++)
        for (int k = 0; k < 3; k++) {
            float a = mm->weights[t] * mm->delta_bounds[6 * t + k], b = mm->weights[t] * mm->delta_bounds[6 * t + 3 + k];
            blo[k] += fminf(a, b);
            bhi[k] += fmaxf(a, b);
        }
    cg_mesh box = { .bounds_min = { blo[0], blo[1], blo[2] }, .bounds_max = { bhi[0], bhi[1], bhi[2] } };
    box_add(scene->instances[mm->instance].world, &box, lo, hi);
}

bool
cg_scene_motion_bounds(cg_scene *scene, double lo[3], double hi[3])
{
    int count = 0;
    double *times = motion_times(scene, &count);
    if (!times)
        return false;
    int n = scene->instance_count;
    double *box = malloc(sizeof *box * 6 * (size_t)(n > 0 ? n : 1));
    if (!box) {
        free(times);
        return false;
    }
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            box[6 * i + k] = INFINITY, box[6 * i + 3 + k] = -INFINITY;
    bool *skinned = calloc((size_t)(n > 0 ? n : 1), sizeof *skinned);
    if (!skinned) {
        free(box);
        free(times);
        return false;
    }
    for (int k = 0; k < scene->skinned_count; k++)
        skinned[scene->skinned[k].instance] = true;
    for (int k = 0; k < scene->morphed_count; k++)
        skinned[scene->morphed[k].instance] = true;
    double now = scene->time;
    for (int s = 0; s < count; s++) {
        pose(scene, times[s], 0, NULL, false);
        for (int i = 0; i < n; i++) {
            const cg_instance *inst = &scene->instances[i];
            if (inst->moving && !skinned[i] && scene->meshes[inst->mesh].vertex_count > 0)
                box_add(inst->world, &scene->meshes[inst->mesh], box + 6 * i, box + 6 * i + 3);
        }
        for (int k = 0; k < scene->skinned_count; k++)
            skinned_box_add(scene, &scene->skinned[k], box + 6 * scene->skinned[k].instance,
                            box + 6 * scene->skinned[k].instance + 3);
        for (int k = 0; k < scene->morphed_count; k++)
            morphed_box_add(scene, &scene->morphed[k], box + 6 * scene->morphed[k].instance,
                            box + 6 * scene->morphed[k].instance + 3);
    }
    free(skinned);
    pose(scene, now, 0, NULL, false);
    bool any = false;
    for (int i = 0; i < n; i++) {
        cg_instance *inst = &scene->instances[i];
        if (!inst->moving || scene->meshes[inst->mesh].vertex_count == 0)
            continue;
        for (int k = 0; k < 3; k++) {
            inst->motion_min[k] = (float)box[6 * i + k];
            inst->motion_max[k] = (float)box[6 * i + 3 + k];
            lo[k] = fmin(lo[k], box[6 * i + k]);
            hi[k] = fmax(hi[k], box[6 * i + 3 + k]);
        }
        any = true;
    }
    free(box);
    free(times);
    return any;
}
