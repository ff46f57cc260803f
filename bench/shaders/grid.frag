#version 450 core
// Writes the same G-buffer targets as the terrain, so both passes cost the same per pixel.
layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;

void main() {
    outAlbedo = vec4(0.3, 0.35, 0.2, 1.0);
    outNormal = vec4(0.0, 0.0, 1.0, 0.0);
}
