/* The pass SDK (passes/sdk/): every block of shaders/common/blocks.h has, as GL lays it out for
 * GLSL, the size and member offsets of its C struct; a pass state deletes the GL objects it owns;
 * cgp_register_passes refuses a pass type of another ABI before registering any; cgp_mesh_bounds
 * transforms and filters as voxelize and heightmap_raster need; cgp_instances_changed sees every
 * change to the instances a filter keeps, and none to the others; cgp_lighting_changed tells the
 * lights from the shadow map and keeps the lights by value. */
#include <float.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/shader.h"
#include "sdk/blocks.h"
#include "sdk/instances.h"
#include "sdk/pass.h"
#include "sdk/scene.h"
#include "sdk/shadow.h"
#include "test_support.h"

static GLuint layout_program;

/* Property `prop` of the resource `name` of the layout program's `interface`; fails the test
 * when the program has no such active resource. */
static GLint
resource_property(GLenum interface, const char *name, GLenum prop)
{
    GLuint index = glGetProgramResourceIndex(layout_program, interface, name);
    if (index == GL_INVALID_INDEX)
        fail_msg("%s: not active in the program", name);
    GLint value = -1;
    glGetProgramResourceiv(layout_program, interface, index, 1, &prop, 1, NULL, &value);
    return value;
}

/* GL's offset of `member` in block `block` (interface: GL_UNIFORM or GL_BUFFER_VARIABLE). */
static GLint
member_offset(GLenum interface, const char *block, const char *member)
{
    char name[256];
    snprintf(name, sizeof name, "%s.%s", block, member);
    return resource_property(interface, name, GL_OFFSET);
}

/* GL's size of block `block` (interface: GL_UNIFORM_BLOCK or GL_SHADER_STORAGE_BLOCK). */
static GLint
block_size(GLenum interface, const char *block)
{
    return resource_property(interface, block, GL_BUFFER_DATA_SIZE);
}

/* One check per member, expanded from the block's member list: C offsetof against GL_OFFSET. */
#define CHECK_MEMBER(type, name) check(#name, offsetof(BLOCK_TYPE, name));
#define CHECK_ARRAY(type, name, count) check(#name "[0]", offsetof(BLOCK_TYPE, name));

#define CHECK_BLOCK(glsl, c_type, MEMBERS, block_interface, member_interface)                              \
    do {                                                                                                  \
        typedef c_type BLOCK_TYPE;                                                                        \
        const char *block = glsl;                                                                         \
        GLenum interface = member_interface;                                                              \
        (void)block, (void)interface;                                                                     \
        MEMBERS(CHECK_MEMBER, CHECK_ARRAY)                                                                \
        GLint gl_size = block_size(block_interface, glsl);                                                \
        print_message("# %s: C %zu bytes, GL %d\n", glsl, sizeof(c_type), gl_size);                     \
        assert_int_equal(gl_size, sizeof(c_type));                                                        \
    } while (0)

#define check(member, c_offset)                                                                           \
    do {                                                                                                  \
        GLint gl_offset = member_offset(interface, block, member);                                        \
        if (gl_offset != (GLint)(c_offset))                                                               \
            fail_msg("%s.%s: GL offset %d, C offset %zu", block, member, gl_offset, (size_t)(c_offset));  \
    } while (0);

static void
blocks_have_the_c_layout_in_glsl(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    cg_error err = {0};
    assert_cg_ok(cg_program_compute(cg_test_data_path("shaders/blocks_layout.comp"), NULL, &layout_program, &err),
                 &err);
    CHECK_BLOCK("CgShadow", cg_shadow_block, CG_SHADOW_BLOCK, GL_UNIFORM_BLOCK, GL_UNIFORM);
    CHECK_BLOCK("CgVolumeBlock", cg_volume_block, CG_VOLUME_BLOCK, GL_UNIFORM_BLOCK, GL_UNIFORM);
    CHECK_BLOCK("CgHeightmapBlock", cg_heightmap_block, CG_HEIGHTMAP_BLOCK, GL_UNIFORM_BLOCK, GL_UNIFORM);
    CHECK_BLOCK("CgConeSet", cg_cone_set_block, CG_CONE_SET_BLOCK, GL_UNIFORM_BLOCK, GL_UNIFORM);
    CHECK_BLOCK("CgConeGather", cg_cone_gather_block, CG_CONE_GATHER_BLOCK, GL_UNIFORM_BLOCK, GL_UNIFORM);
    CHECK_BLOCK("CgHybridGather", cg_hybrid_gather_block, CG_HYBRID_GATHER_BLOCK, GL_UNIFORM_BLOCK, GL_UNIFORM);
    CHECK_BLOCK("CgSkyBlock", cg_sky_block, CG_SKY_BLOCK, GL_UNIFORM_BLOCK, GL_UNIFORM);
    CHECK_BLOCK("CgHsatInfo", cg_hsat_info_block, CG_HSAT_INFO_BLOCK, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE);
    glDeleteProgram(layout_program);
    assert_no_gl_errors(ctx);
}

typedef struct owner_state {
    GLuint program, framebuffer, buffer;
    int *cleaned;
} owner_state;

static void
count_cleanup(void *state)
{
    ++*((owner_state *)state)->cleaned;
}

static void
state_deletes_what_it_owns(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    cg_error err = {0};
    owner_state *s = cgp_state_new(NULL, sizeof *s, &err);
    assert_non_null(s);
    int cleaned = 0;
    s->cleaned = &cleaned;
    cgp_state_on_destroy(s, count_cleanup);
    assert_cg_ok(cgp_compute_program(s, "mip2d/downsample.comp", "#define FORMAT rgba16f\n", &s->program, &err), &err);
    s->framebuffer = cgp_framebuffer(s);
    s->buffer = cgp_buffer(s, 64, NULL, 0);
    assert_true(glIsProgram(s->program));
    /* Names of this context are not reused while the test runs: deleted ones stay deleted. */
    GLuint program = s->program, framebuffer = s->framebuffer, buffer = s->buffer;
    cgp_state_destroy(s);
    assert_int_equal(cleaned, 1);
    assert_false(glIsProgram(program));
    assert_false(glIsFramebuffer(framebuffer));
    assert_false(glIsBuffer(buffer));
    cgp_state_destroy(NULL);
    /* A failing prepare: cgp_prepared destroys the state and leaves *state alone. */
    void *kept = &cleaned;
    owner_state *t = cgp_state_new(NULL, sizeof *t, &err);
    t->buffer = cgp_buffer(t, 16, NULL, 0);
    GLuint doomed = t->buffer;
    assert_false(cgp_prepared(&kept, t, false));
    assert_ptr_equal(kept, &cleaned);
    assert_false(glIsBuffer(doomed));
    assert_no_gl_errors(ctx);
}

static bool
declare_nothing(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    (void)pass, (void)err;
    fg_declare_nothing_to_do(decl, "test");
    return true;
}

static bool
execute_nothing(fg_pass *pass, void *state, cg_error *err)
{
    (void)pass, (void)state, (void)err;
    return true;
}

static void
registration_checks_the_abi_first(void **state)
{
    (void)state;
    static const fg_pass_type current = {.abi_version = FG_ABI_VERSION, .name = "sdk_current", .doc = "test",
                                         .declare = declare_nothing, .execute = execute_nothing};
    static const fg_pass_type other = {.abi_version = FG_ABI_VERSION + 1u, .name = "sdk_other", .doc = "test",
                                       .declare = declare_nothing, .execute = execute_nothing};
    const fg_pass_type *const both[] = {&current, &other};
    fg_registry *registry = fg_registry_create();
    cg_error err = {0};
    /* The second type's ABI is wrong: neither is registered. */
    assert_cg_status(cgp_register_passes(registry, FG_ABI_VERSION, both, 2, &err), &err, CG_ERR_PLUGIN_ABI);
    assert_non_null(strstr(err.message, "sdk_other"));
    assert_int_equal(fg_registry_count(registry), 0);
    /* A host of another ABI refuses every type. */
    assert_cg_status(cgp_register_passes(registry, FG_ABI_VERSION + 1u, both, 1, &err), &err, CG_ERR_PLUGIN_ABI);
    assert_cg_ok(cgp_register_passes(registry, FG_ABI_VERSION, both, 1, &err), &err);
    assert_non_null(fg_registry_find(registry, "sdk_current"));
    fg_registry_destroy(registry);
}

static void
mesh_bounds_of_a_subset(void **state)
{
    (void)state;
    cg_scene scene;
    cg_error err = {0};
    /* The furnace with its floor a height field: the floor alone, the box alone, both. */
    assert_cg_ok(cg_scene_load("builtin:furnace?heightfield=1&scale=2", &scene, &err), &err);
    double lo[3], hi[3];
    assert_true(cgp_mesh_bounds(&scene, CG_MESHES_HEIGHTFIELD, lo, hi));
    const double floor_lo[3] = {-1, -1, -1}, floor_hi[3] = {1, -1, 1};
    for (int k = 0; k < 3; k++) {
        assert_float_equal(lo[k], floor_lo[k], 1e-6);
        assert_float_equal(hi[k], floor_hi[k], 1e-6);
    }
    assert_true(cgp_mesh_bounds(&scene, CG_MESHES_COMPLEX, lo, hi));
    assert_true(cgp_mesh_bounds(&scene, CG_MESHES_ALL, lo, hi));
    for (int k = 0; k < 3; k++) {
        assert_float_equal(lo[k], -1, 1e-6);
        assert_float_equal(hi[k], 1, 1e-6);
    }
    cg_scene_free(&scene);
    /* No mesh passes: false, and the bounds say empty. */
    assert_cg_ok(cg_scene_load("builtin:furnace", &scene, &err), &err);
    assert_false(cgp_mesh_bounds(&scene, CG_MESHES_HEIGHTFIELD, lo, hi));
    assert_true(lo[0] == DBL_MAX && hi[0] == -DBL_MAX);
    cg_scene_free(&scene);
}

static void
instances_changed_by_filter(void **state)
{
    (void)state;
    cg_scene scene;
    cg_error err = {0};
    /* The furnace with its floor a height field: a change to the box is a change for the complex
     * filter only. The GPU scene is only compared (its generation), so a struct stands for it. */
    assert_cg_ok(cg_scene_load("builtin:furnace?heightfield=1&scale=2", &scene, &err), &err);
    cg_gpu_scene gpu = {.scene = &scene, .generation = 7};
    fg_frame frame = {.scene = &scene, .gpu_scene = &gpu};
    cgp_instance_record complex = {0}, heightfield = {0};
    assert_string_equal(cgp_instances_changed(&complex, &frame, CG_MESHES_COMPLEX, "moved"), "first frame");
    assert_cg_ok(cgp_instances_remember(&complex, &frame, CG_MESHES_COMPLEX, &err), &err);
    assert_cg_ok(cgp_instances_remember(&heightfield, &frame, CG_MESHES_HEIGHTFIELD, &err), &err);
    assert_null(cgp_instances_changed(&complex, &frame, CG_MESHES_COMPLEX, "moved"));
    assert_null(cgp_instances_changed(&heightfield, &frame, CG_MESHES_HEIGHTFIELD, "moved"));
    /* Another filter than recorded is a change. */
    assert_non_null(cgp_instances_changed(&complex, &frame, CG_MESHES_ALL, "moved"));
    int box = -1;
    for (int i = 0; i < scene.instance_count && box < 0; i++)
        if (scene.meshes[scene.instances[i].mesh].kind == CG_MESH_COMPLEX)
            box = i;
    assert_true(box >= 0);
    /* A world changed by hand, without a new revision: seen, by value. */
    scene.instances[box].world[12] += 0.5f;
    assert_string_equal(cgp_instances_changed(&complex, &frame, CG_MESHES_COMPLEX, "moved"), "moved");
    assert_null(cgp_instances_changed(&heightfield, &frame, CG_MESHES_HEIGHTFIELD, "moved"));
    scene.instances[box].world[12] -= 0.5f;
    assert_null(cgp_instances_changed(&complex, &frame, CG_MESHES_COMPLEX, "moved"));
    /* Its material's albedo. */
    int material = scene.meshes[scene.instances[box].mesh].material;
    scene.materials[material].base_color[0] *= 0.5f;
    assert_string_equal(cgp_instances_changed(&complex, &frame, CG_MESHES_COMPLEX, "moved"), "moved");
    scene.materials[material].base_color[0] *= 2.0f;
    /* Another upload. */
    gpu.generation = 8;
    assert_string_equal(cgp_instances_changed(&complex, &frame, CG_MESHES_COMPLEX, "moved"), "scene uploaded again");
    cgp_instance_record_free(&complex);
    cgp_instance_record_free(&heightfield);
    assert_string_equal(cgp_instances_changed(&complex, &frame, CG_MESHES_COMPLEX, "moved"), "first frame");
    cg_scene_free(&scene);
}

/* The lighting record (sdk/shadow.h) that voxel_light and heightmap_raster keep: nothing recorded
 * is a change of the lights; the lights are compared by value and kept by value (the scene's array
 * may change or go after cgp_lighting_remember); a shadow map's objects or matrix block alone is
 * CGP_LIGHTING_SHADOW; the lights win when both changed. */
static void
lighting_record_tells_lights_from_shadow(void **state)
{
    (void)state;
    cg_error err = {0};
    cg_light lights[2];
    memset(lights, 0, sizeof lights);
    cg_default_sun(&lights[0]);
    cg_default_sun(&lights[1]);
    lights[1].intensity = 1.0f;
    cgp_lighting_record now = {.taken = true, .lights = lights, .light_count = 2, .shadow_objects = {3, 4}};
    now.shadow_block[0] = 1;
    cgp_lighting_record kept = {0};
    assert_int_equal(cgp_lighting_changed(&kept, &now), CGP_LIGHTING_LIGHTS);
    assert_cg_ok(cgp_lighting_remember(&kept, &now, &err), &err);
    assert_int_equal(cgp_lighting_changed(&kept, &now), CGP_LIGHTING_SAME);
    /* Kept by value: the record does not follow the scene's array. */
    assert_ptr_not_equal(kept.lights, lights);
    lights[1].intensity = 2.0f;
    assert_int_equal(cgp_lighting_changed(&kept, &now), CGP_LIGHTING_LIGHTS);
    lights[1].intensity = 1.0f;
    now.light_count = 1;
    assert_int_equal(cgp_lighting_changed(&kept, &now), CGP_LIGHTING_LIGHTS);
    now.light_count = 2;
    /* The shadow map alone: its matrix block, its objects. */
    now.shadow_block[255] = 9;
    assert_int_equal(cgp_lighting_changed(&kept, &now), CGP_LIGHTING_SHADOW);
    lights[0].direction[0] += 0.1f;
    assert_int_equal(cgp_lighting_changed(&kept, &now), CGP_LIGHTING_LIGHTS);
    lights[0].direction[0] -= 0.1f;
    now.shadow_block[255] = 0;
    now.shadow_objects[1] = 5;
    assert_int_equal(cgp_lighting_changed(&kept, &now), CGP_LIGHTING_SHADOW);
    /* Remembered again with fewer lights, then none. */
    now.light_count = 1;
    assert_cg_ok(cgp_lighting_remember(&kept, &now, &err), &err);
    assert_int_equal(cgp_lighting_changed(&kept, &now), CGP_LIGHTING_SAME);
    now.light_count = 0;
    now.lights = NULL;
    assert_int_equal(cgp_lighting_changed(&kept, &now), CGP_LIGHTING_LIGHTS);
    assert_cg_ok(cgp_lighting_remember(&kept, &now, &err), &err);
    assert_int_equal(cgp_lighting_changed(&kept, &now), CGP_LIGHTING_SAME);
    cgp_lighting_record_free(&kept);
    assert_int_equal(cgp_lighting_changed(&kept, &now), CGP_LIGHTING_LIGHTS);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(blocks_have_the_c_layout_in_glsl),
             cmocka_unit_test(state_deletes_what_it_owns),
             cmocka_unit_test(registration_checks_the_abi_first),
             cmocka_unit_test(mesh_bounds_of_a_subset),
             cmocka_unit_test(instances_changed_by_filter),
             cmocka_unit_test(lighting_record_tells_lights_from_shadow))
