/* apps/demo/demo_anim.h: the demo's animation clock and the sun key's turn, kept apart from
 * the window so that they are tested without one (tests/test_demo.c).
 *
 * The clock holds the time the scene is posed at (app_session_set_time, every frame), playing
 * or paused. Playing moves it on every frame by the frame's wall time, or with --fps F by
 * exactly 1/F: then frame k of a run from --time T is posed at T + k / F, the time
 * `conegraph render --time T --fps F` poses its frame k at (computed the same way, so the
 * same double). Past the animation's last key it starts again from its first (render holds
 * the last pose instead; the demo loops so that it can be watched). Space plays and pauses;
 * [ and ] and the UI's slider scrub: they pause and move the time, within the animation's
 * first and last key.
 *
 * The sun key (L) turns every directional light about world +y at 20 degrees per second on
 * top of what the animation does: the lights' directions as the scene has them (posed by the
 * animation when a light is animated, as loaded otherwise) are the base, and the lights hold
 * the base turned by the key's angle. Before each pose the lights go back to their base, so
 * that the animation compares its pose with its own last one and reports no change when the
 * time did not change; after it the angle is applied again. A change of either bumps the
 * scene's light stamp (cg_scene_lights_changed), so that passes that cache on it (the path
 * tracer) see the move, and goes to the GPU scene.
 *
 * Declares: demo_clock, demo_clock_init, demo_clock_time, demo_clock_frame_seconds,
 *           demo_clock_tick, demo_clock_toggle, demo_clock_step, demo_clock_seek,
 *           DEMO_SUN_DEGREES_PER_SECOND, demo_sun, demo_sun_init, demo_sun_free,
 *           demo_sun_advance, demo_sun_reset, demo_sun_unturn, demo_sun_turn.
 */
#ifndef CONEGRAPH_DEMO_ANIM_H
#define CONEGRAPH_DEMO_ANIM_H

#include <stdbool.h>

#include "cg/error.h"
#include "cg/scene.h"

/* The scrub step without --fps: one frame at render's default --fps 30. */
#define DEMO_CLOCK_DEFAULT_FPS 30.0

typedef struct demo_clock {
    bool animated;          /* cg_scene_is_animated: without animation the clock never moves */
    double start, end;      /* the first and last key time (cg_scene_animation_range) */
    double fps;             /* --fps: > 0 a fixed step of 1/fps a frame; 0: the frame's wall time */
    bool playing;
    /* The time: origin + frames / fps with --fps (exactly T + k / F), else origin. */
    double origin;
    long frames;
} demo_clock;

/* A clock at `time` seconds for a scene animated over start..end (animated false: never
 * moves, never plays); fps 0 for wall time. */
void demo_clock_init(demo_clock *c, bool animated, double start, double end, double time, double fps, bool play);
/* The time the scene is to be posed at. */
double demo_clock_time(const demo_clock *c);
/* One scrub step: 1/fps, or 1/DEMO_CLOCK_DEFAULT_FPS without --fps. */
double demo_clock_frame_seconds(const demo_clock *c);
/* The next frame (not the first): a playing clock moves on by 1/fps (fixed step) or by
 * `wall_seconds`, the time since the last frame, starting again from `start` once past `end`.
 * Returns whether the time changed. */
bool demo_clock_tick(demo_clock *c, double wall_seconds);
/* Space: plays a paused clock, pauses a playing one; false (nothing done) without animation. */
bool demo_clock_toggle(demo_clock *c);
/* [ and ] (10 frames with Shift): pauses and moves the time by `frames` scrub steps, kept
 * within start..end. */
void demo_clock_step(demo_clock *c, int frames);
/* The UI's slider: pauses at t, kept within start..end. */
void demo_clock_seek(demo_clock *c, double t);

#define DEMO_SUN_DEGREES_PER_SECOND 20.0

typedef struct demo_sun {
    float (*base)[3];       /* [count]: each light's direction as the scene has it */
    int count;              /* the scene's light count when made */
    double angle;           /* radians about world +y the key has turned the directional lights */
    double applied;         /* the angle the lights were last turned by */
    bool moving;            /* L: the angle grows every frame */
    bool any;               /* the scene has a directional light to turn */
} demo_sun;

/* Takes the scene's light directions as the base (after the scene's lighting is settled:
 * the default sun is one of them). Fails only out of memory. */
bool demo_sun_init(demo_sun *sun, const cg_scene *scene, cg_error *err);
void demo_sun_free(demo_sun *sun);
/* A frame went by: a moving sun turns by `seconds` at DEMO_SUN_DEGREES_PER_SECOND. */
void demo_sun_advance(demo_sun *sun, double seconds);
/* Shift+L: the key's turn undone (the sun where the scene, animated or not, has it), stopped. */
void demo_sun_reset(demo_sun *sun);
/* Before posing the scene: the lights back at their base directions. */
void demo_sun_unturn(const demo_sun *sun, cg_scene *scene);
/* After posing (`posed`: the pose changed a light, so that the GPU scene was given the lights
 * unturned): the lights' directions become the base and the directional ones are turned by the
 * angle. Returns whether the lights now differ from what the GPU scene holds: then the caller
 * calls cg_scene_lights_changed and cg_gpu_scene_update_lights. */
bool demo_sun_turn(demo_sun *sun, cg_scene *scene, bool posed);

#endif
