/* Diffuse cone sets; see sdk/cone.h and docs/vct.md for the weight derivation. */
#include "sdk/cone.h"

#include "cg/bsdf.h"

#include "sdk/pass.h"
#include "sdk/sampler.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const int cone_set_sizes[] = { CGP_CONE_SET_SIZES };

/* The widest automatic cone: a hemisphere-wide cone (1-cone set) would have an infinite
 * diameter, so its half-angle is capped here; the gather's aperture parameter overrides. */
#define CONE_MAX_AUTO_HALF_ANGLE (60.0 * M_PI / 180.0)

/* One ring of a set: `count` cones at polar angle `theta`, owning the band [lo, hi]. */
typedef struct cone_ring {
    int count;
    double theta, lo, hi;
    double azimuth_offset;  /* radians */
} cone_ring;

const int *
cgp_cone_set_sizes(int *count)
{
    *count = (int)(sizeof cone_set_sizes / sizeof cone_set_sizes[0]);
    return cone_set_sizes;
}

bool
cgp_cone_set_valid_size(int count)
{
    for (size_t i = 0; i < sizeof cone_set_sizes / sizeof cone_set_sizes[0]; i++)
        if (cone_set_sizes[i] == count)
            return true;
    return false;
}

static double
deg(double d)
{
    return d * M_PI / 180.0;
}

/* Polar angle whose sin^2 is s: the bands of the 16-cone set are chosen by their cosine weight. */
static double
polar_of_sin2(double s)
{
    return asin(sqrt(s));
}

static int
rings_for(int count, cone_ring rings[4])
{
    switch (count) {
    case 1:
        rings[0] = (cone_ring){1, 0.0, 0.0, deg(90.0), 0.0};
        return 1;
    case 6:
        /* Crassin et al. 2011: one cone along the normal, five at 60 deg; the cell boundary
         * is the mid polar angle, 30 deg, which yields their weights pi/4 and 3pi/20 (/pi). */
        rings[0] = (cone_ring){1, 0.0, 0.0, deg(30.0), 0.0};
        rings[1] = (cone_ring){5, deg(60.0), deg(30.0), deg(90.0), 0.0};
        return 2;
    case 9:
        /* VCT paper 3.2.1: one forward cone and eight side cones rotated 45 deg from the
         * normal in 45 deg azimuth increments; boundary at the mid polar angle, 22.5 deg. */
        rings[0] = (cone_ring){1, 0.0, 0.0, deg(22.5), 0.0};
        rings[1] = (cone_ring){8, deg(45.0), deg(22.5), deg(90.0), 0.0};
        return 2;
    case 16:
        /* 1 + 5 + 10 with bands of equal cosine weight per cone: sin^2 of the band edges is
         * 1/16 and 6/16; each ring sits at its band's cosine-weighted median. */
        rings[0] = (cone_ring){1, 0.0, 0.0, polar_of_sin2(1.0 / 16.0), 0.0};
        rings[1] = (cone_ring){5, polar_of_sin2(3.5 / 16.0), polar_of_sin2(1.0 / 16.0),
                               polar_of_sin2(6.0 / 16.0), 0.0};
        rings[2] = (cone_ring){10, polar_of_sin2(11.0 / 16.0), polar_of_sin2(6.0 / 16.0),
                               deg(90.0), deg(18.0)};
        return 3;
    case 26:
        /* The 16-cone set with its outer band split into two rings of 10 of equal cosine weight
         * (sin^2 6/16 to 11/16 and 11/16 to 1): half angles 12.4 and 19.2 deg where the 16 set's
         * outer ring has 22.9. A wide cone that meets a surface obliquely fills at the crossing
         * though its far rays pass beyond the surface's edge; narrower cones near the horizon
         * cut that excess on compact sources (docs/vct.md, "Cone sets and the oblique
         * crossings"). The inner rings are the 16 set's; the two rings of 10 are staggered by half
         * their spacing (18 deg), the inner of them against the ring of 5 as in the 16 set. */
        rings[0] = (cone_ring){1, 0.0, 0.0, polar_of_sin2(1.0 / 16.0), 0.0};
        rings[1] = (cone_ring){5, polar_of_sin2(3.5 / 16.0), polar_of_sin2(1.0 / 16.0),
                               polar_of_sin2(6.0 / 16.0), 0.0};
        rings[2] = (cone_ring){10, polar_of_sin2(8.5 / 16.0), polar_of_sin2(6.0 / 16.0),
                               polar_of_sin2(11.0 / 16.0), deg(18.0)};
        rings[3] = (cone_ring){10, polar_of_sin2(13.5 / 16.0), polar_of_sin2(11.0 / 16.0),
                               deg(90.0), 0.0};
        return 4;
    default:
        return 0;
    }
}

bool
cgp_cone_set_make(int count, cgp_cone_set *out)
{
    cone_ring rings[4];
    int ring_count = rings_for(count, rings);
    if (ring_count == 0)
        return false;
    out->count = 0;
    for (int r = 0; r < ring_count; r++) {
        const cone_ring *ring = &rings[r];
        double s_lo = sin(ring->lo), s_hi = sin(ring->hi);
        /* (1/pi) * integral_{lo}^{hi} integral_{sector} cos(t) sin(t) dphi dt
         *   = (sin^2 hi - sin^2 lo) / count */
        double weight = (s_hi * s_hi - s_lo * s_lo) / ring->count;
        /* Solid angle of the cell: 2 pi (cos lo - cos hi) / count; the cone with the same
         * solid angle 2 pi (1 - cos a) has cos a = 1 - (cos lo - cos hi) / count. */
        double half = acos(1.0 - (cos(ring->lo) - cos(ring->hi)) / ring->count);
        if (half > CONE_MAX_AUTO_HALF_ANGLE)
            half = CONE_MAX_AUTO_HALF_ANGLE;
        for (int i = 0; i < ring->count; i++) {
            double phi = ring->azimuth_offset + 2.0 * M_PI * i / ring->count;
            cgp_cone *c = &out->cones[out->count++];
            c->direction[0] = (float)(sin(ring->theta) * cos(phi));
            c->direction[1] = (float)(sin(ring->theta) * sin(phi));
            c->direction[2] = (float)cos(ring->theta);
            c->weight = (float)weight;
            c->half_angle = (float)half;
            c->cell_lo = (float)ring->lo;
            c->cell_hi = (float)ring->hi;
        }
    }
    return true;
}

bool
cgp_cone_set_of_param(const fg_pass *pass, const char *param, cgp_cone_set *out, cg_error *err)
{
    int count = fg_param_int(pass, param);
    if (cgp_cone_set_make(count, out))
        return true;
    char sizes[64] = "";
    size_t used = 0;
    for (size_t i = 0; i < sizeof cone_set_sizes / sizeof cone_set_sizes[0] && used < sizeof sizes; i++)
        used += (size_t)snprintf(sizes + used, sizeof sizes - used, "%s%d", i ? ", " : "", cone_set_sizes[i]);
    return cg_fail(err, CG_ERR_GRAPH_PARAM_RANGE, "pass '%s': %s: no cone set of %d cones (sets: %s)",
                   fg_pass_name(pass), param, count, sizes);
}

bool
cgp_cone_set_of_pass(const fg_pass *pass, cgp_cone_set *out, cg_error *err)
{
    return cgp_cone_set_of_param(pass, "cones", out, err);
}

void
cgp_cone_block_fill_march(const cgp_cone_set *set, double step, double start_offset, double max_distance,
                          double lod_bias, cg_cone_set_block *out)
{
    *out = (cg_cone_set_block){
        .count = {set->count, 0, 0, 0},
        .march = {(float)step, (float)start_offset, (float)max_distance, (float)lod_bias},
    };
    for (int k = 0; k < set->count; k++) {
        const cgp_cone *c = &set->cones[k];
        for (int i = 0; i < 3; i++)
            out->cones[k][i] = c->direction[i];
        out->cones[k][3] = c->weight;
        out->apertures[k][0] = (float)tan(c->half_angle);
    }
}

void
cgp_cone_block_fill(const fg_pass *pass, const cgp_cone_set *set, cg_cone_set_block *out)
{
    double aperture = fg_param_float(pass, "aperture");
    *out = (cg_cone_set_block){
        .count = {set->count, 0, 0, 0},
        .march = {fg_param_float(pass, "step"), fg_param_float(pass, "start_offset"),
                  fg_param_float(pass, "max_distance"), fg_param_float(pass, "lod_bias")},
    };
    for (int k = 0; k < set->count; k++) {
        const cgp_cone *c = &set->cones[k];
        for (int i = 0; i < 3; i++)
            out->cones[k][i] = c->direction[i];
        out->cones[k][3] = c->weight;
        out->apertures[k][0] = (float)(aperture > 0.0 ? tan(0.5 * aperture * M_PI / 180.0) : tan(c->half_angle));
    }
}

void
cgp_cone_upload(const fg_pass *pass, const cgp_cone_set *set, GLuint buffer)
{
    cg_cone_set_block block;
    cgp_cone_block_fill(pass, set, &block);
    cgp_uniform_upload(buffer, CG_BINDING_CONES, &block, sizeof block);
}

/* The inputs the SDK declares for a gather, by these names in declare and found by them in
 * cgp_gather_prepare (cgp_gather_slots). */
static const char *const volume_name = "volume", *const region_name = "region", *const glossy_name = "glossy";
static const char *const reflection_name = "reflection", *const refraction_name = "refraction";
static const char *const direction_names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
static const char *const surface_names[2] = {"sides", "normals"};

bool
cgp_gather_declare_volume(fg_pass *pass, fg_declare *decl, const fg_resource_desc **volume,
                          const fg_resource_desc **region, cg_error *err)
{
    *volume = fg_declare_input(decl, volume_name, FG_TEXTURE_3D, FG_ACCESS_SAMPLED, false);
    *region = fg_declare_input(decl, region_name, FG_BUFFER, FG_ACCESS_UNIFORM, false);
    int directions = 0, surface = 0;
    for (int d = 0; d < 6; d++)
        directions += fg_declare_input(decl, direction_names[d], FG_TEXTURE_3D, FG_ACCESS_SAMPLED, false) != NULL;
    for (int d = 0; d < 2; d++)
        surface += fg_declare_input(decl, surface_names[d], FG_TEXTURE_3D, FG_ACCESS_SAMPLED, false) != NULL;
    if (directions != 0 && directions != 6)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': the anisotropic inputs px nx py ny pz nz go together (a mip3d pass's "
                       "outputs with anisotropic = true); %d of 6 are present", fg_pass_name(pass), directions);
    if (surface == 1)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': the surface inputs 'sides' and 'normals' go together (a voxel_light pass's "
                       "outputs, with its 'radiance' as 'volume')", fg_pass_name(pass));
    if (directions && surface)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': the anisotropic inputs px .. nz and the surface inputs sides, normals belong to "
                       "two different volumes; connect one", fg_pass_name(pass));
    if ((directions || surface) && !*volume)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT, "pass '%s': input '%s' needs input 'volume'",
                       fg_pass_name(pass), directions ? "px" : "sides");
    if (*volume && !*region)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': input 'volume' needs input 'region' (a voxelize or voxel_light pass's output "
                       "'region')", fg_pass_name(pass));
    if (fg_declare_input(decl, glossy_name, FG_TEXTURE_3D, FG_ACCESS_SAMPLED, false) && !surface)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': input 'glossy' (a voxel_light pass's output with glossy = true) needs that pass's "
                       "'radiance', 'sides' and 'normals' as 'volume', 'sides' and 'normals'", fg_pass_name(pass));
    if (*region && (*region)->buffer_bytes < sizeof(cg_volume_block))
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'region' holds %zu bytes; a voxelize 'region' holds %zu",
                       fg_pass_name(pass), (*region)->buffer_bytes, sizeof(cg_volume_block));
    return true;
}

cgp_volume_model
cgp_gather_volume_model(const fg_pass *pass, const cgp_gather_slots *slots)
{
    if (fg_slot_present(pass, slots->directions[0]))
        return CGP_VOLUME_ANISOTROPIC;
    if (fg_slot_present(pass, slots->surface[0]))
        return CGP_VOLUME_SURFACE;
    return CGP_VOLUME_RADIANCE;
}

const char *
cgp_gather_volume_define(cgp_volume_model model)
{
    switch (model) {
    case CGP_VOLUME_ANISOTROPIC: return "#define CG_CONE_ANISOTROPIC\n";
    case CGP_VOLUME_SURFACE: return "#define CG_CONE_SURFACE\n";
    case CGP_VOLUME_RADIANCE: break;
    }
    return "";
}

void
cgp_gather_bind_volume(const fg_pass *pass, const cgp_gather *g, GLuint sampler, bool unbind)
{
    cgp_volume_model model = g->model;
    if (model == CGP_VOLUME_ANISOTROPIC)
        for (int d = 0; d < 6; d++) {
            glBindTextureUnit(CG_UNIT_ANISO + (GLuint)d, unbind ? 0 : fg_slot_texture(pass, g->slots.directions[d]));
            glBindSampler(CG_UNIT_ANISO + (GLuint)d, unbind ? 0 : sampler);
        }
    if (model == CGP_VOLUME_SURFACE) {
        static const GLuint units[2] = {CG_UNIT_SIDES, CG_UNIT_NORMALS};
        for (int d = 0; d < 2; d++) {
            glBindTextureUnit(units[d], unbind ? 0 : fg_slot_texture(pass, g->slots.surface[d]));
            glBindSampler(units[d], unbind ? 0 : sampler);
        }
    }
}

static const char *const material_names[5] = {"albedo", "specular", "material", "transmission", "attenuation"};
static const GLuint material_units[5] = {CG_UNIT_ALBEDO, CG_UNIT_SPECULAR, CG_UNIT_MATERIAL, CG_UNIT_TRANSMISSION,
                                         CG_UNIT_ATTENUATION};

bool
cgp_gather_declare_material(fg_pass *pass, fg_declare *decl, bool *present, cg_error *err)
{
    int count = 0;
    for (int i = 0; i < 5; i++)
        count += fg_declare_input(decl, material_names[i], FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false) != NULL;
    *present = count == 5;
    if (count != 0 && count != 5)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': the material inputs albedo, specular, material, transmission and attenuation go "
                       "together (a gbuffer pass's outputs); %d of 5 are connected", fg_pass_name(pass), count);
    return true;
}

fg_resource_desc
cgp_gather_declare_outputs(fg_pass *pass, fg_declare *decl, const fg_resource_desc *position)
{
    fg_resource_desc out = cgp_image_like(pass, position, GL_RGBA32F);
    fg_declare_output(decl, "radiance", &out, FG_ACCESS_IMAGE_STORE);
    if (fg_param_bool(pass, "specular"))
        fg_declare_output(decl, reflection_name, &out, FG_ACCESS_IMAGE_STORE);
    if (fg_param_bool(pass, "refraction"))
        fg_declare_output(decl, refraction_name, &out, FG_ACCESS_IMAGE_STORE);
    return out;
}

/* ---- the split-sum table (cgp_brdf_table_fill) */

void
cgp_brdf_table_fill(int size, float *rgba)
{
    /* The integrals are cg/bsdf.h's, the path tracer's BSDF: one definition of the lobes. */
    for (int i = 0; i < size; i++) {
        float nv = (float)i / (float)(size - 1), keep = 0.0f, c = 0.0f;
        cg_bsdf_diffuse_albedo_terms(nv, &keep, &c);
        for (int j = 0; j < size; j++) {
            float roughness = (float)j / (float)(size - 1), scale = 0.0f, bias = 0.0f;
            cg_bsdf_specular_albedo_terms(roughness * roughness, nv, &scale, &bias);
            float *t = &rgba[4 * ((size_t)j * (size_t)size + (size_t)i)];
            t[0] = scale;
            t[1] = bias;
            t[2] = c;
            t[3] = 1.0f;
        }
    }
}

void
cgp_brdf_hemispherical_fill(int size, float *rg)
{
    float *table = malloc(sizeof(float) * 4 * (size_t)size * (size_t)size);
    if (!table) {
        memset(rg, 0, sizeof(float) * 2 * (size_t)size);
        return;
    }
    cgp_brdf_table_fill(size, table);
    for (int j = 0; j < size; j++) {
        double a = 0.0, b = 0.0;
        /* The trapezoid rule over the columns, which lie at n.v = i / (size - 1). */
        for (int i = 0; i < size; i++) {
            const float *t = &table[4 * ((size_t)j * (size_t)size + (size_t)i)];
            double nv = (double)i / (double)(size - 1), w = (i == 0 || i == size - 1 ? 0.5 : 1.0) / (double)(size - 1);
            a += 2.0 * nv * (double)t[0] * w;
            b += 2.0 * nv * (double)t[1] * w;
        }
        rg[2 * j] = (float)a;
        rg[2 * j + 1] = (float)b;
    }
    free(table);
}

/* A table as a linearly filtered, edge-clamped float texture owned by `state`. */
static GLuint
table_texture(void *state, GLenum internal, GLenum format, int width, int height, const float *texels)
{
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, internal, width, height);
    glTextureSubImage2D(tex, 0, 0, 0, width, height, format, GL_FLOAT, texels);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return cgp_own(state, CGP_GL_TEXTURE, tex);
}

GLuint
cgp_brdf_hemispherical_texture(void *state)
{
    static float table[2 * CGP_BRDF_TABLE_SIZE];
    static bool made;
    if (!made) {
        cgp_brdf_hemispherical_fill(CGP_BRDF_TABLE_SIZE, table);
        made = true;
    }
    return table_texture(state, GL_RG32F, GL_RG, CGP_BRDF_TABLE_SIZE, 1, table);
}

GLuint
cgp_brdf_table_texture(void *state)
{
    static float table[4 * CGP_BRDF_TABLE_SIZE * CGP_BRDF_TABLE_SIZE];
    static bool made;
    if (!made) {
        cgp_brdf_table_fill(CGP_BRDF_TABLE_SIZE, table);
        made = true;
    }
    return table_texture(state, GL_RGBA32F, GL_RGBA, CGP_BRDF_TABLE_SIZE, CGP_BRDF_TABLE_SIZE, table);
}

void
cgp_gather_find_slots(const fg_pass *pass, cgp_gather_io io, cgp_gather_slots *out)
{
    *out = (cgp_gather_slots){.position = io.position, .normal = io.normal, .radiance = io.radiance};
    out->reflection = fg_pass_slot_if_declared(pass, reflection_name);
    out->refraction = fg_pass_slot_if_declared(pass, refraction_name);
    out->volume = fg_pass_slot(pass, volume_name);
    out->region = fg_pass_slot(pass, region_name);
    out->glossy = fg_pass_slot(pass, glossy_name);
    for (int d = 0; d < 6; d++)
        out->directions[d] = fg_pass_slot(pass, direction_names[d]);
    for (int d = 0; d < 2; d++)
        out->surface[d] = fg_pass_slot(pass, surface_names[d]);
    for (int i = 0; i < 5; i++)
        out->material[i] = fg_pass_slot(pass, material_names[i]);
}

bool
cgp_gather_prepare(void *state, const fg_pass *pass, cgp_gather *g, cgp_gather_io io, const char *shader,
                   const char *defines, size_t gather_bytes, cg_error *err)
{
    cgp_gather_find_slots(pass, io, &g->slots);
    g->model = cgp_gather_volume_model(pass, &g->slots);
    g->material = fg_slot_present(pass, g->slots.material[1]) && fg_slot_present(pass, g->slots.material[2]);
    char all[1024];
    snprintf(all, sizeof all, "%s%s%s%s", defines ? defines : "", cgp_gather_volume_define(g->model),
             g->material ? "#define CG_GATHER_MATERIAL\n" : "",
             fg_slot_present(pass, g->slots.glossy) ? "#define CG_GATHER_GLOSSY\n" : "");
    if (!cgp_cone_set_of_pass(pass, &g->set, err) || !cgp_compute_program(state, shader, all, &g->program, err))
        return false;
    g->volume_sampler = cgp_sampler_volume(state);
    g->one_level_sampler = cgp_sampler_volume_one_level(state);
    g->cone_block = cgp_uniform_buffer(state, sizeof(cg_cone_set_block));
    g->gather_block = cgp_uniform_buffer(state, gather_bytes);
    g->state = state;
    if (g->material)
        g->brdf_table = cgp_brdf_table_texture(state);
    cgp_sky_prepare(state, &g->sky);
    g->reads = cgp_reads_counter(state);
    return true;
}

bool
cgp_gather_begin(const fg_pass *pass, cgp_gather *g, const void *block, size_t gather_bytes, GLuint volume,
                 GLuint region, cg_error *err)
{
    if (!cgp_sky_update(g->state, &g->sky, fg_pass_frame(pass)->scene, err))
        return false;
    cgp_sky_bind(&g->sky);
    cgp_reads_begin(g->reads);
    glUseProgram(g->program);
    cgp_cone_upload(pass, &g->set, g->cone_block);
    cgp_uniform_upload(g->gather_block, CG_BINDING_GATHER, block, gather_bytes);
    glBindBufferBase(GL_UNIFORM_BUFFER, CG_BINDING_VOLUME, region);
    glBindTextureUnit(CG_UNIT_VOLUME, volume);
    glBindSampler(CG_UNIT_VOLUME, g->volume_sampler);
    if (volume)
        cgp_gather_bind_volume(pass, g, g->volume_sampler, false);
    if (volume && g->model == CGP_VOLUME_SURFACE) {
        glBindTextureUnit(CG_UNIT_OCCUPANCY, volume);
        glBindSampler(CG_UNIT_OCCUPANCY, g->one_level_sampler);
        /* The lobes' volume: its occupancy is `volume`'s (one geometry, voxel_light's glossy). */
        if (fg_slot_present(pass, g->slots.glossy)) {
            glBindTextureUnit(CG_UNIT_GLOSSY, fg_slot_texture(pass, g->slots.glossy));
            glBindSampler(CG_UNIT_GLOSSY, g->volume_sampler);
        }
    }
    glBindTextureUnit(CG_UNIT_POSITION, fg_slot_texture(pass, g->slots.position));
    glBindTextureUnit(CG_UNIT_NORMAL, fg_slot_texture(pass, g->slots.normal));
    if (g->material) {
        for (int i = 0; i < 5; i++)
            glBindTextureUnit(material_units[i], fg_slot_texture(pass, g->slots.material[i]));
        glBindTextureUnit(CG_UNIT_BRDF_TABLE, g->brdf_table);
    }
    glBindImageTexture(0, fg_slot_texture(pass, g->slots.radiance), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    /* The specular and refracted cones' outputs, at image units 1 and 4 in both gathers' shaders. */
    if (fg_slot_present(pass, g->slots.reflection))
        glBindImageTexture(1, fg_slot_texture(pass, g->slots.reflection), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    if (fg_slot_present(pass, g->slots.refraction))
        glBindImageTexture(4, fg_slot_texture(pass, g->slots.refraction), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    return true;
}

void
cgp_gather_dispatch(const fg_pass *pass, const cgp_gather *g)
{
    cgp_dispatch_over(pass, g->slots.radiance);
}

void
cgp_gather_end(fg_pass *pass, const cgp_gather *g)
{
    cgp_reads_end(pass, g->reads, "pixel");
    glBindSampler(CG_UNIT_VOLUME, 0);
    glBindSampler(CG_UNIT_OCCUPANCY, 0);
    glBindTextureUnit(CG_UNIT_OCCUPANCY, 0);
    glBindSampler(CG_UNIT_GLOSSY, 0);
    glBindTextureUnit(CG_UNIT_GLOSSY, 0);
    cgp_gather_bind_volume(pass, g, 0, true);
    cgp_sky_unbind();
    glUseProgram(0);
}

void
cgp_cone_frame(const float n[3], float t[3], float b[3])
{
    /* Duff et al. 2017, listing 3 (sign chosen as in shaders/common/cone_trace.glsl). */
    float sign = n[2] >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sign + n[2]);
    float bb = n[0] * n[1] * a;
    t[0] = 1.0f + sign * n[0] * n[0] * a;
    t[1] = sign * bb;
    t[2] = -sign * n[0];
    b[0] = bb;
    b[1] = sign + n[1] * n[1] * a;
    b[2] = -n[1];
}
