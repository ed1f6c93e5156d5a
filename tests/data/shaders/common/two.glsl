#include "common/one.glsl"
float two() { return one() + one(); }
