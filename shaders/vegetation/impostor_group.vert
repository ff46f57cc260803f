#version 450 core
// A group impostor (seed 004 §3.5): the capture window of a tile's image, a quad in the
// plane through the tile centre that faced the capture viewpoint (ImpostorRenderer).

uniform mat4 uProjection;
uniform vec3 uCentre;  // view space, metres
uniform vec3 uRight;   // half-extent vectors of the window, view space
uniform vec3 uUp;

layout(location = 0) out vec2 vUv;
layout(location = 1) out vec3 vView;

void main() {
    const vec2 corners[6] = vec2[6](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0),
                                    vec2(-1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));
    vec2 c = corners[gl_VertexID];
    vec3 p = uCentre + uRight * c.x + uUp * c.y;
    vUv = c * 0.5 + 0.5;
    vView = p;
    gl_Position = uProjection * vec4(p, 1.0);
}
