#version 450 core
/* Includes two.glsl, which includes one.glsl; the second include of one.glsl expands to nothing.
#include "common/does_not_exist.glsl" is inside this comment and left alone. */
#include "common/two.glsl"
#include "common/one.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { float value[]; };
void main() { value[gl_GlobalInvocationID.x] = two() + float(VALUE) + float(gl_GlobalInvocationID.x); }
