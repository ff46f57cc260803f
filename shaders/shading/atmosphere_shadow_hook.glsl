// Hook for shadowed in-scattering (light shafts, seed 001 §7): the fraction of the sun's
// disc visible from a point on a view ray, given as its offset from the camera in ECEF
// metres (float-precise near the camera, where shadow maps are). 1 = unshadowed. The
// aerial-perspective pass (atmosphere_aerial_perspective.comp) multiplies single
// scattering by it; wiring it to the sun's shadow maps replaces this body (the maps'
// samplers and matrices as uniforms of that pass).
float atmosphereSunVisibility(vec3 offsetFromCameraEcef) {
    return 1.0;
}
