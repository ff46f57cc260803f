#version 450 core
// Includes lib/color.glsl twice: the second one must be skipped.
#include "lib/color.glsl"
#include "lib/color.glsl"
layout(location = 0) out vec4 fragColor;
void main() { fragColor = vec4(helperColor(), 1.0); }
