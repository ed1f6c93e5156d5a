#version 450 core
// Passes each triangle through unchanged; lifts it to z = DEPTH for the depth-only test.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
void main() {
    for (int i = 0; i < 3; i++) {
        gl_Position = vec4(gl_in[i].gl_Position.xy, DEPTH, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
