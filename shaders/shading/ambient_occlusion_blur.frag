#version 450 core
// Depth- and normal-aware 4 x 4 blur of the screen-space ambient occlusion
// (ambient_occlusion.frag): its slice/step pattern repeats every 4 x 4 pixels, so a box
// over the 4 x 4 block round a pixel averages every pattern phase once. Neighbours on
// another surface get no weight, so occlusion does not bleed over silhouettes: the sky,
// normals turned by more than ~35°, and points farther from the pixel's tangent plane than
// 1 % of its distance (a plane test, not a depth ratio: ground seen at a grazing angle
// changes depth by tens of percent per pixel yet is one surface).

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outOcclusion;

uniform sampler2D uOcclusion;  // raw, r
uniform sampler2D uNormal;
uniform sampler2D uDepth;        // reversed-Z
uniform vec2 uProjectionScale;   // projection[0][0], projection[1][1]
uniform vec2 uProjectionOffset;  // projection[2][0], projection[2][1]
uniform float uNear;             // metres

vec3 viewPosition(vec2 pixelCentre, float depth) {
    vec2 ndc = pixelCentre / vec2(textureSize(uDepth, 0)) * 2.0 - 1.0;
    float z = uNear / depth;
    return vec3((ndc + uProjectionOffset) / uProjectionScale * z, -z);
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(uDepth, 0);
    float depth = texelFetch(uDepth, pixel, 0).r;
    if (depth <= 0.0) {
        outOcclusion = vec4(1.0);
        return;
    }
    vec3 p = viewPosition(vec2(pixel) + 0.5, depth);
    vec3 normal = normalize(texelFetch(uNormal, pixel, 0).xyz);
    float tolerance = 0.01 * length(p);
    float sum = 0.0, weights = 0.0;
    for (int y = -2; y <= 1; ++y) {
        for (int x = -2; x <= 1; ++x) {
            ivec2 q = clamp(pixel + ivec2(x, y), ivec2(0), size - 1);
            float d = texelFetch(uDepth, q, 0).r;
            if (d <= 0.0) {
                continue;
            }
            float offPlane = abs(dot(viewPosition(vec2(q) + 0.5, d) - p, normal));
            float facing = dot(normalize(texelFetch(uNormal, q, 0).xyz), normal);
            float w = step(offPlane, tolerance) * step(0.82, facing);
            sum += w * texelFetch(uOcclusion, q, 0).r;
            weights += w;
        }
    }
    outOcclusion = vec4(weights > 0.0 ? sum / weights : texelFetch(uOcclusion, pixel, 0).r);
}
