#version 450 core
// Single view-direction impostors (seed 004 §3.2): a quad perpendicular to the chosen
// capture view, covering the plant's bounding sphere, in view space (ImpostorRenderer).

struct Impostor {
    vec4 centreRadius;  // view-space sphere centre; w: model radius (metres)
    vec4 right;         // capture right × instance scale; w: view layer
    vec4 up;            // capture up × instance scale
    vec4 toward;        // capture toward-eye × instance scale
    vec4 tint;
};
layout(std430, binding = 2) readonly buffer Impostors {
    Impostor impostors[];
};

uniform mat4 uProjection;
uniform int uFirst;

layout(location = 0) out vec2 vUv;
layout(location = 1) out vec3 vView;
layout(location = 2) flat out int vIndex;

void main() {
    const vec2 corners[6] = vec2[6](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0),
                                    vec2(-1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));
    int index = uFirst + gl_InstanceID;
    Impostor m = impostors[index];
    vec2 c = corners[gl_VertexID];
    vec3 p = m.centreRadius.xyz + (m.right.xyz * c.x + m.up.xyz * c.y) * m.centreRadius.w;
    vUv = c * 0.5 + 0.5;
    vView = p;
    vIndex = index;
    gl_Position = uProjection * vec4(p, 1.0);
}
