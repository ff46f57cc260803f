#version 450 core
// Full-screen triangle without vertex buffers: draw 3 vertices with an empty VAO.
// vUv is (0,0) at the bottom-left and (1,1) at the top-right of the viewport.

layout(location = 0) out vec2 vUv;

void main() {
    vec2 position = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    vUv = position;
    gl_Position = vec4(position * 2.0 - 1.0, 0.0, 1.0);
}
