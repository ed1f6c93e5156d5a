/* Whether a scene is lit, the default light, and skies written back as text
 * (core/scene/lighting.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cg/scene.h"
#include "test_support.h"

static void
what_lights_a_scene(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    /* A spot light; emissive walls and no light; neither. */
    assert_cg_ok(cg_scene_load("builtin:cornell", &s, &err), &err);
    assert_true(cg_scene_is_lit(&s));
    cg_scene_free(&s);
    assert_cg_ok(cg_scene_load("builtin:furnace", &s, &err), &err);
    assert_int_equal(s.light_count, 0);
    assert_true(cg_scene_is_lit(&s));
    cg_scene_free(&s);
    assert_cg_ok(cg_scene_load("builtin:furnace?radiance=0", &s, &err), &err);
    assert_false(cg_scene_is_lit(&s));
    /* A black sky lights nothing; a grey one does. */
    cg_sky sky;
    assert_cg_ok(cg_sky_parse("0", &sky, &err), &err);
    assert_true(cg_sky_is_black(&sky));
    assert_cg_ok(cg_scene_set_sky(&s, &sky, &err), &err);
    assert_false(cg_scene_is_lit(&s));
    assert_cg_ok(cg_sky_parse("0,0,0.1", &sky, &err), &err);
    assert_false(cg_sky_is_black(&sky));
    assert_cg_ok(cg_scene_set_sky(&s, &sky, &err), &err);
    assert_true(cg_scene_is_lit(&s));
    cg_scene_free(&s);
}

/* Emitters light a scene when their radiance x area over all the surfaces' area reaches 1% of
 * a white surface under the default sun: the furnace (a sphere of emitting walls) gives its
 * radiance itself; a furnace that faint is not lit, and a small emitter among large walls is
 * not, as ClearCoatTest's labels. */
static void
faint_emitters_do_not_light(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load("builtin:furnace?radiance=0.5", &s, &err), &err);
    assert_true(cg_scene_emits(&s));
    assert_float_equal(cg_scene_emitted_light(&s), 0.5, 1e-6);
    assert_true(cg_scene_is_lit(&s));
    cg_scene_free(&s);
    assert_cg_ok(cg_scene_load("builtin:furnace?radiance=0.009", &s, &err), &err);
    assert_true(cg_scene_emits(&s));
    assert_true(CG_EMITTERS_MIN_LIGHT > 0.009 && CG_EMITTERS_MIN_LIGHT < 0.0096);
    assert_false(cg_scene_is_lit(&s));
    /* The same walls at 0.5, and a second instance of the sphere, not emitting, 30 times its
     * size: the emitters' share of the area is 1/901. */
    s.materials[s.meshes[0].material].emissive_strength *= 0.5f / 0.009f;
    assert_true(cg_scene_is_lit(&s));
    /* Grown by hand as the loaders do (cg_scene_free frees these arrays). */
    s.materials = realloc(s.materials, sizeof *s.materials * (size_t)(s.material_count + 1));
    s.meshes = realloc(s.meshes, sizeof *s.meshes * (size_t)(s.mesh_count + 1));
    s.instances = realloc(s.instances, sizeof *s.instances * (size_t)(s.instance_count + 1));
    assert_true(s.materials && s.meshes && s.instances);
    cg_material *dark = &s.materials[s.material_count];
    *dark = s.materials[s.meshes[0].material];
    dark->emissive[0] = dark->emissive[1] = dark->emissive[2] = 0.0f;
    cg_mesh *copy = &s.meshes[s.mesh_count];
    *copy = s.meshes[0];
    size_t vb = sizeof(float) * 3 * copy->vertex_count, ib = sizeof(uint32_t) * copy->index_count;
    copy->positions = malloc(vb);
    copy->normals = malloc(vb);
    copy->indices = malloc(ib);
    copy->texcoords = NULL;
    copy->tangents = NULL;
    memcpy(copy->positions, s.meshes[0].positions, vb);
    memcpy(copy->normals, s.meshes[0].normals, vb);
    memcpy(copy->indices, s.meshes[0].indices, ib);
    copy->material = s.material_count++;
    cg_instance *big = &s.instances[s.instance_count];
    *big = s.instances[0];
    big->mesh = s.mesh_count++;
    s.instance_count++;
    for (int k = 0; k < 3; k++)
        big->world[5 * k] *= 30.0f;
    assert_float_equal(cg_scene_emitted_light(&s), 0.5 / 901.0, 1e-6);
    assert_false(cg_scene_is_lit(&s));
    cg_scene_free(&s);
}

static void
default_light(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load("builtin:furnace?radiance=0", &s, &err), &err);
    assert_cg_ok(cg_scene_add_default_sun(&s, &err), &err);
    assert_int_equal(s.light_count, 1);
    const cg_light *sun = &s.lights[0];
    assert_string_equal(sun->name, CG_DEFAULT_SUN_NAME);
    assert_int_equal(sun->type, CG_LIGHT_DIRECTIONAL);
    assert_true(sun->intensity == CG_DEFAULT_SUN_IRRADIANCE);
    /* Unit length, 55 degrees below the horizontal (it travels down), 30 degrees from -z
     * towards -x (it comes from +z, +x). */
    double len = sqrt(sun->direction[0] * sun->direction[0] + sun->direction[1] * sun->direction[1] +
                      sun->direction[2] * sun->direction[2]);
    assert_float_equal(len, 1.0, 1e-6);
    assert_float_equal(asin(-sun->direction[1]) * 180.0 / M_PI, 55.0, 1e-4);
    assert_float_equal(atan2(-sun->direction[0], -sun->direction[2]) * 180.0 / M_PI, 30.0, 1e-4);
    assert_true(cg_scene_is_lit(&s));
    assert_cg_ok(cg_scene_validate(&s, &err), &err);
    /* The default sky is grey and uniform, and a Preetham sky can follow the default sun. */
    cg_sky sky;
    cg_default_sky(&sky);
    assert_int_equal(sky.type, CG_SKY_UNIFORM);
    assert_true(sky.radiance[0] == CG_DEFAULT_SKY_RADIANCE && sky.radiance[2] == CG_DEFAULT_SKY_RADIANCE);
    assert_cg_ok(cg_sky_parse("preetham", &sky, &err), &err);
    assert_cg_ok(cg_scene_set_sky(&s, &sky, &err), &err);
    cg_scene_free(&s);
}

/* cg_sky_format writes what cg_sky_parse reads back to an equal sky. */
static void
sky_text_round_trip(void **state)
{
    (void)state;
    const char *texts[] = { "none", "0.2", "0.5,0.6,0.8", "preetham", "preetham:2.5", "preetham:7,0.03" };
    cg_error err = { 0 };
    for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++) {
        cg_sky a, b;
        char text[128];
        assert_cg_ok(cg_sky_parse(texts[i], &a, &err), &err);
        cg_sky_format(&a, text, sizeof text);
        assert_cg_ok(cg_sky_parse(text, &b, &err), &err);
        if (!cg_sky_equal(&a, &b))
            fail_msg("'%s' was written as '%s', which reads back otherwise", texts[i], text);
    }
    cg_sky a, b;
    assert_cg_ok(cg_sky_parse("0.2", &a, &err), &err);
    assert_cg_ok(cg_sky_parse("0.2,0.2,0.3", &b, &err), &err);
    assert_false(cg_sky_equal(&a, &b));
    assert_cg_ok(cg_sky_parse("preetham:3", &b, &err), &err);
    assert_false(cg_sky_equal(&a, &b));
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(what_lights_a_scene),
             cmocka_unit_test(faint_emitters_do_not_light),
             cmocka_unit_test(default_light),
             cmocka_unit_test(sky_text_round_trip))
