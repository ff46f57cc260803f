#version 450 core
// Spherical geometry clipmap terrain (seed 001 ch. 5): static rings on the view
// hemisphere (TerrainRings), mapped to the ellipsoid around the viewer and displaced
// by the height clipmap. Camera-relative throughout: the CPU passes the ground point
// relative to the camera, the shader adds stable offsets (map_transform.glsl).
#include "map_transform.glsl"
#include "clipmap.glsl"

layout(location = 0) in vec4 inVertex;  // view angle (level 0), blend, sin bearing, cos bearing
layout(location = 1) in float inSeam;   // +1 first column, -1 duplicated last column

uniform sampler2DArray uHeight;
uniform int uLevel;             // ring level i: uses clipmap levels i and i - 1
// The clipmap level the ring samples: uLevel, or a coarser one while ring i's own level
// is not resident yet (interactive frames after a jump): the ring then shows that level
// alone (no blend), exactly as the coarser rings around it do at their shared border.
uniform int uTextureLevel;
uniform float uLevelScale;      // 2^-i
uniform float uBearingSign;     // +1: bearing 0 is north; -1: south (viewer in the south)
uniform mat3 uMeridianToView;   // viewer's meridian frame -> view space
uniform vec3 uGroundToCamera;   // the ground point relative to the camera, view space
uniform mat4 uProjection;       // reversed-Z, infinite far plane
uniform bool uOcean;            // clamp heights below 0 m to the sea surface
uniform float uRingStep;        // 2^(1/ringsPerLevel) - 1: a ring's step over its view angle
uniform float uBearingStep;     // 2 pi / columns (radians)
// Metres from the camera inside which the geometry is clipped, for the far-field canopy
// (FarFieldCanopy::draw enables GL_CLIP_DISTANCE0; the terrain leaves it disabled, so
// this is ignored there). The clip distance is interpolated linearly across a triangle
// while the distance is convex, so a clipped point is nearer than this: conservative.
uniform float uClipInside;
// Interactive frames whose camera is below the ground of every resident clipmap level
// (an aircraft over a valley that the coarse levels, averaging the ridges around it, fill
// higher than the camera; TerrainRenderer::update): every vertex's height is capped at
// uNadirCeiling (ellipsoid height, metres, a little under the camera) at the nadir, rising
// 1:10 with the distance from it, so the ground drawn near the camera is below the eye and
// rays looking down meet it instead of passing under the coarse surface to the sky (the
// viewer bench's `frames_with_holes`, issue 20). Terrain farther than ten times the
// coarse ground's excess over the ceiling is untouched.
uniform bool uNadirCeilingOn;
uniform float uNadirCeiling;

layout(location = 0) out vec4 vDetailCoordinate;  // xy: detail level i, zw: level i - 1
layout(location = 1) out float vBlend;
layout(location = 2) out vec4 vHeightCoordinate;  // xy: height level i, zw: level i - 1
layout(location = 3) out vec3 vUp;               // surface normal of the ellipsoid, view space
layout(location = 4) out float vDistance;        // metres from the camera

void main() {
    float theta = inVertex.x * uLevelScale;
    float blend = uTextureLevel < uLevel ? 0.0 : inVertex.y;
    float sinBearing = inVertex.z * uBearingSign;
    float cosBearing = inVertex.w * uBearingSign;
    vec2 offset = mapOffset(theta, sinBearing, cosBearing);
    // Beyond the pole the bearing-0 column meets the opposite meridian, where atan
    // jumps between -pi and +pi: pin each copy of that column to its side (§5.4.4).
    float px = uViewerLatitude.y * cos(theta) - uViewerLatitude.x * sin(theta) * cosBearing;
    if (inSeam != 0.0 && px < 0.0) {
        offset.y = PI * inSeam * uBearingSign;
    }

    int coarser = max(uTextureLevel - 1, 0);
    vec2 fine = clipmapCoordinate(uHeightLevels[uTextureLevel], offset);
    vec2 coarse = clipmapCoordinate(uHeightLevels[coarser], offset);
    float heightFine = textureLod(uHeight, vec3(fine, float(uTextureLevel)), 0.0).r;
    float heightCoarse = textureLod(uHeight, vec3(coarse, float(coarser)), 0.0).r;
    // Written so that blend == 1 gives the coarse value exactly: level borders match
    // the next coarser level's inner ring bit for bit (no cracks).
    float height = heightFine * (1.0 - blend) + heightCoarse * blend;
    if (uOcean) {
        height = max(height, 0.0);
    }
    // The mesh's flat triangles are chords of the curved surface and lie below it by up
    // to the sagitta of a cell, R (a^2 + b^2) / 8 for sides of a and b radians: ~0.5 km
    // at the limb seen from 1,800 km, where rays grazing the ellipsoid passed between
    // the chords to the sky (the viewer bench's holes, issue 20). Lifting every vertex by
    // its cell's sagitta makes the mesh enclose the surface. The steps depend on the
    // view angle only (rings are spaced geometrically at every level), so vertices
    // shared by two levels are lifted alike: no cracks. Below a millimetre within 5 km of
    // a walker, 1 m at an aircraft's horizon.
    float radialStep = theta * uRingStep;
    float bearingArc = sin(theta) * uBearingStep;
    height += WGS84_A * (radialStep * radialStep + bearingArc * bearingArc) * 0.125;
    // A function of the view angle alone, like the lift: shared vertices stay shared. The
    // heights are along each vertex's own ellipsoid normal, so the capped surface curves
    // away under the camera's horizontal plane besides rising 1:10 (theta R is the
    // distance along the ground).
    if (uNadirCeilingOn) {
        height = min(height, uNadirCeiling + 0.1 * WGS84_A * theta);
    }

    vec3 position = uMeridianToView * ecefOffset(offset, height) + uGroundToCamera;
    vHeightCoordinate = vec4(fine, coarse);
    vDetailCoordinate = vec4(clipmapCoordinate(uDetailLevels[uTextureLevel], offset),
                             clipmapCoordinate(uDetailLevels[coarser], offset));
    vBlend = blend;
    vUp = uMeridianToView * surfaceUp(offset);
    vDistance = length(position);
    gl_ClipDistance[0] = vDistance - uClipInside;
    gl_Position = uProjection * vec4(position, 1.0);
}
