#version 450 core
// Buildings and placed models (render/objects/MeshRenderer): triangles with a per-instance
// affine transform into view (or light) space, formed on the CPU in double precision
// relative to the eye, so positions keep millimetres at any distance from the origin.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec4 aColor;  // sRGB8, normalised
layout(location = 3) in vec4 aRow0;   // rows of the 3×4 model → view transform
layout(location = 4) in vec4 aRow1;
layout(location = 5) in vec4 aRow2;
layout(location = 6) in vec2 aUv;     // base colour texture coordinates (glTF: v down)

uniform mat4 uProjection;

layout(location = 0) out vec3 vNormal;
layout(location = 1) out vec3 vColor;
layout(location = 2) out vec3 vView;
layout(location = 3) out vec2 vUv;

vec3 srgbToLinear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}

void main() {
    vec4 p = vec4(aPosition, 1.0);
    vec3 view = vec3(dot(aRow0, p), dot(aRow1, p), dot(aRow2, p));
    mat3 linear = transpose(mat3(aRow0.xyz, aRow1.xyz, aRow2.xyz));
    vNormal = linear * aNormal;  // uniform scale: no inverse transpose needed
    vColor = srgbToLinear(aColor.rgb);
    vView = view;
    vUv = aUv;
    gl_Position = uProjection * vec4(view, 1.0);
}
