#version 450 core
// Single impostor fragment: the captured albedo (alpha = coverage, alpha-tested at 0.5),
// the captured normal turned into view space and the captured leaf depth (offset from
// the plane through the sphere centre along the capture direction) written as
// gl_FragDepth, so the impostor depth-tests and shades like the mesh (ImpostorRenderer).
// uWriteDistance (group capture): normal.w = the leaf's distance from the eye.

struct Impostor {
    vec4 centreRadius;
    vec4 right;
    vec4 up;
    vec4 toward;
    vec4 tint;
};
layout(std430, binding = 2) readonly buffer Impostors {
    Impostor impostors[];
};

layout(location = 0) in vec2 vUv;
layout(location = 1) in vec3 vView;
layout(location = 2) flat in int vIndex;

uniform sampler2DArray uAlbedo;  // linear RGB × coverage, alpha = coverage (mipmapped)
uniform sampler2DArray uNormal;  // capture-frame normal (nearest)
uniform sampler2DArray uDepth;   // orthographic capture depth, 0 = nothing (nearest)
uniform mat4 uProjection;
uniform bool uWriteDistance;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;

void main() {
    Impostor m = impostors[vIndex];
    vec3 coordinate = vec3(vUv, m.right.w);
    vec4 albedo = texture(uAlbedo, coordinate);
    if (albedo.a < 0.5) {
        discard;
    }
    float depth = texture(uDepth, coordinate).r;
    if (depth <= 0.0) {
        discard;
    }
    // Capture depth 1 is R toward the eye from the centre plane, 0 is R behind it.
    float offset = (2.0 * depth - 1.0) * m.centreRadius.w;
    vec3 p = vView + m.toward.xyz * offset;
    vec4 clip = uProjection * vec4(p, 1.0);
    gl_FragDepth = clip.z / clip.w;
    vec3 n = texture(uNormal, coordinate).xyz;
    vec3 normal = normalize(m.right.xyz * n.x + m.up.xyz * n.y + m.toward.xyz * n.z);
    if (dot(normal, p) > 0.0) {
        normal = -normal;
    }
    outAlbedo = vec4(albedo.rgb / albedo.a * m.tint.rgb, 1.0);
    outNormal = vec4(normal, uWriteDistance ? length(p) : 2.0);  // 2: leaves (shade.frag)
}
