#version 450 core
layout(local_size_x = 1) in;

#include "common/does_not_exist.glsl"
void main() {}
