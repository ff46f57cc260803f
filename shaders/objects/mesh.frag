#version 450 core
// G-buffer of buildings and models: linear albedo (ambient occlusion 1) and the view-space
// normal (material 3: built object, lit by the shading pass), two-sided. Textured parts
// multiply the vertex colour (glTF's baseColorFactor) by the base colour texture: an
// sRGB8 texture, so the sampled value is linear; mipmapped (trilinear) against aliasing.
layout(location = 0) in vec3 vNormal;
layout(location = 1) in vec3 vColor;
layout(location = 2) in vec3 vView;
layout(location = 3) in vec2 vUv;

layout(binding = 0) uniform sampler2D uBaseColor;
uniform int uTextured;  // 1: the part has a base colour texture bound to unit 0

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;

void main() {
    vec3 normal = normalize(vNormal);
    if (dot(normal, vView) > 0.0) {
        normal = -normal;  // open model surfaces seen from behind
    }
    vec3 albedo = vColor;
    if (uTextured != 0) {
        albedo *= texture(uBaseColor, vUv).rgb;
    }
    outAlbedo = vec4(albedo, 1.0);
    outNormal = vec4(normal, 3.0);  // material 3: built object (shade.frag)
}
