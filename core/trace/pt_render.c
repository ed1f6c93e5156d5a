/* The CPU path tracer on Embree 3: see pt_render.h for the physics and the conventions. */
#include "cg/pt_render.h"

#include "cg/bsdf.h"
#include "cg/progress.h"

#include "pt_sky.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>


/* Embree's C API names its records as plain structs. */
typedef struct RTCRay RTCRay;
typedef struct RTCRayHit RTCRayHit;
typedef struct RTCIntersectContext RTCIntersectContext;

#define PT_PI 3.14159265358979323846f
#define PT_TILE 16
#define PT_MAX_BOUNCES 64
#define PT_MAX_SPP (1 << 20)
#define PT_MAX_THREADS 256

typedef struct v3 {
    float x, y, z;
} v3;

static inline v3
mk(float x, float y, float z)
{
    return (v3){ x, y, z };
}

static inline v3
add(v3 a, v3 b)
{
    return mk(a.x + b.x, a.y + b.y, a.z + b.z);
}

static inline v3
sub(v3 a, v3 b)
{
    return mk(a.x - b.x, a.y - b.y, a.z - b.z);
}

static inline v3
mul(v3 a, v3 b)
{
    return mk(a.x * b.x, a.y * b.y, a.z * b.z);
}

static inline v3
scale(v3 a, float s)
{
    return mk(a.x * s, a.y * s, a.z * s);
}

static inline float
dot(v3 a, v3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

static inline v3
neg(v3 a)
{
    return mk(-a.x, -a.y, -a.z);
}

static inline v3
normalize(v3 a)
{
    float len = sqrtf(dot(a, a));
    return len > 0.0f ? scale(a, 1.0f / len) : a;
}

/* ---------------------------------------------------------------- scene */

/* A texture decoded once to linear float RGBA, rows bottom to top like the GL upload. */
typedef struct pt_texture {
    int width, height;
    float *rgba;
} pt_texture;

/* What shading needs of one Embree geometry (one scene instance). */
typedef struct pt_geometry {
    const cg_mesh *mesh;
    const cg_material *material;
    const float *vertices;    /* world space, x y z per vertex: Embree's own vertex buffer */
    float normal_matrix[9];   /* cofactor of the upper 3x3 of the instance matrix, column-major */
    int64_t emitter_base;     /* emitter index of triangle 0 (triangle k is base + k); -1: emits nothing */
    bool mirrored;            /* the instance matrix flips orientation: front faces wind clockwise */
    const float *world;       /* the instance's local-to-world matrix (tangents) */
} pt_geometry;

/* Every triangle of an emissive material, for next-event estimation: one is chosen with
 * probability proportional to its power (area x mean emitted radiance), then a point
 * uniformly on it. */
typedef struct pt_emitters {
    int64_t count;
    uint32_t *geometry, *triangle; /* by emitter index */
    double *cdf;              /* count + 1 running sums of the power, cdf[0] = 0 */
} pt_emitters;

struct pt_scene {
    const cg_scene *scene;
    RTCDevice device;
    RTCScene rtc;
    pt_geometry *geometries;  /* by Embree geomID */
    unsigned geometry_count;
    pt_texture *textures;     /* by cg_scene texture index */
    size_t triangles;
    pt_emitters emitters;
    pt_sky sky;
};

pt_settings
pt_settings_default(void)
{
    return (pt_settings){ .spp = 64, .bounces = 1, .seed = 1, .threads = 0, .jitter = false,
                          .progress = false, .glossy_bounces = 1, .transmission_bounces = 4,
                          .caustics = false };
}

static void
cofactor3(const float m[16], float out[9])
{
    /* Column-major 4x4: element (row r, column c) is m[c*4 + r]. */
#define M(r, c) m[(c) * 4 + (r)]
    float a = M(0, 0), b = M(0, 1), c = M(0, 2);
    float d = M(1, 0), e = M(1, 1), f = M(1, 2);
    float g = M(2, 0), h = M(2, 1), i = M(2, 2);
#undef M
    /* The cofactor matrix is det(M) times the inverse transpose: it maps normals correctly up
     * to scale and sign, and shading re-normalises and orients them against the geometric normal. */
    float cof[3][3] = {
        { e * i - f * h, -(d * i - f * g), d * h - e * g },
        { -(b * i - c * h), a * i - c * g, -(a * h - b * g) },
        { b * f - c * e, -(a * f - c * d), a * e - b * d },
    };
    for (int r = 0; r < 3; r++)
        for (int col = 0; col < 3; col++)
            out[col * 3 + r] = cof[r][col];
}

/* The sRGB EOTF (IEC 61966-2-1), as GL applies it to SRGB8_ALPHA8 texels. */
static float
srgb_decode(float v)
{
    return v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f);
}

static bool
textures_create(pt_scene *pts, cg_error *err)
{
    const cg_scene *scene = pts->scene;
    if (scene->texture_count == 0)
        return true;
    pts->textures = calloc((size_t)scene->texture_count, sizeof *pts->textures);
    if (!pts->textures)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "path_trace: %d texture records", scene->texture_count);
    for (int t = 0; t < scene->texture_count; t++) {
        const cg_texture *src = &scene->textures[t];
        pt_texture *dst = &pts->textures[t];
        if (src->width <= 0 || src->height <= 0 || !src->rgba)
            return cg_fail(err, CG_ERR_IMAGE_FORMAT, "path_trace: texture %d '%s' is empty (%dx%d)",
                           t, src->name, src->width, src->height);
        size_t n = (size_t)src->width * (size_t)src->height * 4;
        dst->rgba = malloc(n * sizeof(float));
        if (!dst->rgba)
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "path_trace: texture '%s' %dx%d", src->name,
                           src->width, src->height);
        dst->width = src->width;
        dst->height = src->height;
        /* GL decodes SRGB8_ALPHA8 texels before filtering; alpha is always linear. */
        for (size_t k = 0; k < n; k++) {
            float v = (float)src->rgba[k] / 255.0f;
            dst->rgba[k] = (src->srgb && (k & 3) != 3) ? srgb_decode(v) : v;
        }
    }
    return true;
}

static const cg_material *
material_of(const cg_scene *scene, const cg_mesh *mesh)
{
    int mi = mesh->material;
    return (mi >= 0 && mi < scene->material_count) ? &scene->materials[mi] : &scene->materials[0];
}

static inline v3
emissive_factor(const cg_material *mat)
{
    return mk(mat->emissive[0] * mat->emissive_strength, mat->emissive[1] * mat->emissive_strength,
              mat->emissive[2] * mat->emissive_strength);
}

/* A triangle's world-space vertices, unit normal (of its winding) and area. */
static void
triangle_frame(const pt_geometry *g, uint32_t prim, v3 p[3], v3 *normal, float *area)
{
    const uint32_t *tri = &g->mesh->indices[3 * (size_t)prim];
    for (int k = 0; k < 3; k++) {
        const float *q = &g->vertices[3 * (size_t)tri[k]];
        p[k] = mk(q[0], q[1], q[2]);
    }
    v3 e1 = sub(p[1], p[0]), e2 = sub(p[2], p[0]);
    v3 c = mk(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
    float len = sqrtf(dot(c, c));
    *area = 0.5f * len;
    *normal = len > 0.0f ? scale(c, 1.0f / len) : mk(0, 0, 0);
}

/* The mean of a texture's linear RGB: what an emissive texture does to a triangle's power. */
static float
texture_mean(const pt_texture *tex)
{
    double sum = 0.0;
    size_t n = (size_t)tex->width * (size_t)tex->height;
    for (size_t k = 0; k < n; k++)
        sum += (double)tex->rgba[4 * k] + tex->rgba[4 * k + 1] + tex->rgba[4 * k + 2];
    return (float)(sum / (3.0 * (double)n));
}

/* The emitter table: every triangle of every geometry whose material emits, with its power
 * area x mean emitted radiance (the factor's channel mean times the emissive texture's mean). */
static bool
emitters_create(pt_scene *pts, cg_error *err)
{
    const cg_scene *scene = pts->scene;
    pt_emitters *e = &pts->emitters;
    int64_t count = 0;
    for (unsigned g = 0; g < pts->geometry_count; g++) {
        pt_geometry *geo = &pts->geometries[g];
        v3 f = emissive_factor(geo->material);
        geo->emitter_base = -1;
        if (f.x > 0.0f || f.y > 0.0f || f.z > 0.0f) {
            geo->emitter_base = count;
            count += geo->mesh->index_count / 3;
        }
    }
    if (count == 0)
        return true;
    e->geometry = malloc(sizeof *e->geometry * (size_t)count);
    e->triangle = malloc(sizeof *e->triangle * (size_t)count);
    e->cdf = malloc(sizeof *e->cdf * (size_t)(count + 1));
    float *means = calloc((size_t)(scene->texture_count > 0 ? scene->texture_count : 1), sizeof *means);
    if (!e->geometry || !e->triangle || !e->cdf || !means) {
        free(means);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "path_trace: %lld emissive triangles", (long long)count);
    }
    for (int t = 0; t < scene->texture_count; t++)
        means[t] = -1.0f; /* computed when first needed */
    e->count = count;
    e->cdf[0] = 0.0;
    for (unsigned g = 0; g < pts->geometry_count; g++) {
        const pt_geometry *geo = &pts->geometries[g];
        if (geo->emitter_base < 0)
            continue;
        v3 f = emissive_factor(geo->material);
        double power = ((double)f.x + f.y + f.z) / 3.0;
        int t = geo->material->emissive_texture;
        if (t >= 0 && t < scene->texture_count) {
            if (means[t] < 0.0f)
                means[t] = texture_mean(&pts->textures[t]);
            power *= means[t];
        }
        uint32_t tris = geo->mesh->index_count / 3;
        for (uint32_t k = 0; k < tris; k++) {
            int64_t i = geo->emitter_base + k;
            v3 p[3], n;
            float area;
            triangle_frame(geo, k, p, &n, &area);
            e->geometry[i] = g;
            e->triangle[i] = k;
            e->cdf[i + 1] = e->cdf[i] + power * area;
        }
    }
    free(means);
    if (!(e->cdf[count] > 0.0)) {
        /* Emissive materials on triangles of zero area only: nothing to sample. */
        free(e->geometry);
        free(e->triangle);
        free(e->cdf);
        memset(e, 0, sizeof *e);
        for (unsigned g = 0; g < pts->geometry_count; g++)
            pts->geometries[g].emitter_base = -1;
    }
    return true;
}

static void ray_filter(const struct RTCFilterFunctionNArguments *args);

/* The determinant of the upper 3x3 of a column-major 4x4. */
static float
det3(const float m[16])
{
    return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
           m[8] * (m[1] * m[6] - m[5] * m[2]);
}

static void
rtc_error_to_log(void *user, enum RTCError code, const char *str)
{
    (void)user;
    fprintf(stderr, "path_trace: embree error %d: %s\n", (int)code, str ? str : "");
}

bool
pt_scene_create(const cg_scene *scene, pt_scene **out, cg_error *err)
{
    *out = NULL;
    pt_scene *pts = calloc(1, sizeof *pts);
    if (!pts)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "path_trace: scene record");
    pts->scene = scene;
    pts->device = rtcNewDevice(NULL);
    if (!pts->device) {
        free(pts);
        return cg_fail(err, CG_ERR_PASS, "path_trace: rtcNewDevice failed (error %d)",
                       (int)rtcGetDeviceError(NULL));
    }
    rtcSetDeviceErrorFunction(pts->device, rtc_error_to_log, NULL);
    if (!textures_create(pts, err))
        goto fail;
    pts->rtc = rtcNewScene(pts->device);
    /* Watertight traversal: no light leaks through the shared edges of a closed box. */
    rtcSetSceneFlags(pts->rtc, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(pts->rtc, RTC_BUILD_QUALITY_MEDIUM);
    pts->geometries = calloc((size_t)(scene->instance_count > 0 ? scene->instance_count : 1),
                             sizeof *pts->geometries);
    if (!pts->geometries) {
        cg_fail(err, CG_ERR_OUT_OF_MEMORY, "path_trace: %d geometries", scene->instance_count);
        goto fail;
    }
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_instance *inst = &scene->instances[i];
        if (inst->mesh < 0 || inst->mesh >= scene->mesh_count) {
            cg_fail(err, CG_ERR_USAGE, "path_trace: instance %d names mesh %d of %d", i, inst->mesh,
                    scene->mesh_count);
            goto fail;
        }
        const cg_mesh *mesh = &scene->meshes[inst->mesh];
        uint32_t tris = mesh->index_count / 3;
        if (tris == 0 || mesh->vertex_count == 0)
            continue;
        RTCGeometry geom = rtcNewGeometry(pts->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        float *vtx = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                             3 * sizeof(float), mesh->vertex_count);
        uint32_t *idx = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                3 * sizeof(uint32_t), tris);
        if (!vtx || !idx) {
            rtcReleaseGeometry(geom);
            cg_fail(err, CG_ERR_OUT_OF_MEMORY, "path_trace: buffers of mesh '%s' (%u vertices)",
                    mesh->name, mesh->vertex_count);
            goto fail;
        }
        const float *w = inst->world;
        for (uint32_t v = 0; v < mesh->vertex_count; v++) {
            const float *p = &mesh->positions[3 * v];
            for (int r = 0; r < 3; r++)
                vtx[3 * v + r] = w[r] * p[0] + w[4 + r] * p[1] + w[8 + r] * p[2] + w[12 + r];
        }
        for (uint32_t k = 0; k < tris * 3; k++) {
            if (mesh->indices[k] >= mesh->vertex_count) {
                rtcReleaseGeometry(geom);
                cg_fail(err, CG_ERR_USAGE, "path_trace: mesh '%s' index %u out of range (%u vertices)",
                        mesh->name, mesh->indices[k], mesh->vertex_count);
                goto fail;
            }
            idx[k] = mesh->indices[k];
        }
        const cg_material *mat = material_of(scene, mesh);
        /* Only surfaces that can be missed pay for a filter call on every hit. */
        if (mat->alpha_mode != CG_ALPHA_OPAQUE || !mat->double_sided) {
            rtcSetGeometryIntersectFilterFunction(geom, ray_filter);
            rtcSetGeometryOccludedFilterFunction(geom, ray_filter);
        }
        rtcCommitGeometry(geom);
        unsigned id = pts->geometry_count++;
        rtcAttachGeometryByID(pts->rtc, geom, id);
        rtcReleaseGeometry(geom);
        pts->geometries[id].mesh = mesh;
        pts->geometries[id].material = mat;
        pts->geometries[id].mirrored = det3(inst->world) < 0.0f;
        pts->geometries[id].world = inst->world;
        pts->geometries[id].vertices = vtx;
        cofactor3(inst->world, pts->geometries[id].normal_matrix);
        pts->triangles += tris;
    }
    rtcCommitScene(pts->rtc);
    enum RTCError code = rtcGetDeviceError(pts->device);
    if (code != RTC_ERROR_NONE) {
        cg_fail(err, CG_ERR_PASS, "path_trace: building the BVH failed (embree error %d)", (int)code);
        goto fail;
    }
    if (!emitters_create(pts, err) || !pt_sky_create(scene, &pts->sky, err))
        goto fail;
    *out = pts;
    return true;
fail:
    pt_scene_destroy(pts);
    return false;
}

void
pt_scene_destroy(pt_scene *pts)
{
    if (!pts)
        return;
    if (pts->rtc)
        rtcReleaseScene(pts->rtc);
    if (pts->device)
        rtcReleaseDevice(pts->device);
    if (pts->textures)
        for (int t = 0; t < pts->scene->texture_count; t++)
            free(pts->textures[t].rgba);
    free(pts->textures);
    free(pts->geometries);
    free(pts->emitters.geometry);
    free(pts->emitters.triangle);
    free(pts->emitters.cdf);
    pt_sky_destroy(&pts->sky);
    free(pts);
}

size_t
pt_scene_triangle_count(const pt_scene *pts)
{
    return pts->triangles;
}

/* ---------------------------------------------------------------- random numbers */

/* splitmix64 (Steele, Lea, Flood 2014) is a counter hashed by a bijective mixer: the n-th
 * draw depends only on the key and n, which is what makes pixels independent of scheduling. */
static inline uint64_t
mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

typedef struct pt_rng {
    uint64_t key;
    uint64_t counter;
} pt_rng;

static inline pt_rng
rng_for_sample(uint32_t seed, uint64_t pixel, uint32_t sample)
{
    uint64_t key = mix64(((uint64_t)seed << 32) ^ 0x5851F42D4C957F2Dull);
    key = mix64(key ^ pixel * 0x9E3779B97F4A7C15ull);
    key = mix64(key ^ ((uint64_t)sample * 0xD1B54A32D192ED03ull + 1));
    return (pt_rng){ key, 0 };
}

/* Uniform in [0,1): 24 random bits, exactly representable in a float. */
static inline float
rng_next(pt_rng *rng)
{
    uint64_t bits = mix64(rng->key + 0x9E3779B97F4A7C15ull * ++rng->counter);
    return (float)(bits >> 40) * (1.0f / 16777216.0f);
}

/* ---------------------------------------------------------------- shading */

static void
texture_sample(const pt_texture *tex, float s, float t, float out[4])
{
    /* GL_LINEAR with GL_REPEAT: texel centres at (i + 0.5) / size. */
    float x = s * (float)tex->width - 0.5f;
    float y = t * (float)tex->height - 0.5f;
    float fx = floorf(x), fy = floorf(y);
    float ax = x - fx, ay = y - fy;
    long ix = (long)fx, iy = (long)fy;
    long w = tex->width, h = tex->height;
    long x0 = ((ix % w) + w) % w, x1 = (x0 + 1) % w;
    long y0 = ((iy % h) + h) % h, y1 = (y0 + 1) % h;
    const float *p00 = &tex->rgba[4 * (y0 * w + x0)];
    const float *p10 = &tex->rgba[4 * (y0 * w + x1)];
    const float *p01 = &tex->rgba[4 * (y1 * w + x0)];
    const float *p11 = &tex->rgba[4 * (y1 * w + x1)];
    for (int c = 0; c < 4; c++) {
        float a = p00[c] + (p10[c] - p00[c]) * ax;
        float b = p01[c] + (p11[c] - p01[c]) * ax;
        out[c] = a + (b - a) * ay;
    }
}

typedef struct pt_hit {
    unsigned geometry, triangle; /* Embree geomID and primID */
    v3 position;
    float magnitude;      /* largest |coordinate| of the hit triangle's vertices */
    v3 origin;            /* where rays leave the surface (spawn_point) */
    float offset;         /* and their tnear */
    v3 geometric_normal;  /* unit, facing the incoming ray */
    v3 shading_normal;    /* unit, same hemisphere as geometric_normal */
    v3 albedo;            /* base colour (factor x texture): the Lambertian albedo */
    v3 emission;
    cg_bsdf bsdf;
    bool lambertian;      /* no glossy or transmission lobe: shaded as before the BSDF (bit for bit) */
    bool back;            /* the ray came from the back of the triangle (its winding's normal) */
    float eta;            /* for a solid's transmission: ior entering, 1/ior leaving (cg/bsdf.h) */
} pt_hit;

/* Relative size of the offset that lifts a spawned ray's origin off its surface: 2^-19, 16
 * times float's unit roundoff 2^-23 (FLT_EPSILON). */
#define PT_OFFSET_RELATIVE 1.9073486328125e-6f

/* Where rays leave the hit's surface on the side of n (the unit geometric normal): the point
 * pushed along n by d = 2^-19 times the largest coordinate of the triangle's vertices, and
 * the rays start at tnear = d from there. No absolute term, so the offset scales with the
 * scene (the same image at 1e-6 m and at 1e6 m). The bound covers the error of the
 * barycentric hit point (a few ulps of the vertices' magnitude) and that of Embree's test of
 * the same triangle from the new origin (its edge and plane functions are formed from
 * vertex - origin differences, so their errors are ulps of that same magnitude): the ray
 * cannot find its own triangle again, the self-intersection that Wächter and Binder, "A Fast
 * and Robust Method for Avoiding Self-Intersection" (Ray Tracing Gems, ch. 6), avoid with an
 * integer-ulp offset. Their method keeps an absolute offset of 2^-16 near the origin, which
 * would still be larger than a 1e-6 m scene; a bound proportional to the vertices' magnitude
 * has no such floor. tnear is for the neighbour across a concave crease: a hit on the crease
 * itself rounds to either side of the other surface's plane, and a shadow ray from the wrong
 * side would cross that plane within a few ulps of its origin and leave a black line along
 * the crease. */
static inline void
spawn_point(pt_hit *hit)
{
    const v3 p = hit->position;
    float m = fmaxf(hit->magnitude, fmaxf(fabsf(p.x), fmaxf(fabsf(p.y), fabsf(p.z))));
    hit->offset = PT_OFFSET_RELATIVE * m;
    hit->origin = add(p, scale(hit->geometric_normal, hit->offset));
}

static inline void
triangle_texcoords(const cg_mesh *mesh, const uint32_t *tri, float u, float v, float st[2])
{
    st[0] = st[1] = 0.0f;
    if (!mesh->texcoords)
        return;
    float w = 1.0f - u - v;
    const float *t0 = &mesh->texcoords[2 * tri[0]], *t1 = &mesh->texcoords[2 * tri[1]],
                *t2 = &mesh->texcoords[2 * tri[2]];
    st[0] = w * t0[0] + u * t1[0] + v * t2[0];
    st[1] = w * t0[1] + u * t1[1] + v * t2[1];
}

/* KHR_texture_transform's affine map of TEXCOORD_0 (cg_uv_transform). An all-zero matrix (a
 * material record filled by hand, never a loader's) is the identity. */
static inline void
uv_of(const cg_material *mat, cg_material_texture which, const float st[2], float out[2])
{
    const float *m = mat->uv[which].m;
    if (m[0] == 0.0f && m[1] == 0.0f && m[2] == 0.0f && m[3] == 0.0f) {
        out[0] = st[0], out[1] = st[1];
        return;
    }
    out[0] = m[0] * st[0] + m[2] * st[1] + m[4];
    out[1] = m[1] * st[0] + m[3] * st[1] + m[5];
}

/* Samples texture `index` of the scene at TEXCOORD_0 st through the material's transform for
 * `which`; false (out untouched) where the material has no such texture. */
static bool
material_texel(const pt_scene *pts, const cg_material *mat, int index, cg_material_texture which,
               const float st[2], float out[4])
{
    if (index < 0 || index >= pts->scene->texture_count)
        return false;
    float uv[2];
    uv_of(mat, which, st, uv);
    texture_sample(&pts->textures[index], uv[0], uv[1], out);
    return true;
}

/* Emitted radiance = emissive x emissive texture x emissive_strength (the same from both sides). */
static v3
emission_at(const pt_scene *pts, const cg_material *mat, const float st[2])
{
    v3 emission = emissive_factor(mat);
    if (mat->emissive_texture >= 0 && mat->emissive_texture < pts->scene->texture_count &&
        (emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f)) {
        float texel[4];
        material_texel(pts, mat, mat->emissive_texture, CG_TEX_EMISSIVE, st, texel);
        emission = mul(emission, mk(texel[0], texel[1], texel[2]));
    }
    return emission;
}

static inline float
max_abs3(const float *p)
{
    return fmaxf(fabsf(p[0]), fmaxf(fabsf(p[1]), fabsf(p[2])));
}

static void
shade_hit(const pt_scene *pts, const RTCRayHit *rh, pt_hit *hit)
{
    const pt_geometry *g = &pts->geometries[rh->hit.geomID];
    const cg_mesh *mesh = g->mesh;
    const uint32_t *tri = &mesh->indices[3 * rh->hit.primID];
    hit->geometry = rh->hit.geomID;
    hit->triangle = rh->hit.primID;
    float u = rh->hit.u, v = rh->hit.v, w = 1.0f - u - v;
    v3 dir = mk(rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z);

    /* The hit point from the barycentrics on the triangle's own world-space vertices, not
     * org + t dir: its error is then a few ulps of the vertices' coordinates whatever the
     * ray's length, which is what spawn_point's bound assumes. */
    const float *p0 = &g->vertices[3 * tri[0]], *p1 = &g->vertices[3 * tri[1]],
                *p2 = &g->vertices[3 * tri[2]];
    hit->position = mk(w * p0[0] + u * p1[0] + v * p2[0], w * p0[1] + u * p1[1] + v * p2[1],
                       w * p0[2] + u * p1[2] + v * p2[2]);
    hit->magnitude = fmaxf(max_abs3(p0), fmaxf(max_abs3(p1), max_abs3(p2)));
    v3 ng = normalize(mk(rh->hit.Ng_x, rh->hit.Ng_y, rh->hit.Ng_z));
    if (dot(ng, dir) > 0.0f)
        ng = neg(ng);
    hit->geometric_normal = ng;
    {
        /* The side by the winding (glTF: counter-clockwise is the front), not by Embree's Ng. */
        v3 e1 = mk(p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]);
        v3 e2 = mk(p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]);
        v3 front = mk(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
        hit->back = (dot(front, dir) > 0.0f) != g->mirrored;
    }

    const float *n0 = &mesh->normals[3 * tri[0]], *n1 = &mesh->normals[3 * tri[1]],
                *n2 = &mesh->normals[3 * tri[2]];
    float nl[3];
    for (int c = 0; c < 3; c++)
        nl[c] = w * n0[c] + u * n1[c] + v * n2[c];
    const float *m = g->normal_matrix;
    v3 ns = normalize(mk(m[0] * nl[0] + m[3] * nl[1] + m[6] * nl[2],
                         m[1] * nl[0] + m[4] * nl[1] + m[7] * nl[2],
                         m[2] * nl[0] + m[5] * nl[1] + m[8] * nl[2]));

    const cg_material *mat = g->material;
    float st[2];
    triangle_texcoords(mesh, tri, u, v, st);
    float texel[4];
    if (mesh->tangents && mesh->texcoords &&
        material_texel(pts, mat, mat->normal_texture, CG_TEX_NORMAL, st, texel) && dot(ns, ns) > 0.5f) {
        /* glTF 2.0 normalTexture: n = normalize(T x + B y + N z) with (x, y, z) = (2 texel - 1) x
         * (scale, scale, 1) and B = cross(N, T) x the tangent's w (glTF 3.7.2.1, TANGENT). */
        const float *t0 = &mesh->tangents[4 * tri[0]], *t1 = &mesh->tangents[4 * tri[1]],
                    *t2 = &mesh->tangents[4 * tri[2]];
        v3 tl = mk(w * t0[0] + u * t1[0] + v * t2[0], w * t0[1] + u * t1[1] + v * t2[1],
                   w * t0[2] + u * t1[2] + v * t2[2]);
        const float *x = g->world;
        v3 tw = mk(x[0] * tl.x + x[4] * tl.y + x[8] * tl.z, x[1] * tl.x + x[5] * tl.y + x[9] * tl.z,
                   x[2] * tl.x + x[6] * tl.y + x[10] * tl.z);
        tw = normalize(sub(tw, scale(ns, dot(tw, ns)))); /* Gram-Schmidt against the interpolated N */
        float sign = (t0[3] < 0.0f ? -1.0f : 1.0f) * (g->mirrored ? -1.0f : 1.0f);
        v3 bw = scale(mk(ns.y * tw.z - ns.z * tw.y, ns.z * tw.x - ns.x * tw.z, ns.x * tw.y - ns.y * tw.x), sign);
        float tx = (2.0f * texel[0] - 1.0f) * mat->normal_scale, ty = (2.0f * texel[1] - 1.0f) * mat->normal_scale;
        float tz = 2.0f * texel[2] - 1.0f;
        v3 nm = normalize(add(add(scale(tw, tx), scale(bw, ty)), scale(ns, tz)));
        if (dot(nm, nm) > 0.5f && dot(tw, tw) > 0.5f)
            ns = nm;
    }
    if (dot(ns, ng) < 0.0f)
        ns = neg(ns);
    if (!(dot(ns, ns) > 0.5f)) /* zero or NaN interpolated normal */
        ns = ng;
    hit->shading_normal = ns;

    float base[4] = { mat->base_color[0], mat->base_color[1], mat->base_color[2], mat->base_color[3] };
    v3 albedo = mk(base[0], base[1], base[2]);
    if (material_texel(pts, mat, mat->base_color_texture, CG_TEX_BASE_COLOR, st, texel)) {
        albedo = mul(albedo, mk(texel[0], texel[1], texel[2]));
        base[3] *= texel[3];
    }
    base[0] = albedo.x, base[1] = albedo.y, base[2] = albedo.z;
    hit->albedo = albedo;
    float metallic = mat->metallic, roughness = mat->roughness, transmission = mat->transmission;
    if (material_texel(pts, mat, mat->metallic_roughness_texture, CG_TEX_METALLIC_ROUGHNESS, st, texel)) {
        roughness *= texel[1];
        metallic *= texel[2];
    }
    if (transmission > 0.0f &&
        material_texel(pts, mat, mat->transmission_texture, CG_TEX_TRANSMISSION, st, texel))
        transmission *= texel[0];
    cg_bsdf_from_material(mat, base, metallic, roughness, transmission, &hit->bsdf);
    const cg_bsdf *b = &hit->bsdf;
    hit->lambertian = b->f0[0] == 0.0f && b->f0[1] == 0.0f && b->f0[2] == 0.0f && b->f90 == 0.0f &&
                      b->transmission[0] == 0.0f && b->transmission[1] == 0.0f && b->transmission[2] == 0.0f;
    hit->eta = hit->back && b->thickness > 0.0f ? 1.0f / b->ior : b->ior;
    hit->emission = emission_at(pts, mat, st);
    spawn_point(hit);
}

/* What the filter functions need to know of the ray being traced: Embree passes the context it
 * was given, and this record starts with it (the extended-context idiom of Embree 3's manual,
 * rtcInitIntersectContext). */
typedef struct pt_ray_context {
    RTCIntersectContext ictx;
    const pt_scene *pts;
    uint64_t key;         /* the ray's random key: BLEND's pass-through draws hash it */
    bool camera;          /* a camera ray: back faces of single-sided materials are not there */
} pt_ray_context;

typedef struct pt_worker_ctx {
    const pt_scene *pts;
    pt_ray_context rc;
    uint64_t rays;
} pt_worker_ctx;

/* Whether the surface is there for the ray at (u, v) of triangle prim of geometry g, t along
 * it: MASK's holes and BLEND's pass-through for every ray, back faces of single-sided materials
 * for camera rays only. BLEND passes with probability 1 - alpha by a hash of the ray's key, the
 * geometry and t rounded to 12 bits of mantissa (2^-12 relative): the same crossing of a
 * surface decides the same way every time Embree asks, also where a ray meets the shared edge
 * of two triangles and Embree reports both (hashing the triangle made those edges pass twice as
 * often: 0.56 instead of 0.75 on a quad's diagonal), while two faces of a closed mesh are two
 * draws. */
static bool
surface_there(const pt_ray_context *rc, unsigned geometry, unsigned prim, float u, float v, float t, v3 dir)
{
    const pt_scene *pts = rc->pts;
    const pt_geometry *g = &pts->geometries[geometry];
    const cg_material *mat = g->material;
    const uint32_t *tri = &g->mesh->indices[3 * (size_t)prim];
    if (rc->camera && !mat->double_sided) {
        const float *p0 = &g->vertices[3 * tri[0]], *p1 = &g->vertices[3 * tri[1]], *p2 = &g->vertices[3 * tri[2]];
        v3 e1 = mk(p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]);
        v3 e2 = mk(p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]);
        v3 front = mk(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
        if ((dot(front, dir) > 0.0f) != g->mirrored)
            return false;
    }
    if (mat->alpha_mode == CG_ALPHA_OPAQUE)
        return true;
    float alpha = mat->base_color[3];
    float st[2], texel[4];
    triangle_texcoords(g->mesh, tri, u, v, st);
    if (material_texel(pts, mat, mat->base_color_texture, CG_TEX_BASE_COLOR, st, texel))
        alpha *= texel[3];
    if (mat->alpha_mode == CG_ALPHA_MASK)
        return alpha >= mat->alpha_cutoff;
    uint32_t tbits;
    memcpy(&tbits, &t, sizeof tbits);
    uint64_t h = mix64(rc->key ^ mix64(((uint64_t)geometry << 32 | (tbits >> 11)) + 0x632BE59BD9B4E019ull));
    return (float)(h >> 40) * (1.0f / 16777216.0f) < alpha;
}

/* Embree's RTCRayN and RTCHitN accessors are C++ only; these read the same SOA layouts
 * (rtcore_ray.h: a ray's dir_x at float 4N + i, tfar at 8N + i, a hit's u, v, primID, geomID at
 * 3N, 4N, 5N, 6N). */
static void
ray_filter(const struct RTCFilterFunctionNArguments *args)
{
    const pt_ray_context *rc = (const pt_ray_context *)args->context;
    const float *ray = (const float *)args->ray;
    const float *hitf = (const float *)args->hit;
    const unsigned *hitu = (const unsigned *)args->hit;
    unsigned N = args->N;
    for (unsigned i = 0; i < N; i++) {
        if (args->valid[i] != -1)
            continue;
        v3 dir = mk(ray[4 * N + i], ray[5 * N + i], ray[6 * N + i]);
        /* Embree sets the ray's tfar (float 8N + i) to the candidate hit's distance for the filter. */
        if (!surface_there(rc, hitu[6 * N + i], hitu[5 * N + i], hitf[3 * N + i], hitf[4 * N + i], ray[8 * N + i],
                           dir))
            args->valid[i] = 0;
    }
}

/* A ray's random key, from the sample's generator without drawing from it (so that the draws of
 * a scene without BLEND materials stay what they were): its key, its count so far and a salt. */
static inline uint64_t
ray_key(const pt_rng *rng, uint64_t salt)
{
    return mix64(rng->key ^ (rng->counter * 0xD6E8FEB86659FD93ull + salt));
}

static bool
occluded(pt_worker_ctx *wc, v3 org, v3 dir, float tnear, float tfar, uint64_t key)
{
    RTCRay ray = { 0 };
    ray.org_x = org.x; ray.org_y = org.y; ray.org_z = org.z;
    ray.dir_x = dir.x; ray.dir_y = dir.y; ray.dir_z = dir.z;
    ray.tnear = tnear;
    ray.tfar = tfar;
    ray.mask = 0xFFFFFFFFu;
    ray.flags = 0;
    wc->rays++;
    wc->rc.camera = false;
    wc->rc.key = key;
    rtcOccluded1(wc->pts->rtc, &wc->rc.ictx, &ray);
    return ray.tfar < 0.0f;
}

/* A direction drawn uniformly in solid angle in the cone of half angle `half` about unit d
 * (cos theta uniform in [cos half, 1]), on the basis of Duff et al. 2017. */
static v3
sample_cone(v3 d, float half, float u1, float u2)
{
    float cos_max = cosf(half);
    float ct = 1.0f - u1 * (1.0f - cos_max), st = sqrtf(fmaxf(0.0f, 1.0f - ct * ct));
    float sign = copysignf(1.0f, d.z);
    float a = -1.0f / (sign + d.z);
    float b = d.x * d.y * a;
    v3 t = mk(1.0f + sign * d.x * d.x * a, sign * b, -sign * d.x);
    v3 bt = mk(b, sign + d.y * d.y * a, -d.y);
    float phi = 2.0f * PT_PI * u2;
    return normalize(add(add(scale(t, st * cosf(phi)), scale(bt, st * sinf(phi))), scale(d, ct)));
}

/* f x |n.l| of the hit's BSDF for light arriving from wi, seen from wo (cg_bsdf_eval). */
static v3
bsdf_f_cos(const pt_hit *hit, v3 wo, v3 wi, int lobes)
{
    float n[3] = { hit->shading_normal.x, hit->shading_normal.y, hit->shading_normal.z };
    float v[3] = { wo.x, wo.y, wo.z }, l[3] = { wi.x, wi.y, wi.z }, f[3];
    cg_bsdf_eval(&hit->bsdf, n, v, l, hit->eta, lobes, f);
    return mk(f[0], f[1], f[2]);
}

static double
bsdf_pdf(const pt_hit *hit, v3 wo, v3 wi, int lobes)
{
    float n[3] = { hit->shading_normal.x, hit->shading_normal.y, hit->shading_normal.z };
    float v[3] = { wo.x, wo.y, wo.z }, l[3] = { wi.x, wi.y, wi.z };
    return (double)cg_bsdf_pdf(&hit->bsdf, n, v, l, hit->eta, lobes);
}

/* Light of every punctual light reflected at the hit towards wo (next-event estimation): for a
 * Lambertian hit the irradiance x albedo/pi as it always was, else sum E f |n.l|. A directional
 * light with an angular diameter is sampled in its disc (one direction per vertex). */
static v3
punctual_light(pt_worker_ctx *wc, const pt_hit *hit, v3 wo, int lobes, pt_rng *rng)
{
    const cg_scene *scene = wc->pts->scene;
    v3 total = mk(0, 0, 0);
    for (int i = 0; i < scene->light_count; i++) {
        const cg_light *l = &scene->lights[i];
        v3 color = scale(mk(l->color[0], l->color[1], l->color[2]), l->intensity);
        v3 wi;
        float dist = INFINITY, factor = 1.0f;
        if (l->type == CG_LIGHT_DIRECTIONAL) {
            wi = normalize(neg(mk(l->direction[0], l->direction[1], l->direction[2])));
            if (l->angular_diameter > 0.0f) {
                float u1 = rng_next(rng), u2 = rng_next(rng);
                wi = sample_cone(wi, 0.5f * l->angular_diameter, u1, u2);
            }
        } else {
            v3 to_light = sub(mk(l->position[0], l->position[1], l->position[2]), hit->position);
            float d2 = dot(to_light, to_light);
            if (!(d2 > 0.0f))
                continue;
            dist = sqrtf(d2);
            wi = scale(to_light, 1.0f / dist);
            factor = 1.0f / d2; /* E = I / d^2 */
            if (l->range > 0.0f) {
                /* KHR_lights_punctual's recommended window: clamp(1 - (d/range)^4, 0, 1)^2. */
                float r = dist / l->range;
                float win = fminf(fmaxf(1.0f - r * r * r * r, 0.0f), 1.0f);
                factor *= win * win;
            }
            if (l->type == CG_LIGHT_SPOT) {
                /* KHR_lights_punctual spot falloff: saturate(cd * scale + offset)^2 with
                 * scale = 1 / max(0.001, cos(inner) - cos(outer)), offset = -cos(outer) * scale. */
                float cos_outer = cosf(l->outer_cone_angle);
                float angle_scale = 1.0f / fmaxf(0.001f, cosf(l->inner_cone_angle) - cos_outer);
                float angle_offset = -cos_outer * angle_scale;
                v3 spot_dir = normalize(mk(l->direction[0], l->direction[1], l->direction[2]));
                float cd = dot(spot_dir, neg(wi));
                float att = fminf(fmaxf(cd * angle_scale + angle_offset, 0.0f), 1.0f);
                factor *= att * att;
            }
        }
        float cos_theta = dot(hit->shading_normal, wi);
        if (cos_theta <= 0.0f || dot(hit->geometric_normal, wi) <= 0.0f || factor <= 0.0f)
            continue;
        /* Shorten the shadow ray so that it does not hit a surface at the light itself. */
        float tfar = isinf(dist) ? INFINITY : dist * (1.0f - 1e-5f);
        if (occluded(wc, hit->origin, wi, hit->offset, tfar, ray_key(rng, 0x1000u + (uint64_t)i)))
            continue;
        if (hit->lambertian)
            total = add(total, scale(color, factor * cos_theta));
        else
            total = add(total, mul(scale(color, factor), bsdf_f_cos(hit, wo, wi, lobes)));
    }
    return hit->lambertian ? scale(mul(hit->albedo, total), 1.0f / PT_PI) : total;
}

/* Cosine-weighted direction about n (Malley's method) on the orthonormal basis of
 * Duff et al. 2017, "Building an Orthonormal Basis, Revisited". */
static v3
sample_cosine(v3 n, float u1, float u2)
{
    float sign = copysignf(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    v3 t = mk(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    v3 bt = mk(b, sign + n.y * n.y * a, -n.y);
    float r = sqrtf(u1), phi = 2.0f * PT_PI * u2;
    float x = r * cosf(phi), y = r * sinf(phi), z = sqrtf(fmaxf(0.0f, 1.0f - u1));
    return normalize(add(add(scale(t, x), scale(bt, y)), scale(n, z)));
}

static inline void
ray_init(RTCRayHit *rh, v3 org, v3 dir, float tnear)
{
    memset(rh, 0, sizeof *rh);
    rh->ray.org_x = org.x; rh->ray.org_y = org.y; rh->ray.org_z = org.z;
    rh->ray.dir_x = dir.x; rh->ray.dir_y = dir.y; rh->ray.dir_z = dir.z;
    rh->ray.tnear = tnear;
    rh->ray.tfar = INFINITY;
    rh->ray.mask = 0xFFFFFFFFu;
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

/* ---------------------------------------------------------------- emitters and MIS */

/* The power heuristic with beta = 2 (Veach and Guibas, "Optimally Combining Sampling
 * Techniques for Monte Carlo Rendering", SIGGRAPH 1995, section 4.1): the weight of the
 * strategy that drew the sample with density `pa` against the other one's `pb`, both
 * solid-angle densities of the same direction. In double: a small emitter far away has a
 * density beyond float's range once squared. */
static inline float
power_heuristic(double pa, double pb)
{
    if (!(pa > 0.0))
        return 0.0f;
    double r = pb / pa;
    return (float)(1.0 / (1.0 + r * r));
}

/* Index of the emitter whose power interval holds u x total (u in [0, 1)): binary search of
 * the first cdf[i + 1] > u total, so that triangles of zero power are never chosen. */
static int64_t
emitter_pick(const pt_emitters *e, double u)
{
    double target = u * e->cdf[e->count];
    int64_t lo = 0, hi = e->count - 1;
    while (lo < hi) {
        int64_t mid = lo + (hi - lo) / 2;
        if (e->cdf[mid + 1] > target)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

/* Solid-angle density with which emitter sampling from `from` picks the point `at` of
 * triangle (geometry, triangle) seen along the unit direction `dir`: the triangle's share of
 * the power over its area, times distance^2 / |cos| at the emitter (both sides emit). */
static double
emitter_pdf(const pt_scene *pts, unsigned geometry, unsigned triangle, v3 from, v3 at, v3 dir)
{
    const pt_emitters *e = &pts->emitters;
    const pt_geometry *g = &pts->geometries[geometry];
    if (g->emitter_base < 0 || e->count == 0)
        return 0.0;
    int64_t i = g->emitter_base + triangle;
    double share = (e->cdf[i + 1] - e->cdf[i]) / e->cdf[e->count];
    v3 p[3], n;
    float area;
    triangle_frame(g, triangle, p, &n, &area);
    double cos_l = fabs((double)dot(n, dir));
    if (!(share > 0.0) || !(area > 0.0f) || !(cos_l > 0.0))
        return 0.0;
    v3 d = sub(at, from);
    return share * (double)dot(d, d) / ((double)area * cos_l);
}

/* Light from the emissive triangles at the hit, by one emitter sample (next-event
 * estimation) weighted against cosine sampling of the BRDF: returns albedo/pi x Le x cos x w /
 * pdf for a point chosen by power, then uniformly on its triangle (Shirley's square-root
 * map of the unit square onto a triangle), with a shadow ray between the two offset ends. */
static v3
emitter_direct(pt_worker_ctx *wc, const pt_hit *hit, v3 wo, int lobes, pt_rng *rng)
{
    const pt_scene *pts = wc->pts;
    const pt_emitters *e = &pts->emitters;
    /* 48 random bits for the choice: 24 would not tell apart millions of triangles. */
    double u = ((double)rng_next(rng) + (double)rng_next(rng) * (1.0 / 16777216.0));
    float r1 = rng_next(rng), r2 = rng_next(rng);
    int64_t i = emitter_pick(e, u);
    unsigned geometry = e->geometry[i], triangle = e->triangle[i];
    if (geometry == hit->geometry && triangle == hit->triangle)
        return mk(0, 0, 0); /* a flat triangle does not light itself */
    const pt_geometry *g = &pts->geometries[geometry];
    v3 p[3], n;
    float area;
    triangle_frame(g, triangle, p, &n, &area);
    float su = sqrtf(r1), bu = 1.0f - su, bv = r2 * su, bw = 1.0f - bu - bv;
    v3 y = mk(bw * p[0].x + bu * p[1].x + bv * p[2].x, bw * p[0].y + bu * p[1].y + bv * p[2].y,
              bw * p[0].z + bu * p[1].z + bv * p[2].z);
    v3 to = sub(y, hit->position);
    float d2 = dot(to, to);
    if (!(d2 > 0.0f) || !(area > 0.0f))
        return mk(0, 0, 0);
    v3 wi = scale(to, 1.0f / sqrtf(d2));
    float cos_x = dot(hit->shading_normal, wi), cos_l = fabsf(dot(n, wi));
    if (cos_x <= 0.0f || dot(hit->geometric_normal, wi) <= 0.0f || !(cos_l > 0.0f))
        return mk(0, 0, 0);
    const uint32_t *tri = &g->mesh->indices[3 * (size_t)triangle];
    float st[2];
    triangle_texcoords(g->mesh, tri, bu, bv, st);
    v3 le = emission_at(pts, g->material, st);
    if (le.x <= 0.0f && le.y <= 0.0f && le.z <= 0.0f)
        return mk(0, 0, 0);
    double share = (e->cdf[i + 1] - e->cdf[i]) / e->cdf[e->count];
    double pdf = share * (double)d2 / ((double)area * cos_l);
    /* The light's end of the shadow ray is lifted off the emitter towards the hit, as the
     * hit's end is (spawn_point), so that neither end finds its own surface. */
    float m = fmaxf(fmaxf(fabsf(p[0].x), fmaxf(fabsf(p[0].y), fabsf(p[0].z))),
                    fmaxf(fmaxf(fabsf(p[1].x), fmaxf(fabsf(p[1].y), fabsf(p[1].z))),
                          fmaxf(fabsf(p[2].x), fmaxf(fabsf(p[2].y), fabsf(p[2].z)))));
    v3 n_towards = dot(n, wi) < 0.0f ? n : neg(n);
    v3 target = add(y, scale(n_towards, PT_OFFSET_RELATIVE * m));
    /* An unnormalised direction: the segment is t in [tnear, 1); stopping 1e-5 of its length
     * short of the lifted end leaves what rounding does to org + 1 x dir out of it. */
    v3 seg = sub(target, hit->origin);
    float seg_len = sqrtf(dot(seg, seg));
    if (!(seg_len > 0.0f))
        return mk(0, 0, 0);
    if (occluded(wc, hit->origin, seg, hit->offset / seg_len, 1.0f - 1e-5f, ray_key(rng, 0x2000u)))
        return mk(0, 0, 0);
    if (!hit->lambertian) {
        float w = power_heuristic(pdf, bsdf_pdf(hit, wo, wi, lobes));
        return scale(mul(bsdf_f_cos(hit, wo, wi, lobes), le), (float)((double)w / pdf));
    }
    float w = power_heuristic(pdf, cos_x / PT_PI);
    float k = (float)((double)cos_x * w / (PT_PI * pdf));
    return scale(mul(hit->albedo, le), k);
}

/* ---------------------------------------------------------------- sky */

static inline v3
sky_radiance(const pt_scene *pts, v3 dir)
{
    float d[3] = { dir.x, dir.y, dir.z }, rgb[3];
    cg_sky_model_radiance(&pts->sky.model, d, rgb);
    return mk(rgb[0], rgb[1], rgb[2]);
}

/* Solid-angle density with which sky sampling at a point of shading normal n draws dir: the
 * cosine about n for a uniform sky, the table's for an analytic one. */
static double
sky_pdf(const pt_scene *pts, v3 n, v3 dir)
{
    if (pts->sky.model.type == CG_SKY_UNIFORM)
        return fmax(0.0, (double)dot(n, dir)) / PT_PI;
    float d[3] = { dir.x, dir.y, dir.z };
    return pt_sky_pdf(&pts->sky, d);
}

/* Light from the sky at the hit by one sky sample weighted against cosine sampling of the
 * BRDF (power heuristic): a uniform sky is sampled by the cosine about the shading normal
 * (the BRDF's own density, so both weights are 1/2 and an unoccluded surface gets exactly
 * albedo x L), an analytic one from its table. */
static v3
sky_direct(pt_worker_ctx *wc, const pt_hit *hit, v3 wo, int lobes, pt_rng *rng)
{
    const pt_scene *pts = wc->pts;
    float u1 = rng_next(rng), u2 = rng_next(rng);
    v3 wi;
    double pdf;
    if (pts->sky.model.type == CG_SKY_UNIFORM) {
        wi = sample_cosine(hit->shading_normal, u1, u2);
        pdf = fmax(0.0, (double)dot(hit->shading_normal, wi)) / PT_PI;
    } else {
        float d[3];
        if (!pt_sky_sample(&pts->sky, u1, u2, d, &pdf))
            return mk(0, 0, 0);
        wi = mk(d[0], d[1], d[2]);
    }
    float cos_x = dot(hit->shading_normal, wi);
    if (!(pdf > 0.0) || cos_x <= 0.0f || dot(hit->geometric_normal, wi) <= 0.0f)
        return mk(0, 0, 0);
    v3 l = sky_radiance(pts, wi);
    if (l.x <= 0.0f && l.y <= 0.0f && l.z <= 0.0f)
        return mk(0, 0, 0);
    if (occluded(wc, hit->origin, wi, hit->offset, INFINITY, ray_key(rng, 0x3000u)))
        return mk(0, 0, 0);
    if (!hit->lambertian) {
        float w = power_heuristic(pdf, bsdf_pdf(hit, wo, wi, lobes));
        return scale(mul(bsdf_f_cos(hit, wo, wi, lobes), l), (float)((double)w / pdf));
    }
    float w = power_heuristic(pdf, cos_x / PT_PI);
    float k = (float)((double)cos_x * w / (PT_PI * pdf));
    return scale(mul(hit->albedo, l), k);
}

/* ---------------------------------------------------------------- paths */

/* Radiance along one camera ray, with bounces counted as Cycles and pbrt count them: at
 * every vertex x1 ... x(n+1) of the path (n = `bounces`), light arrives directly from every
 * source: punctual lights (next-event estimation), emissive triangles and the sky (one
 * sample of each, combined with the cosine-sampled continuation by the power heuristic);
 * emission and sky are seen where the camera ray lands or escapes. So n = 0 is the direct
 * light of every source plus what the camera sees, and each bounce adds one diffuse
 * reflection. The continuation from x(n+1) only looks for emitters and the sky (its MIS
 * half of their direct light); it is not traced when the scene has neither. The Lambertian BRDF albedo/pi times cos over the cosine pdf cos/pi leaves
 * the albedo as the throughput factor. */
/* Which part of the image a contribution belongs to: light that arrives at vertex `depth`
 * (0 = where the camera ray lands) reaches the camera after `depth` reflections, and light
 * that a vertex receives directly after depth + 1. */
static inline pt_part
part_seen(int depth, pt_part direct)
{
    return depth == 0 ? PT_PART_EMITTED : (depth == 1 ? direct : PT_PART_INDIRECT);
}

static inline pt_part
part_received(int depth, pt_part direct)
{
    return depth == 0 ? direct : PT_PART_INDIRECT;
}

static v3
radiance(pt_worker_ctx *wc, v3 org, v3 dir, float tnear, const pt_settings *settings, pt_rng *rng,
         v3 parts[PT_PART_COUNT])
{
    const pt_scene *pts = wc->pts;
    const bool emitters = pts->emitters.count > 0;
    const bool sky = pts->sky.model.type != CG_SKY_NONE;
    v3 sum = mk(0, 0, 0), throughput = mk(1, 1, 1);
    v3 prev_position = mk(0, 0, 0), prev_normal = mk(0, 0, 0);
    float prev_pdf = 0.0f;  /* solid-angle density of the BSDF sample that made this ray */
    bool prev_mis = false;  /* light sampling could have found this ray's light too */
    int diffuse = 0, glossy = 0, transmission = 0; /* scatterings of each kind so far */
    bool last = false;      /* a limit is passed: this vertex shows its emission only */
    RTCRayHit rh;
    ray_init(&rh, org, dir, tnear);
    for (int depth = 0;; depth++) {
        wc->rays++;
        wc->rc.camera = depth == 0;
        wc->rc.key = ray_key(rng, 0x4000u + (uint64_t)depth);
        rtcIntersect1(pts->rtc, &wc->rc.ictx, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
            if (sky) {
                v3 d = mk(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
                float w = !prev_mis ? 1.0f : power_heuristic(prev_pdf, sky_pdf(pts, prev_normal, d));
                v3 c = mul(throughput, scale(sky_radiance(pts, d), w));
                sum = add(sum, c);
                parts[part_seen(depth, PT_PART_DIRECT_SKY)] = add(parts[part_seen(depth, PT_PART_DIRECT_SKY)], c);
            }
            break;
        }
        pt_hit hit;
        shade_hit(pts, &rh, &hit);
        if (hit.back && hit.bsdf.thickness > 0.0f && !hit.lambertian &&
            (hit.bsdf.sigma[0] > 0.0f || hit.bsdf.sigma[1] > 0.0f || hit.bsdf.sigma[2] > 0.0f)) {
            /* The ray travelled inside this solid from its last vertex: Beer-Lambert over that length
             * (KHR_materials_volume). */
            v3 d = mk(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
            float t = rh.ray.tfar * sqrtf(dot(d, d));
            throughput = mul(throughput, mk(expf(-hit.bsdf.sigma[0] * t), expf(-hit.bsdf.sigma[1] * t),
                                            expf(-hit.bsdf.sigma[2] * t)));
        }
        if (hit.emission.x > 0.0f || hit.emission.y > 0.0f || hit.emission.z > 0.0f) {
            float w = 1.0f; /* the camera ray, or a sample no light sampling draws */
            if (prev_mis) {
                v3 d = mk(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
                w = power_heuristic(prev_pdf, emitter_pdf(pts, hit.geometry, hit.triangle, prev_position,
                                                           hit.position, d));
            }
            v3 c = mul(throughput, scale(hit.emission, w));
            sum = add(sum, c);
            pt_part part = part_seen(depth, PT_PART_DIRECT_EMITTERS);
            parts[part] = add(parts[part], c);
        }
        if (last)
            break; /* the continuation of the last vertex: emitters and sky only */
        /* Without caustics, a path that has scattered diffusely sees no glossy or transmission lobe. */
        int lobes = settings->caustics || diffuse == 0 ? CG_BSDF_ALL_LOBES : CG_BSDF_DIFFUSE;
        v3 wo = normalize(neg(mk(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z)));
        /* A shading normal (interpolated or mapped) that turns away from the viewer leaves the
         * BSDF nothing to reflect (cg/bsdf.h wants n.v > 0): there the geometric normal shades.
         * The Lambertian path keeps its old rule (the cosine about the shading normal). */
        if (!hit.lambertian && dot(hit.shading_normal, wo) <= 0.0f)
            hit.shading_normal = hit.geometric_normal;
        /* A mirror or a smooth glass (no diffuse lobe, deltas only) has nothing light sampling
         * can find: no shadow rays for it. */
        const cg_bsdf *b = &hit.bsdf;
        bool lit = hit.lambertian || !cg_bsdf_is_smooth(b) ||
                   ((lobes & CG_BSDF_DIFFUSE) && (b->diffuse[0] > 0.0f || b->diffuse[1] > 0.0f || b->diffuse[2] > 0.0f));
        /* `sum` adds the terms in the order it always did, so that the image does not depend
         * on whether the parts are asked for; the parts are summed beside it. */
        v3 c = mk(0, 0, 0);
        pt_part part;
        if (lit) {
            c = mul(throughput, punctual_light(wc, &hit, wo, lobes, rng));
            sum = add(sum, c);
            part = part_received(depth, PT_PART_DIRECT_PUNCTUAL);
            parts[part] = add(parts[part], c);
        }
        if (emitters && lit) {
            c = mul(throughput, emitter_direct(wc, &hit, wo, lobes, rng));
            sum = add(sum, c);
            part = part_received(depth, PT_PART_DIRECT_EMITTERS);
            parts[part] = add(parts[part], c);
        }
        if (sky && lit) {
            c = mul(throughput, sky_direct(wc, &hit, wo, lobes, rng));
            sum = add(sum, c);
            part = part_received(depth, PT_PART_DIRECT_SKY);
            parts[part] = add(parts[part], c);
        }
        v3 next, origin = hit.origin;
        if (hit.lambertian) {
            /* The Lambertian BRDF albedo/pi times cos over the cosine pdf cos/pi leaves the albedo. */
            if (diffuse == settings->bounces && !emitters && !sky)
                break;
            throughput = mul(throughput, hit.albedo);
            if (throughput.x <= 0.0f && throughput.y <= 0.0f && throughput.z <= 0.0f)
                break;
            float u1 = rng_next(rng), u2 = rng_next(rng);
            next = sample_cosine(hit.shading_normal, u1, u2);
            if (dot(next, hit.geometric_normal) <= 0.0f)
                break; /* below the true surface (shading normal tilted away): no light */
            prev_pdf = dot(hit.shading_normal, next) / PT_PI;
            prev_mis = true;
            diffuse++;
        } else {
            float u[3] = { rng_next(rng), rng_next(rng), rng_next(rng) };
            float n[3] = { hit.shading_normal.x, hit.shading_normal.y, hit.shading_normal.z };
            float v[3] = { wo.x, wo.y, wo.z };
            cg_bsdf_sample_result bs;
            if (!cg_bsdf_sample(&hit.bsdf, n, v, hit.eta, lobes, u, &bs))
                break;
            next = mk(bs.l[0], bs.l[1], bs.l[2]);
            bool through = bs.lobe == CG_BSDF_TRANSMISSION;
            /* The geometric normal decides the side (a shading normal can tilt a sample across). */
            if ((dot(next, hit.geometric_normal) > 0.0f) == through)
                break;
            if (through)
                origin = sub(hit.position, scale(hit.geometric_normal, hit.offset));
            diffuse += bs.lobe == CG_BSDF_DIFFUSE;
            glossy += bs.lobe == CG_BSDF_GLOSSY;
            transmission += through;
            throughput = mul(throughput, mk(bs.weight[0], bs.weight[1], bs.weight[2]));
            if (!(throughput.x > 0.0f || throughput.y > 0.0f || throughput.z > 0.0f))
                break;
            /* Light sampling covers the reflection side's non-delta lobes only (pt_render.h). */
            prev_mis = !bs.delta && !through;
            prev_pdf = bs.pdf;
        }
        last = diffuse > settings->bounces || glossy > settings->glossy_bounces ||
               transmission > settings->transmission_bounces;
        if (last && !emitters && !sky)
            break;
        prev_position = hit.position;
        prev_normal = hit.shading_normal;
        ray_init(&rh, origin, next, hit.offset);
    }
    return sum;
}

/* ---------------------------------------------------------------- camera and tiles */

/* The camera ray through NDC (x, y). Built in camera space and in double precision, then
 * turned into the world by the camera-to-world matrix: a perspective ray starts at the eye
 * with tnear = its distance to the near plane (what the rasteriser clips), an orthographic
 * one on the near plane. Never the difference of two world-space points: at 1.6 km from the
 * origin two points 5 cm apart (a near plane) differ by a few float ulps only, which tilted
 * each ray by up to 1e-3 rad and stair-stepped the edges. */
static void
camera_ray(const cg_view *view, double ndc_x, double ndc_y, v3 *org, v3 *dir, float *tnear)
{
    const float *ip = view->inv_proj, *iv = view->inv_view;
    double c[4];
    for (int r = 0; r < 4; r++)
        c[r] = ip[r] * ndc_x + ip[4 + r] * ndc_y - ip[8 + r] + ip[12 + r];
    double p[3] = { c[0] / c[3], c[1] / c[3], c[2] / c[3] }; /* the near-plane point, camera space */
    double o[3], d[3], t0;
    if (view->orthographic) {
        o[0] = p[0], o[1] = p[1], o[2] = p[2];
        d[0] = 0.0, d[1] = 0.0, d[2] = -1.0;
        t0 = 0.0;
    } else {
        double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        o[0] = o[1] = o[2] = 0.0;
        d[0] = p[0] / len, d[1] = p[1] / len, d[2] = p[2] / len;
        t0 = len;
    }
    double wo[3], wd[3];
    for (int r = 0; r < 3; r++) {
        wo[r] = iv[r] * o[0] + iv[4 + r] * o[1] + iv[8 + r] * o[2] + iv[12 + r];
        wd[r] = iv[r] * d[0] + iv[4 + r] * d[1] + iv[8 + r] * d[2];
    }
    double n = sqrt(wd[0] * wd[0] + wd[1] * wd[1] + wd[2] * wd[2]);
    *org = mk((float)wo[0], (float)wo[1], (float)wo[2]);
    *dir = mk((float)(wd[0] / n), (float)(wd[1] / n), (float)(wd[2] / n));
    *tnear = (float)(t0 * n); /* inv_view is orthonormal (camera.c), so n = 1 up to rounding */
}

typedef struct pt_job {
    const pt_scene *pts;
    const cg_view *view;
    const pt_settings *settings;
    float *rgba;
    float *const *parts;      /* PT_PART_COUNT images or NULLs, or NULL */
    int tiles_x, tiles_y, tile_count;
    atomic_int next_tile;
    atomic_int tiles_done;
    atomic_uint_fast64_t rays;
    cg_progress *progress;    /* NULL: none; updated by the main thread alone */
} pt_job;

static void
render_tile(pt_job *job, pt_worker_ctx *wc, int tile)
{
    const cg_view *view = job->view;
    const pt_settings *s = job->settings;
    int x0 = (tile % job->tiles_x) * PT_TILE, y0 = (tile / job->tiles_x) * PT_TILE;
    int x1 = x0 + PT_TILE < view->width ? x0 + PT_TILE : view->width;
    int y1 = y0 + PT_TILE < view->height ? y0 + PT_TILE : view->height;
    for (int y = y0; y < y1; y++) {
        for (int x = x0; x < x1; x++) {
            uint64_t pixel = (uint64_t)y * (uint64_t)view->width + (uint64_t)x;
            double acc[3] = { 0, 0, 0 }, acc_parts[PT_PART_COUNT][3];
            memset(acc_parts, 0, sizeof acc_parts);
            for (int k = 0; k < s->spp; k++) {
                pt_rng rng = rng_for_sample(s->seed, pixel, (uint32_t)k);
                float jx = 0.5f, jy = 0.5f;
                if (s->jitter) {
                    jx = rng_next(&rng);
                    jy = rng_next(&rng);
                }
                /* Rows top to bottom: row y's centre is at NDC y = 1 - 2 (y + 0.5) / height, the
                 * same point as GL's gl_FragCoord.y = height - y - 0.5 of the flipped read-back. */
                double ndc_x = 2.0 * ((double)x + jx) / (double)view->width - 1.0;
                double ndc_y = 1.0 - 2.0 * ((double)y + jy) / (double)view->height;
                v3 org, dir;
                float tnear;
                camera_ray(view, ndc_x, ndc_y, &org, &dir, &tnear);
                v3 parts[PT_PART_COUNT];
                for (int p = 0; p < PT_PART_COUNT; p++)
                    parts[p] = mk(0, 0, 0);
                v3 l = radiance(wc, org, dir, tnear, s, &rng, parts);
                acc[0] += l.x;
                acc[1] += l.y;
                acc[2] += l.z;
                for (int p = 0; p < PT_PART_COUNT; p++) {
                    acc_parts[p][0] += parts[p].x;
                    acc_parts[p][1] += parts[p].y;
                    acc_parts[p][2] += parts[p].z;
                }
            }
            float *out = &job->rgba[4 * pixel];
            for (int c = 0; c < 3; c++)
                out[c] = (float)(acc[c] / s->spp);
            out[3] = 1.0f;
            for (int p = 0; job->parts && p < PT_PART_COUNT; p++) {
                if (!job->parts[p])
                    continue;
                float *po = &job->parts[p][4 * pixel];
                for (int c = 0; c < 3; c++)
                    po[c] = (float)(acc_parts[p][c] / s->spp);
                po[3] = 1.0f;
            }
        }
    }
}

typedef struct pt_thread_arg {
    pt_job *job;
    bool main_thread;
} pt_thread_arg;

static void *
worker(void *arg)
{
    pt_thread_arg *ta = arg;
    pt_job *job = ta->job;
    pt_worker_ctx wc = { .pts = job->pts, .rays = 0 };
    rtcInitIntersectContext(&wc.rc.ictx);
    wc.rc.pts = job->pts;
    for (;;) {
        int tile = atomic_fetch_add(&job->next_tile, 1);
        if (tile >= job->tile_count)
            break;
        render_tile(job, &wc, tile);
        int done = atomic_fetch_add(&job->tiles_done, 1) + 1;
        if (ta->main_thread && job->progress)
            cg_progress_update(job->progress, done);
    }
    atomic_fetch_add(&job->rays, wc.rays);
    return NULL;
}

const char *
pt_part_name(pt_part part)
{
    static const char *const names[PT_PART_COUNT] = { "emitted", "direct_punctual", "direct_emitters",
                                                       "direct_sky", "indirect" };
    return part >= 0 && part < PT_PART_COUNT ? names[part] : "?";
}

bool
pt_render(const pt_scene *pts, const cg_view *view, const pt_settings *settings, float *rgba,
          uint64_t *rays_traced, cg_error *err)
{
    return pt_render_parts(pts, view, settings, rgba, NULL, rays_traced, err);
}

bool
pt_render_parts(const pt_scene *pts, const cg_view *view, const pt_settings *settings, float *rgba,
                float *const parts[PT_PART_COUNT], uint64_t *rays_traced, cg_error *err)
{
    if (view->width <= 0 || view->height <= 0)
        return cg_fail(err, CG_ERR_USAGE, "path_trace: image size %dx%d, expected positive",
                       view->width, view->height);
    if (settings->spp < 1 || settings->spp > PT_MAX_SPP)
        return cg_fail(err, CG_ERR_USAGE, "path_trace: spp %d, expected 1..%d", settings->spp, PT_MAX_SPP);
    if (settings->bounces < 0 || settings->bounces > PT_MAX_BOUNCES)
        return cg_fail(err, CG_ERR_USAGE, "path_trace: bounces %d, expected 0..%d", settings->bounces,
                       PT_MAX_BOUNCES);
    if (settings->glossy_bounces < 0 || settings->glossy_bounces > PT_MAX_BOUNCES)
        return cg_fail(err, CG_ERR_USAGE, "path_trace: glossy_bounces %d, expected 0..%d",
                       settings->glossy_bounces, PT_MAX_BOUNCES);
    if (settings->transmission_bounces < 0 || settings->transmission_bounces > PT_MAX_BOUNCES)
        return cg_fail(err, CG_ERR_USAGE, "path_trace: transmission_bounces %d, expected 0..%d",
                       settings->transmission_bounces, PT_MAX_BOUNCES);
    if (settings->threads < 0 || settings->threads > PT_MAX_THREADS)
        return cg_fail(err, CG_ERR_USAGE, "path_trace: threads %d, expected 0..%d", settings->threads,
                       PT_MAX_THREADS);
    int threads = settings->threads;
    if (threads == 0) {
        long n = sysconf(_SC_NPROCESSORS_ONLN);
        threads = n > 0 ? (n > PT_MAX_THREADS ? PT_MAX_THREADS : (int)n) : 1;
    }
    pt_job job = { .pts = pts, .view = view, .settings = settings, .rgba = rgba, .parts = parts };
    job.tiles_x = (view->width + PT_TILE - 1) / PT_TILE;
    job.tiles_y = (view->height + PT_TILE - 1) / PT_TILE;
    job.tile_count = job.tiles_x * job.tiles_y;
    atomic_init(&job.next_tile, 0);
    atomic_init(&job.tiles_done, 0);
    atomic_init(&job.rays, 0);

    pthread_t ids[PT_MAX_THREADS];
    pt_thread_arg args[PT_MAX_THREADS];
    int started = 0;
    for (int t = 1; t < threads; t++) {
        args[t] = (pt_thread_arg){ &job, false };
        if (pthread_create(&ids[t], NULL, worker, &args[t]) != 0)
            break; /* fewer threads only slows the render down; the image is the same */
        started = t;
    }
    /* Progress by tiles (cg/progress.h: on a terminal one updating line, into a file a line
     * per 10% and no carriage return; nothing for a render under its delay). */
    cg_progress progress;
    if (settings->progress) {
        char what[96];
        snprintf(what, sizeof what, "path tracing %dx%d at %d spp", view->width, view->height, settings->spp);
        cg_progress_begin(&progress, &(cg_progress_desc){ .what = what, .total = job.tile_count });
        job.progress = &progress;
    }
    args[0] = (pt_thread_arg){ &job, true };
    worker(&args[0]);
    for (int t = 1; t <= started; t++)
        pthread_join(ids[t], NULL);
    /* The main thread updates only after its own tiles: where the others took every tile (a small
     * image), it never did, and the end would print nothing (test_progress_into_a_file, flaky). */
    if (job.progress) {
        cg_progress_update(job.progress, job.tile_count);
        cg_progress_end(job.progress);
    }
    if (rays_traced)
        *rays_traced = atomic_load(&job.rays);
    return true;
}
