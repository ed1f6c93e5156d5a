/* The demo's animation clock and the sun key's turn: see demo_anim.h. */
#include "demo_anim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void
demo_clock_init(demo_clock *c, bool animated, double start, double end, double time, double fps, bool play)
{
    *c = (demo_clock){ .animated = animated, .start = start, .end = end, .fps = fps > 0 ? fps : 0,
                       .playing = animated && play, .origin = time };
}

double
demo_clock_time(const demo_clock *c)
{
    /* As render computes frame k's time (T + k / F): the same double. */
    return c->fps > 0 ? c->origin + c->frames / c->fps : c->origin;
}

double
demo_clock_frame_seconds(const demo_clock *c)
{
    return 1.0 / (c->fps > 0 ? c->fps : DEMO_CLOCK_DEFAULT_FPS);
}

/* The clock at t, counting frames from there. */
static void
restart_at(demo_clock *c, double t)
{
    c->origin = t;
    c->frames = 0;
}

bool
demo_clock_tick(demo_clock *c, double wall_seconds)
{
    if (!c->playing)
        return false;
    double before = demo_clock_time(c);
    if (c->fps > 0)
        c->frames++;
    else
        c->origin += wall_seconds > 0 ? wall_seconds : 0;
    double t = demo_clock_time(c);
    if (c->end > c->start && t > c->end)
        restart_at(c, c->start + fmod(t - c->start, c->end - c->start));
    return demo_clock_time(c) != before;
}

bool
demo_clock_toggle(demo_clock *c)
{
    if (!c->animated)
        return false;
    c->playing = !c->playing;
    return true;
}

/* Within the animation's keys: outside them the pose holds the first or last one anyway. */
static void
keep_within(demo_clock *c)
{
    double t = demo_clock_time(c);
    if (t < c->start)
        restart_at(c, c->start);
    else if (t > c->end)
        restart_at(c, c->end);
}

void
demo_clock_step(demo_clock *c, int frames)
{
    if (!c->animated)
        return;
    c->playing = false;
    if (c->fps > 0)
        c->frames += frames;
    else
        c->origin += frames / DEMO_CLOCK_DEFAULT_FPS;
    keep_within(c);
}

void
demo_clock_seek(demo_clock *c, double t)
{
    if (!c->animated || !isfinite(t))
        return;
    c->playing = false;
    restart_at(c, t);
    keep_within(c);
}

/* ------------------------------------------------------------ the sun key */

bool
demo_sun_init(demo_sun *sun, const cg_scene *scene, cg_error *err)
{
    memset(sun, 0, sizeof *sun);
    if (scene->light_count == 0)
        return true;
    sun->base = malloc(sizeof *sun->base * (size_t)scene->light_count);
    if (!sun->base)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "sun: %d lights", scene->light_count);
    sun->count = scene->light_count;
    for (int i = 0; i < sun->count; i++) {
        memcpy(sun->base[i], scene->lights[i].direction, sizeof sun->base[i]);
        sun->any |= scene->lights[i].type == CG_LIGHT_DIRECTIONAL;
    }
    return true;
}

void
demo_sun_free(demo_sun *sun)
{
    free(sun->base);
    memset(sun, 0, sizeof *sun);
}

void
demo_sun_advance(demo_sun *sun, double seconds)
{
    if (!sun->moving || !(seconds > 0))
        return;
    /* Kept within one turn, so that the angle keeps its precision however long it runs. */
    sun->angle = fmod(sun->angle + seconds * DEMO_SUN_DEGREES_PER_SECOND * M_PI / 180.0, 2.0 * M_PI);
}

void
demo_sun_reset(demo_sun *sun)
{
    sun->angle = 0;
    sun->moving = false;
}

static int
light_count(const demo_sun *sun, const cg_scene *scene)
{
    return sun->count < scene->light_count ? sun->count : scene->light_count;
}

void
demo_sun_unturn(const demo_sun *sun, cg_scene *scene)
{
    for (int i = 0; i < light_count(sun, scene); i++)
        memcpy(scene->lights[i].direction, sun->base[i], sizeof sun->base[i]);
}

bool
demo_sun_turn(demo_sun *sun, cg_scene *scene, bool posed)
{
    double c = cos(sun->angle), s = sin(sun->angle);
    for (int i = 0; i < light_count(sun, scene); i++) {
        cg_light *l = &scene->lights[i];
        memcpy(sun->base[i], l->direction, sizeof sun->base[i]);
        if (l->type != CG_LIGHT_DIRECTIONAL || sun->angle == 0)
            continue;
        /* About world +y (right-handed, as a glTF rotation about +y turns): the elevation stays. */
        double x = sun->base[i][0], z = sun->base[i][2];
        l->direction[0] = (float)(c * x + s * z);
        l->direction[2] = (float)(-s * x + c * z);
    }
    /* The pose gave the GPU scene the lights unturned; a new angle is not there either. */
    bool stale = sun->any && (sun->angle != sun->applied || (posed && sun->angle != 0));
    sun->applied = sun->angle;
    return stale;
}
