// Shared constants (WGS84, pi). Values match sylva::Ellipsoid.
const float PI = 3.14159265358979;
const float WGS84_A = 6378137.0;               // semi-major axis, metres
const float WGS84_E2 = 0.00669437999014132;    // first eccentricity squared
const float WGS84_B = 6356752.314245;          // semi-minor axis, metres
