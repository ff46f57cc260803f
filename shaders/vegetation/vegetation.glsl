// Shared by the vegetation shaders: the per-instance attributes (LodSelector's
// DrawInstance), the screen-door fade of seed 001 §6.4 (Mulder et al. 1998) and the
// ellipsoid noise of sylva::ellipsoidNoise (core/plants/EllipsoidNoise.h), bit for bit.

// Screen-door visibility in [0, 1) of a pixel for an instance: a 4×4 Bayer matrix,
// offset per instance so neighbouring trees do not fade on the same pixels.
float ditherValue(vec2 pixel, float instanceOffset) {
    const float bayer[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0,
                                      3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);
    ivec2 p = ivec2(pixel) & 3;
    return fract((bayer[p.y * 4 + p.x] + 0.5) / 16.0 + instanceOffset);
}

// The fade pair of an error interval [minimum, maximum) at `error` with a band of
// `band` in ln(error): visible where fadeMaximum <= dither < fadeMinimum. Adjacent
// intervals share their boundary, so their fades are complementary.
vec2 intervalFade(float error, float minimum, float maximum, float band) {
    float s = log(error);
    float fadeMinimum = minimum > 0.0 ? clamp((s - log(minimum)) / band + 0.5, 0.0, 1.0) : 1.0;
    float fadeMaximum = isinf(maximum) ? 0.0 : clamp((s - log(maximum)) / band + 0.5, 0.0, 1.0);
    return vec2(fadeMinimum, fadeMaximum);
}

uvec3 pcg3d(uvec3 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    return v;
}

uint ellipsoidNoiseSeed(vec3 center) {
    return floatBitsToUint(center.x) ^ floatBitsToUint(center.y) * 0x9E3779B9u ^
           floatBitsToUint(center.z) * 0x85EBCA6Bu;
}

uvec3 ellipsoidNoiseHash(vec3 q, float cells, uint seed) {
    ivec3 cell = ivec3(floor((q * 0.5 + 0.5) * cells));
    return pcg3d(uvec3(cell + 4096) ^ uvec3(seed, seed * 0x27D4EB2Fu, seed * 0x165667B1u));
}

// Noise value in [0, 1) at unit-sphere point q with `cells` cells per diameter.
float ellipsoidNoise(vec3 q, float cells, uint seed) {
    uvec3 v = ellipsoidNoiseHash(q, cells, seed);
    return float((v.x ^ v.y ^ v.z) >> 8u) / 16777216.0;
}

// Three independent noise values in [0, 1) of one cell (the normal perturbation; shader
// only, so one hash serves all three components).
vec3 ellipsoidNoise3(vec3 q, float cells, uint seed) {
    return vec3(ellipsoidNoiseHash(q, cells, seed) >> 8u) / 16777216.0;
}

// Seasons (issue 21 item 3, core/seasons/Phenology.h): the species' leaf state of the
// render date. Leaf density thins the crown where the level of detail draws it: a ray
// through an ellipsoid of alpha threshold t tests the noise at the front and, where that
// is perforated, at the back hit, so it stops with probability 1 − t²; with a leaf
// fraction f it must stop with f (1 − t²), i.e. threshold sqrt(1 − f (1 − t²)).
uniform float uLeafFraction = 1.0;
// rgb: the autumn colour divided by the species' mean leaf luminance, w: how far the
// leaves have turned. A leaf of luminance L turns towards rgb × L, so the crown's
// light and shade variation survives the colour change.
uniform vec4 uAutumn = vec4(0.0);

float seasonalThreshold(float threshold) {
    float t = max(threshold, 0.0);
    return sqrt(max(1.0 - uLeafFraction * (1.0 - t * t), 0.0));
}

vec3 seasonalLeafColour(vec3 colour) {
    float luminance = dot(colour, vec3(0.2126, 0.7152, 0.0722));
    return mix(colour, uAutumn.rgb * luminance, uAutumn.w);
}
