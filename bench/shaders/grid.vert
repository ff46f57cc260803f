#version 450 core
// Brute-force reference for the terrain benchmark: a full-resolution grid mesh of a
// DEM, positions relative to the DEM's centre (ECEF axes, metres).
layout(location = 0) in vec3 inPosition;

uniform mat3 uEcefToView;
uniform vec3 uCentreToCamera;  // DEM centre relative to the camera, view space
uniform mat4 uProjection;      // reversed-Z

void main() {
    gl_Position = uProjection * vec4(uEcefToView * inPosition + uCentreToCamera, 1.0);
}
