// Found through the shaders root (not next to include/lib/color.glsl).
const float kHalf = 0.5;
