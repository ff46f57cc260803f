// Colour helpers for include/main.frag.
#include "common.glsl"
#include "constants.glsl"
vec3 helperColor() { return vec3(kHalf, kOne, 0.0); }
