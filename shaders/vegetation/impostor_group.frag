#version 450 core
// Group impostor fragment: the tile image's albedo (alpha-tested), its normal from the
// capture frame into view space, and its depth re-projected: the texel stores the leaf's
// distance along the ray from the capture viewpoint, so the leaf is at viewpoint +
// distance × direction(window point − viewpoint) — exact from the capture viewpoint,
// within the validity test's parallax bound elsewhere.

layout(location = 0) in vec2 vUv;
layout(location = 1) in vec3 vView;

uniform sampler2D uAlbedo;  // linear RGB, alpha = coverage
uniform sampler2D uNormal;  // capture-frame normal; w: distance from the capture viewpoint
uniform mat4 uProjection;
uniform vec3 uViewpoint;  // capture viewpoint, view space
uniform mat3 uCaptureToView;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;

void main() {
    vec4 albedo = texture(uAlbedo, vUv);
    if (albedo.a < 0.5) {
        discard;
    }
    vec4 normalDistance = texture(uNormal, vUv);
    if (normalDistance.w <= 0.0) {
        discard;
    }
    vec3 p = uViewpoint + normalize(vView - uViewpoint) * normalDistance.w;
    vec4 clip = uProjection * vec4(p, 1.0);
    gl_FragDepth = clip.z / clip.w;
    vec3 normal = normalize(uCaptureToView * normalDistance.xyz);
    if (dot(normal, p) > 0.0) {
        normal = -normal;
    }
    outAlbedo = vec4(albedo.rgb / albedo.a, 1.0);
    outNormal = vec4(normal, 2.0);  // material 2: leaves (shade.frag)
}
