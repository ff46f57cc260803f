// The hand-over between the drawn trees and the far-field canopy (FarFieldFade.h): both
// sides evaluate the same fade at the fragment's distance and test it against the same
// screen-door value (a 4×4 Bayer matrix with no per-instance offset, Mulder et al. 1998),
// so at each pixel exactly one of them passes: no double-drawn and no empty band.
//
// uFarFieldFade: x = fade start (metres), y = 1 / band width (1/m; 0 = no far field, the
// trees are never dropped), z = near plane (metres; reversed-Z depth = near / view depth).
// uFarFieldRay: the view ray's slope per window pixel, (x, y) / -z =
// gl_FragCoord.xy * uFarFieldRay.xy + uFarFieldRay.zw (off-axis projections included).
uniform vec4 uFarFieldFade;
uniform vec4 uFarFieldRay;

// 0 where the trees are drawn, 1 where the canopy is, linear in the fragment's distance
// from the camera across the band.
float farFieldFade() {
    if (uFarFieldFade.y <= 0.0) {
        return 0.0;
    }
    float viewDepth = uFarFieldFade.z / max(gl_FragCoord.z, 1e-30);
    vec2 slope = gl_FragCoord.xy * uFarFieldRay.xy + uFarFieldRay.zw;
    float distance = viewDepth * sqrt(1.0 + dot(slope, slope));
    return clamp((distance - uFarFieldFade.x) * uFarFieldFade.y, 0.0, 1.0);
}

float farFieldDither() {
    const float bayer[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0,
                                      3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);
    ivec2 p = ivec2(gl_FragCoord.xy) & 3;
    return (bayer[p.y * 4 + p.x] + 0.5) / 16.0;
}

// True where this pixel belongs to the canopy: trees discard there, the canopy elsewhere.
bool farFieldCanopyPixel() {
    return farFieldDither() < farFieldFade();
}
