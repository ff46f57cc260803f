#version 450 core
// G-buffer of buildings and models: linear albedo (ambient occlusion 1) and the view-space
// normal (material 0: lit like the terrain by the shading pass), two-sided.
layout(location = 0) in vec3 vNormal;
layout(location = 1) in vec3 vColor;
layout(location = 2) in vec3 vView;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;

void main() {
    vec3 normal = normalize(vNormal);
    if (dot(normal, vView) > 0.0) {
        normal = -normal;  // open model surfaces seen from behind
    }
    outAlbedo = vec4(vColor, 1.0);
    outNormal = vec4(normal, 3.0);  // material 3: built object (shade.frag)
}
