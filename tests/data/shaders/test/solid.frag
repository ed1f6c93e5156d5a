#version 450 core
#include "common/two.glsl"
layout(location = 0) out vec4 colour;
void main() { colour = vec4(0.25 * one(), 0.25 * two(), RED, 1.0); }
