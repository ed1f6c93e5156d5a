#version 450 core
// Reads an input that fullscreen.vert does not write: a link error.
layout(location = 0) in vec3 never_written;
layout(location = 0) out vec4 colour;
void main() { colour = vec4(never_written, 1.0); }
