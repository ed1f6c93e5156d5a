#include "common/cycle_b.glsl"
