#version 450 core
// The error is in broken_lib.glsl line 3; this file is fine.
layout(location = 0) out vec4 fragColor;
#include "broken_lib.glsl"
void main() { fragColor = vec4(broken()); }
