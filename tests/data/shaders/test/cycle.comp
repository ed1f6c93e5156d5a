#version 450 core
#include "common/cycle_a.glsl"
layout(local_size_x = 1) in;
void main() {}
