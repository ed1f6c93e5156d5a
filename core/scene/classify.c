/* core/scene/classify.c: which meshes are height fields (hybrid cone tracing paper, section V.A,
 * eq. 5), and the normal rule kept beside it as a documented alternative.
 *
 * Eq. 5, per mesh and per instance in world space (y up; an instance that only turns the mesh
 * about the vertical, scales it uniformly and moves it is measured in the mesh's own frame, the
 * same for all such instances: measured once):
 *   Step 1: the bottom face of the instance's bounding box is sampled on a regular grid of
 *     `resolution` samples along its longer horizontal side (the other side in proportion, at
 *     least 2), at the cells' centres; each sample's value is the largest y at which the vertical
 *     line through it meets the mesh ("the maximum value along the Y axis"). The samples with a
 *     value are the vertices Y of the height-field simplification; a sample whose line meets
 *     nothing (a hole) is no vertex of it.
 *   Step 2: d(X, Y) = mean over x in X of min over y in Y of ||x - y||, divided by the body
 *     diagonal D of the bounding box (which removes the model's units). X: the vertices used by
 *     some triangle, or (the paper's faster option) the centroids of the triangles with an area.
 *   The mesh is a height field when d < threshold (0.001 in the paper) for every instance.
 * The printed eq. 5 has a second inf over x, which would average a single number: the prose
 * ("searches for each x the closest point y", "avg(.) denotes the average") reads as above. It is
 * a one-sided mean distance, not a Hausdorff distance, whatever the paper calls it.
 *
 * Orientation plays no part: a sheet facing down is a height field. A mesh with a moving
 * instance (an animated node) is complex, by either rule. Only the lower vertices of a
 * cliff or a skirt lie off the top surface, each by about its drop, so a terrain with a vertical
 * face keeps a small d; a mesh of two stacked layers has a whole layer a storey below the top one.
 *
 * Resolution: the vertices of a perfect height field are not the grid's, so d > 0 even then: the
 * mean distance from a point to the nearest node of a square lattice of spacing h is
 * h (sqrt 2 + ln(1 + sqrt 2)) / 6 = 0.383 h, about 0.27 / N of the diagonal of a flat square
 * terrain sampled N times per side. Below N ~ 270 no terrain passes 0.001; the default, 2048,
 * is the paper's 2D lightmap resolution and leaves that term at 1.3e-4.
 *
 * Acceleration (the paper: an octree and a compute thread per vertex): the sampled heights form a
 * regular grid, so the nearest sample of a point is found in a min-max pyramid of the grid (a
 * quadtree whose nodes bound their samples' x, z and y): a node is visited only when the
 * distance to its box is below the best found, which is exact and costs O(log N) nodes for a
 * point near the surface. Step 1 runs in row bands and step 2 over chunks of points on one
 * thread per core.
 */
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene_internal.h"

#define CLASSIFY_MAX_THREADS 16

const cg_classify_options *
cg_classify_defaults(cg_classify_options *out, const cg_classify_options *in)
{
    *out = in ? *in : (cg_classify_options){ 0 };
    if (out->resolution <= 0)
        out->resolution = CG_EQ5_DEFAULT_RESOLUTION;
    if (!(out->threshold > 0))
        out->threshold = CG_EQ5_DEFAULT_THRESHOLD;
    if (out->threads <= 0) {
        long n = sysconf(_SC_NPROCESSORS_ONLN);
        out->threads = n > 0 ? (int)n : 1;
    }
    if (out->threads > CLASSIFY_MAX_THREADS)
        out->threads = CLASSIFY_MAX_THREADS;
    return out;
}

/* ---------------------------------------------------------------- threads */

typedef void (*range_fn)(void *ctx, size_t begin, size_t end, int part);

typedef struct range_job {
    range_fn fn;
    void *ctx;
    size_t begin, end;
    int part;
} range_job;

static void *
run_range(void *arg)
{
    range_job *j = arg;
    j->fn(j->ctx, j->begin, j->end, j->part);
    return NULL;
}

/* Calls fn over [0, n) cut into `threads` contiguous parts, each on its own thread (the
 * caller's thread takes the first); a thread that cannot start runs its part here. */
static void
parallel_ranges(size_t n, int threads, range_fn fn, void *ctx)
{
    if (threads < 1)
        threads = 1;
    if ((size_t)threads > n)
        threads = n ? (int)n : 1;
    range_job jobs[CLASSIFY_MAX_THREADS];
    pthread_t ids[CLASSIFY_MAX_THREADS];
    bool started[CLASSIFY_MAX_THREADS] = { false };
    for (int t = 0; t < threads; t++)
        jobs[t] = (range_job){ fn, ctx, n * (size_t)t / (size_t)threads, n * (size_t)(t + 1) / (size_t)threads, t };
    for (int t = 1; t < threads; t++)
        started[t] = pthread_create(&ids[t], NULL, run_range, &jobs[t]) == 0;
    run_range(&jobs[0]);
    for (int t = 1; t < threads; t++) {
        if (started[t])
            pthread_join(ids[t], NULL);
        else
            run_range(&jobs[t]);
    }
}

/* ---------------------------------------------------------------- geometry */

static void
transform_point(const float m[16], const float p[3], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = (double)m[r] * p[0] + (double)m[4 + r] * p[1] + (double)m[8 + r] * p[2] + m[12 + r];
}

static double
upper_3x3_determinant(const float m[16])
{
    return (double)m[0] * ((double)m[5] * m[10] - (double)m[9] * m[6]) -
           (double)m[4] * ((double)m[1] * m[10] - (double)m[9] * m[2]) +
           (double)m[8] * ((double)m[1] * m[6] - (double)m[5] * m[2]);
}

/* One instance of a mesh in world space, relative to its bounding box's minimum corner (so that
 * a mesh far from the origin keeps its precision in the grid's floats). */
typedef struct placed_mesh {
    const cg_mesh *mesh;
    double *p;          /* vertex_count x 3, world minus lo */
    double lo[3], size[3];
} placed_mesh;

static bool
place_mesh(const cg_mesh *mesh, const float world[16], placed_mesh *out, cg_error *err)
{
    memset(out, 0, sizeof *out);
    out->mesh = mesh;
    out->p = malloc((size_t)mesh->vertex_count * 3 * sizeof(double) + 1);
    if (!out->p)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory classifying it", mesh->name);
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (uint32_t v = 0; v < mesh->vertex_count; v++) {
        transform_point(world, mesh->positions + 3 * (size_t)v, out->p + 3 * (size_t)v);
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], out->p[3 * (size_t)v + k]);
            hi[k] = fmax(hi[k], out->p[3 * (size_t)v + k]);
        }
    }
    for (uint32_t v = 0; v < mesh->vertex_count; v++)
        for (int k = 0; k < 3; k++)
            out->p[3 * (size_t)v + k] -= lo[k];
    for (int k = 0; k < 3; k++) {
        out->lo[k] = mesh->vertex_count ? lo[k] : 0;
        out->size[k] = mesh->vertex_count ? hi[k] - lo[k] : 0;
    }
    return true;
}

/* ---------------------------------------------------------------- step 1: the height field */

/* The sampled heights (y relative to the box, -inf where the line meets nothing) and their
 * min-max pyramid: level 0 is the grid; a node of level k holds the extremes of its 2 x 2
 * children of level k - 1 (+inf / -inf when all are empty). */
typedef struct hf_grid {
    int nx, nz;
    double hx, hz;          /* sample spacing: sample (i, j) at ((i + 0.5) hx, (j + 0.5) hz) */
    int levels;
    int level_nx[32], level_nz[32];
    size_t offset[32];      /* of each level in lo[] and hi[] (level 0 uses y) */
    float *y;
    float *lo, *hi;         /* levels 1.. */
} hf_grid;

typedef struct raster_ctx {
    const placed_mesh *pm;
    hf_grid *g;
} raster_ctx;

/* Rows [begin, end) of the grid: every triangle with an area seen from above is drawn into the
 * samples its xz projection covers, keeping the largest y. Per row the triangle covers one span
 * of x, where its plane gives y linearly; the span is widened by a tolerance relative to the
 * triangle's size, so that the shared edges of a mesh leave no sample uncovered. */
static void
raster_rows(void *arg, size_t begin, size_t end, int part)
{
    (void)part;
    raster_ctx *c = arg;
    const cg_mesh *m = c->pm->mesh;
    const double *p = c->pm->p;
    hf_grid *g = c->g;
    for (size_t j = begin; j < end; j++)
        for (int i = 0; i < g->nx; i++)
            g->y[j * (size_t)g->nx + i] = -INFINITY;
    double zb = ((double)begin + 0.5) * g->hz, ze = ((double)end - 0.5) * g->hz;
    for (uint32_t t = 0; t + 2 < m->index_count; t += 3) {
        const double *v[3] = { p + 3 * (size_t)m->indices[t], p + 3 * (size_t)m->indices[t + 1],
                               p + 3 * (size_t)m->indices[t + 2] };
        double zmin = fmin(v[0][2], fmin(v[1][2], v[2][2])), zmax = fmax(v[0][2], fmax(v[1][2], v[2][2]));
        if (zmax < zb - g->hz || zmin > ze + g->hz)
            continue;
        double ex = v[1][0] - v[0][0], ez = v[1][2] - v[0][2], fx = v[2][0] - v[0][0], fz = v[2][2] - v[0][2];
        double area2 = ex * fz - ez * fx;
        double xmin = fmin(v[0][0], fmin(v[1][0], v[2][0])), xmax = fmax(v[0][0], fmax(v[1][0], v[2][0]));
        double size = fmax(xmax - xmin, zmax - zmin);
        if (!(fabs(area2) > 1e-18 * size * size))
            continue; /* seen edge-on from above: covers no sample */
        /* The plane y = y0 + a (x - x0) + b (z - z0) through the three vertices. */
        double ey = v[1][1] - v[0][1], fy = v[2][1] - v[0][1];
        double a = (ey * fz - ez * fy) / area2, b = (ex * fy - ey * fx) / area2;
        double tol = 1e-9 * size;
        long j0 = (long)ceil((zmin - tol) / g->hz - 0.5), j1 = (long)floor((zmax + tol) / g->hz - 0.5);
        if (j0 < (long)begin) j0 = (long)begin;
        if (j1 > (long)end - 1) j1 = (long)end - 1;
        for (long j = j0; j <= j1; j++) {
            double z = ((double)j + 0.5) * g->hz;
            /* The span of x where the line at z crosses the triangle: between the crossings of
             * its edges (an edge along the line gives its own ends). */
            double lo = INFINITY, hi = -INFINITY;
            for (int e = 0; e < 3; e++) {
                const double *u = v[e], *w = v[(e + 1) % 3];
                double z0 = fmin(u[2], w[2]), z1 = fmax(u[2], w[2]);
                if (z < z0 - tol || z > z1 + tol)
                    continue;
                if (z1 - z0 <= tol) {
                    lo = fmin(lo, fmin(u[0], w[0]));
                    hi = fmax(hi, fmax(u[0], w[0]));
                    continue;
                }
                double s = fmin(fmax((z - u[2]) / (w[2] - u[2]), 0.0), 1.0);
                double x = u[0] + s * (w[0] - u[0]);
                lo = fmin(lo, x);
                hi = fmax(hi, x);
            }
            if (!(lo <= hi))
                continue;
            long i0 = (long)ceil((lo - tol) / g->hx - 0.5), i1 = (long)floor((hi + tol) / g->hx - 0.5);
            if (i0 < 0) i0 = 0;
            if (i1 > g->nx - 1) i1 = g->nx - 1;
            float *row = &g->y[(size_t)j * g->nx];
            double y = v[0][1] + a * (((double)i0 + 0.5) * g->hx - v[0][0]) + b * (z - v[0][2]);
            double dy = a * g->hx;
            for (long i = i0; i <= i1; i++, y += dy)
                if ((float)y > row[i])
                    row[i] = (float)y;
        }
    }
}

static void
hf_grid_free(hf_grid *g)
{
    free(g->y);
    free(g->lo);
    free(g->hi);
    memset(g, 0, sizeof *g);
}

static bool
hf_grid_build(const placed_mesh *pm, int resolution, int threads, hf_grid *g, cg_error *err)
{
    memset(g, 0, sizeof *g);
    double lx = pm->size[0], lz = pm->size[2], longer = fmax(lx, lz);
    g->nx = (int)fmax(2, round(resolution * lx / longer));
    g->nz = (int)fmax(2, round(resolution * lz / longer));
    g->hx = lx / g->nx;
    g->hz = lz / g->nz;
    size_t total = 0;
    int nx = g->nx, nz = g->nz;
    g->level_nx[0] = nx, g->level_nz[0] = nz;
    g->levels = 1;
    while ((nx > 1 || nz > 1) && g->levels < 32) {
        nx = (nx + 1) / 2, nz = (nz + 1) / 2;
        g->offset[g->levels] = total;
        g->level_nx[g->levels] = nx, g->level_nz[g->levels] = nz;
        total += (size_t)nx * nz;
        g->levels++;
    }
    g->y = malloc((size_t)g->nx * g->nz * sizeof(float));
    g->lo = malloc(total * sizeof(float) + 1);
    g->hi = malloc(total * sizeof(float) + 1);
    if (!g->y || !g->lo || !g->hi) {
        hf_grid_free(g);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory for its %dx%d height-field samples",
                       pm->mesh->name, g->nx, g->nz);
    }
    raster_ctx c = { pm, g };
    parallel_ranges((size_t)g->nz, threads, raster_rows, &c);
    for (int k = 1; k < g->levels; k++) {
        int cnx = g->level_nx[k - 1], cnz = g->level_nz[k - 1];
        for (int j = 0; j < g->level_nz[k]; j++)
            for (int i = 0; i < g->level_nx[k]; i++) {
                float lo = INFINITY, hi = -INFINITY;
                for (int dj = 0; dj < 2; dj++)
                    for (int di = 0; di < 2; di++) {
                        int ci = 2 * i + di, cj = 2 * j + dj;
                        if (ci >= cnx || cj >= cnz)
                            continue;
                        size_t q = (size_t)cj * cnx + ci;
                        float clo, chi;
                        if (k == 1) {
                            clo = g->y[q] == -INFINITY ? INFINITY : g->y[q];
                            chi = g->y[q];
                        } else {
                            clo = g->lo[g->offset[k - 1] + q];
                            chi = g->hi[g->offset[k - 1] + q];
                        }
                        lo = clo < lo ? clo : lo;
                        hi = chi > hi ? chi : hi;
                    }
                g->lo[g->offset[k] + (size_t)j * g->level_nx[k] + i] = lo;
                g->hi[g->offset[k] + (size_t)j * g->level_nx[k] + i] = hi;
            }
    }
    return true;
}

/* ---------------------------------------------------------------- step 2: distances */

/* Squared distance from q to the box of node (k, i, j): its samples' xz centres and y range. */
static double
node_bound(const hf_grid *g, int k, int i, int j, const double q[3])
{
    float lo, hi;
    if (k == 0) {
        lo = hi = g->y[(size_t)j * g->nx + i];
        if (hi == -INFINITY)
            return INFINITY;
    } else {
        size_t o = g->offset[k] + (size_t)j * g->level_nx[k] + i;
        lo = g->lo[o], hi = g->hi[o];
        if (hi < lo)
            return INFINITY; /* no sample under it */
    }
    int span = 1 << k;
    int i0 = i * span, i1 = (i + 1) * span - 1, j0 = j * span, j1 = (j + 1) * span - 1;
    if (i1 > g->nx - 1) i1 = g->nx - 1;
    if (j1 > g->nz - 1) j1 = g->nz - 1;
    double x0 = (i0 + 0.5) * g->hx, x1 = (i1 + 0.5) * g->hx, z0 = (j0 + 0.5) * g->hz, z1 = (j1 + 0.5) * g->hz;
    double dx = q[0] < x0 ? x0 - q[0] : q[0] > x1 ? q[0] - x1 : 0;
    double dz = q[2] < z0 ? z0 - q[2] : q[2] > z1 ? q[2] - z1 : 0;
    double dy = q[1] < lo ? lo - q[1] : q[1] > hi ? q[1] - hi : 0;
    return dx * dx + dy * dy + dz * dz;
}

/* Distance from q to the nearest sample with a value: a depth-first descent of the pyramid,
 * nearer children first, that skips every node farther than the best so far. */
static double
nearest_sample(const hf_grid *g, const double q[3])
{
    typedef struct { int k, i, j; double bound; } entry;
    entry stack[32 * 4];
    int top = 0;
    double best = INFINITY;
    /* First the 4 x 4 samples around q: every other sample is at least one spacing away
     * horizontally, so a point of the surface (nearer than that, the usual case) needs no
     * descent at all. */
    int ci = (int)floor(q[0] / g->hx - 0.5), cj = (int)floor(q[2] / g->hz - 0.5);
    for (int j = cj - 1; j <= cj + 2; j++)
        for (int i = ci - 1; i <= ci + 2; i++)
            if (i >= 0 && j >= 0 && i < g->nx && j < g->nz)
                best = fmin(best, node_bound(g, 0, i, j, q));
    if (best <= fmin(g->hx, g->hz) * fmin(g->hx, g->hz))
        return sqrt(best);
    int k = g->levels - 1;
    for (int j = 0; j < g->level_nz[k]; j++)
        for (int i = 0; i < g->level_nx[k]; i++)
            stack[top++] = (entry){ k, i, j, node_bound(g, k, i, j, q) };
    while (top > 0) {
        entry e = stack[--top];
        if (!(e.bound < best))
            continue;
        if (e.k == 0) {
            best = e.bound; /* a sample's box is the sample itself */
            continue;
        }
        entry child[4];
        int n = 0;
        for (int dj = 0; dj < 2; dj++)
            for (int di = 0; di < 2; di++) {
                int ci = 2 * e.i + di, cj = 2 * e.j + dj;
                if (ci >= g->level_nx[e.k - 1] || cj >= g->level_nz[e.k - 1])
                    continue;
                double b = node_bound(g, e.k - 1, ci, cj, q);
                if (b < best)
                    child[n++] = (entry){ e.k - 1, ci, cj, b };
            }
        /* Pushed farthest first, so that the nearest is searched first. */
        for (int a = 1; a < n; a++)
            for (int b = a; b > 0 && child[b].bound > child[b - 1].bound; b--) {
                entry t = child[b];
                child[b] = child[b - 1];
                child[b - 1] = t;
            }
        for (int a = 0; a < n; a++)
            stack[top++] = child[a];
    }
    return sqrt(best);
}

typedef struct distance_ctx {
    const placed_mesh *pm;
    const hf_grid *g;
    const uint32_t *points;   /* vertex indices (vertices) or first indices of triangles (centroids) */
    bool centroids;
    double sum[CLASSIFY_MAX_THREADS], max[CLASSIFY_MAX_THREADS];
} distance_ctx;

static void
distance_range(void *arg, size_t begin, size_t end, int part)
{
    distance_ctx *c = arg;
    const cg_mesh *m = c->pm->mesh;
    double sum = 0, max = 0;
    for (size_t n = begin; n < end; n++) {
        double q[3];
        if (c->centroids) {
            uint32_t t = c->points[n];
            for (int k = 0; k < 3; k++)
                q[k] = (c->pm->p[3 * (size_t)m->indices[t] + k] + c->pm->p[3 * (size_t)m->indices[t + 1] + k] +
                        c->pm->p[3 * (size_t)m->indices[t + 2] + k]) / 3.0;
        } else {
            memcpy(q, c->pm->p + 3 * (size_t)c->points[n], sizeof q);
        }
        double d = nearest_sample(c->g, q);
        sum += d;
        max = fmax(max, d);
    }
    c->sum[part] = sum;
    c->max[part] = max;
}

/* The points X of eq. 5: the vertices some triangle uses, or the first index of every triangle
 * with an area (its centroid). */
static bool
collect_points(const cg_mesh *m, const double *p, bool centroids, uint32_t **out, size_t *count, cg_error *err)
{
    size_t cap = centroids ? m->index_count / 3 : m->vertex_count;
    uint32_t *pts = malloc(cap * sizeof(uint32_t) + 1);
    uint8_t *used = centroids ? NULL : calloc((size_t)m->vertex_count + 1, 1);
    if (!pts || (!centroids && !used)) {
        free(pts);
        free(used);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory classifying it", m->name);
    }
    size_t n = 0;
    if (centroids) {
        for (uint32_t t = 0; t + 2 < m->index_count; t += 3) {
            const double *a = p + 3 * (size_t)m->indices[t], *b = p + 3 * (size_t)m->indices[t + 1],
                         *c = p + 3 * (size_t)m->indices[t + 2];
            double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
            double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
                   cz = e1[0] * e2[1] - e1[1] * e2[0];
            if (cx * cx + cy * cy + cz * cz > 0)
                pts[n++] = t;
        }
    } else {
        for (uint32_t i = 0; i < m->index_count; i++)
            used[m->indices[i]] = 1;
        for (uint32_t v = 0; v < m->vertex_count; v++)
            if (used[v])
                pts[n++] = v;
    }
    free(used);
    *out = pts;
    *count = n;
    return true;
}

/* Eq. 5 for one instance: *d = mean distance / D, *dmax = largest distance / D; +inf when the
 * instance has no area seen from above (no height field can stand for it). */
static bool
eq5_instance(const cg_mesh *mesh, const float world[16], const cg_classify_options *o, double *d, double *dmax,
             cg_error *err)
{
    placed_mesh pm;
    if (!place_mesh(mesh, world, &pm, err))
        return false;
    double diagonal = sqrt(pm.size[0] * pm.size[0] + pm.size[1] * pm.size[1] + pm.size[2] * pm.size[2]);
    *d = *dmax = INFINITY;
    if (!(diagonal > 0) || !(pm.size[0] > 0) || !(pm.size[2] > 0)) {
        free(pm.p);
        return true;
    }
    hf_grid g;
    uint32_t *points = NULL;
    size_t count = 0;
    bool ok = hf_grid_build(&pm, o->resolution, o->threads, &g, err);
    ok = ok && collect_points(mesh, pm.p, o->points == CG_CLASSIFY_CENTROIDS, &points, &count, err);
    if (ok && count > 0 && g.hi[g.offset[g.levels - 1]] >= g.lo[g.offset[g.levels - 1]]) {
        distance_ctx c = { .pm = &pm, .g = &g, .points = points, .centroids = o->points == CG_CLASSIFY_CENTROIDS };
        int threads = o->threads;
        parallel_ranges(count, threads, distance_range, &c);
        double sum = 0, max = 0;
        for (int t = 0; t < CLASSIFY_MAX_THREADS; t++) {
            sum += c.sum[t];
            max = fmax(max, c.max[t]);
        }
        *d = sum / (double)count / diagonal;
        *dmax = max / diagonal;
    }
    free(points);
    hf_grid_free(&g);
    free(pm.p);
    return ok;
}

/* ---------------------------------------------------------------- the normal rule */

/* The rule the project used before eq. 5 (docs/scenes.md compares them): every triangle with an
 * area faces up in world space, its unit geometric normal (counter-clockwise winding, flipped
 * by a mirroring transform, glTF 3.7.4) having y > CG_HEIGHTFIELD_MIN_NY. It rejects a terrain
 * for one vertical triangle and a sheet facing down, and accepts stacked up-facing layers. */
static bool
normals_up(const cg_mesh *mesh, const float world[16])
{
    double facing = upper_3x3_determinant(world) < 0 ? -1.0 : 1.0;
    for (uint32_t t = 0; t + 2 < mesh->index_count; t += 3) {
        double p[3][3];
        for (int v = 0; v < 3; v++)
            transform_point(world, mesh->positions + 3 * (size_t)mesh->indices[t + v], p[v]);
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = p[1][k] - p[0][k];
            e2[k] = p[2][k] - p[0][k];
        }
        double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0] };
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > 0))
            continue; /* no area: covers nothing and has no orientation */
        if (!(facing * n[1] / len > CG_HEIGHTFIELD_MIN_NY))
            return false;
    }
    return true;
}

/* ---------------------------------------------------------------- per mesh, per scene */

/* Whether an instance's transform only turns the mesh about the vertical, scales it uniformly
 * (mirrored or not) and moves it: its local y stays the world's up, x and z stay horizontal. Eq. 5
 * is then the same for every such instance when measured in the mesh's own frame (its bounding
 * box turns with it; the distances and the diagonal scale alike), so it is measured once. */
static bool
turns_about_vertical(const float m[16])
{
    double s = sqrt((double)m[4] * m[4] + (double)m[5] * m[5] + (double)m[6] * m[6]);
    double tol = 1e-6 * s;
    return s > 0 && fabs(m[4]) <= tol && fabs(m[6]) <= tol && m[5] > 0 && fabs(m[1]) <= tol && fabs(m[9]) <= tol &&
           fabs(sqrt((double)m[0] * m[0] + (double)m[2] * m[2]) - s) <= tol &&
           fabs(sqrt((double)m[8] * m[8] + (double)m[10] * m[10]) - s) <= tol &&
           fabs((double)m[0] * m[8] + (double)m[2] * m[10]) <= tol * s;
}

bool
cg_mesh_classify(const cg_scene *scene, int mesh_index, const cg_classify_options *options, cg_mesh_class *out,
                 cg_error *err)
{
    cg_classify_options o;
    cg_classify_defaults(&o, options);
    const cg_mesh *mesh = &scene->meshes[mesh_index];
    out->distance = out->max_distance = NAN;
    out->instances = 0;
    out->normals_up = true;
    bool all_below = true, own_frame_done = false;
    double own_d = 0, own_dmax = 0;
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_instance *inst = &scene->instances[i];
        if (inst->mesh != mesh_index)
            continue;
        out->instances++;
        /* A moving instance (an animated node) would have to be a height field at every time:
         * not proven, so its mesh is complex by either rule; d is measured as posed. */
        if (inst->moving)
            all_below = false;
        out->normals_up = out->normals_up && !inst->moving && normals_up(mesh, inst->world);
        if (o.rule != CG_CLASSIFY_EQ5)
            continue;
        double d, dmax;
        if (turns_about_vertical(inst->world)) {
            if (!own_frame_done) {
                static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
                if (!eq5_instance(mesh, identity, &o, &own_d, &own_dmax, err))
                    return false;
                own_frame_done = true;
            }
            d = own_d, dmax = own_dmax;
        } else if (!eq5_instance(mesh, inst->world, &o, &d, &dmax, err)) {
            return false;
        }
        /* The worst instance decides: the kind is the mesh's, shared by all of them. */
        if (isnan(out->distance) || d > out->distance)
            out->distance = d;
        if (isnan(out->max_distance) || dmax > out->max_distance)
            out->max_distance = dmax;
        all_below = all_below && d < o.threshold;
    }
    if (out->instances == 0)
        out->kind = CG_MESH_COMPLEX; /* placed nowhere: nothing to classify */
    else if (o.rule == CG_CLASSIFY_EQ5)
        out->kind = all_below ? CG_MESH_HEIGHTFIELD : CG_MESH_COMPLEX;
    else
        out->kind = out->normals_up ? CG_MESH_HEIGHTFIELD : CG_MESH_COMPLEX;
    return true;
}

bool
cg_scene_classify(cg_scene *scene, cg_progress *progress, cg_error *err)
{
    /* Progress by triangles: a mesh's classification costs about its triangles. */
    double triangles = 0, done = 0;
    for (int m = 0; m < scene->mesh_count; m++)
        if (m >= scene->mesh_class_count || scene->mesh_class[m].source == CG_KIND_CLASSIFIED)
            triangles += scene->meshes[m].index_count / 3.0;
    for (int m = 0; m < scene->mesh_count; m++) {
        if (m >= scene->mesh_class_count && !cg_scene_set_kind_source(scene, m, CG_KIND_CLASSIFIED, err))
            return false;
        cg_mesh_class *c = &scene->mesh_class[m];
        cg_kind_source source = c->source;
        if (source != CG_KIND_CLASSIFIED) {
            *c = (cg_mesh_class){ .kind = scene->meshes[m].kind, .source = source, .distance = NAN,
                                  .max_distance = NAN };
            continue;
        }
        if (!cg_mesh_classify(scene, m, &scene->classify, c, err))
            return false;
        c->source = source;
        scene->meshes[m].kind = c->kind;
        done += scene->meshes[m].index_count / 3.0;
        if (progress && triangles > 0)
            cg_progress_update(progress, CG_LOAD_BUILT + (CG_LOAD_TOTAL - CG_LOAD_BUILT) * done / triangles);
    }
    return true;
}
