#version 450 core
#include "common/two.glsl"
layout(local_size_x = 1) in;
void main() {
    float x = two() + not_declared_here;
}
