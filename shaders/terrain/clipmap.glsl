// Clipmap addressing. Level i of every clipmap layer is a layer of a 2D texture array
// with toroidal addressing (GL_REPEAT does the wrap): the texture coordinate of a
// point is the viewer's texel coordinate in that level plus the offset divided by the
// texel size. Everything stays relative to the viewer, so float precision suffices
// at every level (see core/include/sylva/core/tiles/Clipmap.h).

const int MAX_CLIPMAP_LEVELS = 32;

uniform float uClipmapSize;  // texels per side
// Per level: x: 1 / texel width (lon), y: 1 / texel height (lat), both per radian;
// z, w: the viewer's continuous texel coordinate modulo the size (u east, v south).
// Height levels use pyramid level i - 2, detail (colour, normals) i - 1.
uniform vec4 uHeightLevels[MAX_CLIPMAP_LEVELS];
uniform vec4 uDetailLevels[MAX_CLIPMAP_LEVELS];

// Texture coordinate for offsets (dLat, dLon) from the viewer in the level `l`.
vec2 clipmapCoordinate(vec4 l, vec2 offset) {
    return vec2(l.z + offset.y * l.x, l.w - offset.x * l.y) / uClipmapSize;
}
