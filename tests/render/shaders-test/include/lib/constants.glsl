// Found next to include/lib/color.glsl.
const float kOne = 1.0;
