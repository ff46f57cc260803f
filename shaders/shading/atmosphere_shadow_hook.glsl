// Shadowed in-scattering (light shafts, seed 001 §7.2): the fraction of the sun's disc
// visible from a point on a view ray, given as its offset from the camera in ECEF metres
// (float-precise near the camera, where shadow maps are). 1 = unshadowed. The
// aerial-perspective pass (atmosphere_aerial_perspective.comp) multiplies single
// scattering by it, so air in the shadow of a ridge, a tree or a building scatters only
// skylight (multiple scattering) towards the camera: a valley behind a ridge at dusk is
// less hazy, gaps between crowns make shafts. The lookup is the cascaded shadow maps of
// the surfaces (shadows.glsl, one depth comparison per sample; uniforms and the map set
// by ShadowMaps::bindUniforms); outside every cascade, or without shadow maps, the air
// is lit.
#include "shadows.glsl"

float atmosphereSunVisibility(vec3 offsetFromCameraEcef) {
    return sunVisibilityInAir(offsetFromCameraEcef);
}

bool atmosphereHasShadows() {
    return uShadowCascadeCount > 0;
}
