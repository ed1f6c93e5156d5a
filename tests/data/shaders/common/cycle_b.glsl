// cycle_b.glsl includes cycle_a.glsl, which includes cycle_b.glsl.
#include "common/cycle_a.glsl"
