#version 450 core
// Point sample fragment (seed 000 ch. 3): the pixel's view ray intersected with the
// sample's disc (a surfel: its plane through the centre, facing the normal); outside the
// radius, or edge-on, the fragment is discarded; depth from the hit (reversed-Z: near /
// distance along -z), so splats interpenetrate like the leaves they sample.

layout(location = 0) flat in vec4 vCenterRadius;
layout(location = 1) flat in vec3 vNormal;
layout(location = 2) flat in vec3 vColor;

uniform mat4 uProjection;
uniform vec2 uViewport;  // pixels
uniform float uNear;

layout(location = 0) out vec4 outAlbedo;  // rgb: linear albedo, a: ambient occlusion
layout(location = 1) out vec4 outNormal;  // xyz: view-space normal, w: material (0)

void main() {
    vec2 ndc = gl_FragCoord.xy / uViewport * 2.0 - 1.0;
    vec3 ray = vec3((ndc.x + uProjection[2][0]) / uProjection[0][0],
                    (ndc.y + uProjection[2][1]) / uProjection[1][1], -1.0);
    vec3 center = vCenterRadius.xyz;
    float across = dot(ray, vNormal);
    if (abs(across) < 1e-5 * length(ray)) {
        discard;
    }
    vec3 hit = ray * (dot(center, vNormal) / across);
    vec3 offset = hit - center;
    if (dot(offset, offset) > vCenterRadius.w * vCenterRadius.w || hit.z > -uNear) {
        discard;
    }
    gl_FragDepth = uNear / max(-hit.z, uNear);
    vec3 normal = across > 0.0 ? -vNormal : vNormal;
    outAlbedo = vec4(vColor, 1.0);
    outNormal = vec4(normal, 2.0);  // material 2: leaves (shade.frag)
}
