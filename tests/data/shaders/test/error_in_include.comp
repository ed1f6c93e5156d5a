#version 450 core
#include "common/one.glsl"
#include "common/broken.glsl"
layout(local_size_x = 1) in;
void main() {}
