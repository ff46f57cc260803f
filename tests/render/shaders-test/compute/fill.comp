#version 450 core
// Writes (x, y, uValue, FILL_W) into every texel: the test checks layout, uniforms and defines.
#include "../common.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image2D uImage;
uniform float uValue;
void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(uImage)))) {
        return;
    }
    imageStore(uImage, texel, vec4(texel.x, texel.y, uValue + kHalf, FILL_W));
}
