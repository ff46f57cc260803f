// The stable map transform of spherical geometry clipmaps: a line-by-line copy of
// sylva::MapTransform (core/include/sylva/core/geo/MapTransform.h), which explains the
// derivation and is tested against direct formulas in float and double.
#include "../common/constants.glsl"

// x: sin(lat1), y: cos(lat1), z: lat1 of the viewer's ground point.
uniform vec3 uViewerLatitude;

// Offsets (dLat, dLon) of the point at view angle `theta` in direction `bearing`.
vec2 mapOffset(float theta, float sinBearing, float cosBearing) {
    float sinLat = uViewerLatitude.x;
    float cosLat = uViewerLatitude.y;
    float sinTheta = sin(theta);
    float halfSin = sin(theta * 0.5);
    float oneMinusCos = 2.0 * halfSin * halfSin;
    float px = cosLat * (1.0 - oneMinusCos) - sinLat * sinTheta * cosBearing;
    float py = sinTheta * sinBearing;
    float deltaSin = -sinLat * oneMinusCos + cosLat * sinTheta * cosBearing;
    float cosLat2 = sqrt(px * px + py * py);
    float sinLat2 = sinLat + deltaSin;
    float denominator = cosLat + cosLat2;
    float sinDelta;
    if (denominator > 1e-6) {
        sinDelta = deltaSin * (cosLat + sinLat * (sinLat + sinLat2) / denominator);
    } else {
        sinDelta = sinLat2 * cosLat - sinLat * cosLat2;
    }
    return vec2(asin(clamp(sinDelta, -1.0, 1.0)), atan(py, px));
}

// Position of (lat1 + dLat, lon1 + dLon, height) minus the ground point, in the
// viewer's meridian frame (ECEF rotated by -lon1 about z).
vec3 ecefOffset(vec2 offset, float height) {
    float sinLat = uViewerLatitude.x;
    float cosLat = uViewerLatitude.y;
    float halfDLat = offset.x * 0.5;
    float middle = uViewerLatitude.z + halfDLat;
    float sinHalf = sin(halfDLat);
    float dSin = 2.0 * cos(middle) * sinHalf;
    float dCos = -2.0 * sin(middle) * sinHalf;
    float sinLat2 = sinLat + dSin;
    float cosLat2 = cosLat + dCos;
    float w1 = sqrt(1.0 - WGS84_E2 * sinLat * sinLat);
    float w2 = sqrt(1.0 - WGS84_E2 * sinLat2 * sinLat2);
    float n1 = WGS84_A / w1;
    float n2 = WGS84_A / w2;
    float dN = WGS84_A * (WGS84_E2 * dSin * (sinLat2 + sinLat) / (w1 + w2)) / (w1 * w2);
    float halfSinLon = sin(offset.y * 0.5);
    float cosLonMinusOne = -2.0 * halfSinLon * halfSinLon;
    float sinLon = sin(offset.y);
    float dNCos = dN * cosLat2 + n1 * dCos;
    float nCos2 = n2 * cosLat2;
    return vec3(nCos2 * cosLonMinusOne + dNCos + height * cosLat2 * (1.0 + cosLonMinusOne),
                (nCos2 + height * cosLat2) * sinLon,
                (1.0 - WGS84_E2) * (dN * sinLat2 + n1 * dSin) + height * sinLat2);
}

// Unit surface normal at the offset point, in the viewer's meridian frame.
vec3 surfaceUp(vec2 offset) {
    float latitude = uViewerLatitude.z + offset.x;
    float c = cos(latitude);
    return vec3(c * cos(offset.y), c * sin(offset.y), sin(latitude));
}
