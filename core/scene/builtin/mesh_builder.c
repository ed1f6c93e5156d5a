/* The mesh builder of the built-in scenes, and their materials and cameras. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

static bool
grow(void **p, uint32_t *cap, uint32_t need, size_t elem)
{
    if (need <= *cap)
        return true;
    uint32_t c = *cap ? *cap : 64;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, (size_t)c * elem);
    if (!q)
        return false;
    *p = q;
    *cap = c;
    return true;
}

uint32_t
mb_vertex(mesh_builder *b, const double p[3], const double n[3])
{
    uint32_t cap = b->vertex_cap;
    if (!grow((void **)&b->positions, &cap, b->vertex_count + 1, 3 * sizeof(float)) ||
        (cap = b->vertex_cap, !grow((void **)&b->normals, &cap, b->vertex_count + 1, 3 * sizeof(float)))) {
        b->failed = true;
        return 0;
    }
    b->vertex_cap = cap;
    for (int k = 0; k < 3; k++) {
        b->positions[3 * b->vertex_count + k] = (float)p[k];
        b->normals[3 * b->vertex_count + k] = (float)n[k];
    }
    return b->vertex_count++;
}

void
mb_triangle(mesh_builder *b, uint32_t i0, uint32_t i1, uint32_t i2)
{
    if (!grow((void **)&b->indices, &b->index_cap, b->index_count + 3, sizeof(uint32_t))) {
        b->failed = true;
        return;
    }
    b->indices[b->index_count++] = i0;
    b->indices[b->index_count++] = i1;
    b->indices[b->index_count++] = i2;
}

static void
face_normal(const double a[3], const double b[3], const double c[3], double n[3])
{
    double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    double e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        n[k] = len > 0 ? n[k] / len : (k == 1);
}

/* A flat triangle, counter-clockwise seen from the side its normal points to. */
void
mb_flat_triangle(mesh_builder *b, const double p0[3], const double p1[3], const double p2[3])
{
    double n[3];
    face_normal(p0, p1, p2, n);
    uint32_t i0 = mb_vertex(b, p0, n), i1 = mb_vertex(b, p1, n), i2 = mb_vertex(b, p2, n);
    mb_triangle(b, i0, i1, i2);
}

/* A flat quad p0 p1 p2 p3, counter-clockwise seen from its front. */
void
mb_quad(mesh_builder *b, const double p0[3], const double p1[3], const double p2[3], const double p3[3])
{
    double n[3];
    face_normal(p0, p1, p2, n);
    uint32_t i0 = mb_vertex(b, p0, n), i1 = mb_vertex(b, p1, n);
    uint32_t i2 = mb_vertex(b, p2, n), i3 = mb_vertex(b, p3, n);
    mb_triangle(b, i0, i1, i2);
    mb_triangle(b, i0, i2, i3);
}

/* An oriented box: centre c, half extents h along the axes rotated by `yaw` about +y.
 * Faces point outwards; `bottom` adds the underside (left out where it is buried). */
void
mb_box(mesh_builder *b, const double c[3], const double h[3], double yaw, bool bottom)
{
    double cs = cos(yaw), sn = sin(yaw);
    double v[8][3];
    for (int i = 0; i < 8; i++) {
        double lx = (i & 1) ? h[0] : -h[0], ly = (i & 2) ? h[1] : -h[1], lz = (i & 4) ? h[2] : -h[2];
        v[i][0] = c[0] + cs * lx + sn * lz;
        v[i][1] = c[1] + ly;
        v[i][2] = c[2] - sn * lx + cs * lz;
    }
    mb_quad(b, v[4], v[5], v[7], v[6]); /* +z */
    mb_quad(b, v[1], v[0], v[2], v[3]); /* -z */
    mb_quad(b, v[5], v[1], v[3], v[7]); /* +x */
    mb_quad(b, v[0], v[4], v[6], v[2]); /* -x */
    mb_quad(b, v[2], v[6], v[7], v[3]); /* +y */
    if (bottom)
        mb_quad(b, v[0], v[1], v[5], v[4]); /* -y */
}

void
mb_free(mesh_builder *b)
{
    free(b->positions);
    free(b->normals);
    free(b->texcoords);
    free(b->indices);
    memset(b, 0, sizeof *b);
}

const float bs_identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };

/* Moves the builder's arrays into a new mesh with one instance at `world`. */
bool
mb_commit(cg_scene *scene, mesh_builder *b, const char *name, int material, cg_mesh_kind kind,
          const float world[16], cg_error *err)
{
    if (b->failed) {
        mb_free(b);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory building mesh '%s'",
                       scene->name, name);
    }
    cg_mesh m = {
        .vertex_count = b->vertex_count,
        .index_count = b->index_count,
        .positions = b->positions,
        .normals = b->normals,
        .texcoords = b->texcoords,
        .indices = b->indices,
        .material = material,
        .kind = kind,
    };
    cg_copy_name(m.name, name);
    cg_mesh_compute_bounds(&m);
    memset(b, 0, sizeof *b);
    int index = cg_scene_add_mesh(scene, &m, err);
    if (index < 0) {
        free(m.positions);
        free(m.normals);
        free(m.texcoords);
        free(m.indices);
        return false;
    }
    return cg_scene_add_instance(scene, index, world, err) >= 0;
}

int
bs_add_material(cg_scene *scene, const char *name, float r, float g, float b, cg_error *err)
{
    cg_material m = cg_material_default(name);
    m.base_color[0] = r;
    m.base_color[1] = g;
    m.base_color[2] = b;
    return cg_scene_add_material(scene, &m, err);
}

/* Camera-to-world matrix of a camera at `eye` looking at `target` with +y up (glTF: the
 * camera looks down its local -z, +x right, +y up). */
void
bs_look_at_world(const double eye[3], const double target[3], float world[16])
{
    double f[3] = { target[0] - eye[0], target[1] - eye[1], target[2] - eye[2] };
    double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int k = 0; k < 3; k++)
        f[k] /= fl;
    double r[3] = { -f[2], 0, f[0] }; /* f x (0,1,0) */
    double rl = sqrt(r[0] * r[0] + r[2] * r[2]);
    r[0] /= rl;
    r[2] /= rl;
    double u[3] = { r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0] };
    float m[16] = { (float)r[0], (float)r[1], (float)r[2], 0,
                    (float)u[0], (float)u[1], (float)u[2], 0,
                    (float)-f[0], (float)-f[1], (float)-f[2], 0,
                    (float)eye[0], (float)eye[1], (float)eye[2], 1 };
    memcpy(world, m, sizeof m);
}

bool
bs_add_perspective_camera(cg_scene *scene, const char *name, const double eye[3], const double target[3],
                       float yfov, float znear, float zfar, cg_error *err)
{
    cg_camera cam = { .type = CG_CAMERA_PERSPECTIVE, .yfov = yfov, .aspect = 0,
                      .znear = znear, .zfar = zfar };
    cg_copy_name(cam.name, name);
    bs_look_at_world(eye, target, cam.world);
    return cg_scene_add_camera(scene, &cam, err) >= 0;
}

void
bs_quat_from_minus_z(const float d[3], double q[4])
{
    double c = -d[2]; /* dot((0, 0, -1), d) */
    if (c < -0.999999) { /* d = +z: half a turn about y */
        q[0] = 0, q[1] = 1, q[2] = 0, q[3] = 0;
        return;
    }
    /* axis (0, 0, -1) x d, w = 1 + c, normalised: the half-angle form. */
    double x = d[1], y = -d[0], z = 0, w = 1 + c;
    double len = sqrt(x * x + y * y + z * z + w * w);
    q[0] = x / len, q[1] = y / len, q[2] = z / len, q[3] = w / len;
}

void
bs_normalize3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
}

/* A unit cube [-0.5, 0.5]^3 with outward faces, placed by instance transforms. */
void
bs_unit_cube(mesh_builder *b)
{
    double c[3] = { 0, 0, 0 }, h[3] = { 0.5, 0.5, 0.5 };
    mb_box(b, c, h, 0, true);
}

void
bs_trs_matrix(double tx, double ty, double tz, double yaw, double sx, double sy, double sz, float m[16])
{
    double c = cos(yaw), s = sin(yaw);
    float out[16] = { (float)(c * sx), 0, (float)(-s * sx), 0,
                      0, (float)sy, 0, 0,
                      (float)(s * sz), 0, (float)(c * sz), 0,
                      (float)tx, (float)ty, (float)tz, 1 };
    memcpy(m, out, sizeof out);
}
