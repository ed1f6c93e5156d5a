#version 450 core
#include "common/includes_missing.glsl"
layout(local_size_x = 1) in;
void main() {}
