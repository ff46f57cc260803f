#version 450 core
// A box standing on the ground (the shadow tests' pole): 36 vertices from gl_VertexID,
// corners in the local east/north/up frame of its foot, camera-relative ECEF, then the
// light rotation and the cascade's orthographic projection (ShadowCaster contract).
uniform vec3 uFoot;  // camera-relative ECEF metres
uniform mat3 uEastNorthUp;
uniform vec3 uHalfSize;  // east, north half widths; height
uniform mat3 uLightRotation;
uniform mat4 uProjection;

const int kFaces[36] = int[36](0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1, 2, 3, 7, 2, 7, 6,
                               0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3);

void main() {
    int corner = kFaces[gl_VertexID];
    vec3 local = vec3((corner & 1) != 0 ? uHalfSize.x : -uHalfSize.x,
                      (corner & 2) != 0 ? uHalfSize.y : -uHalfSize.y,
                      (corner & 4) != 0 ? uHalfSize.z : 0.0);
    vec3 position = uFoot + uEastNorthUp * local;
    gl_Position = uProjection * vec4(uLightRotation * position, 1.0);
}
