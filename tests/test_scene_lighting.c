/* Whether a scene is lit, the default light, and skies written back as text
 * (core/scene/lighting.c). */
#include <math.h>
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

int
main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(what_lights_a_scene),
        cmocka_unit_test(default_light),
        cmocka_unit_test(sky_text_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
