// Schlick's reflectance model (C. Schlick 1993, "A Customizable Reflectance Model for
// Everyday Rendering", EGWR; seed 001 §7.1: "the BRDF by Schlick for all surfaces"),
// isotropic, for a heterogeneous ("double") material: a Lambertian base of albedo ρ under
// a specular microfacet layer,
//   f(l, v) = (1 - S(u)) ρ / π + S(u) G(v) G(v') Z(t) / (4 π v v'),
// with t = n·h, u = v·h, v = n·view, v' = n·light, h the half vector, roughness r in
// (0, 1], normal-incidence reflectance f0:
//   S(u) = f0 + (1 - f0) (1 - u)^5                 (Schlick's Fresnel approximation)
//   Z(t) = r / (1 + r t² - t²)²                    (Schlick's slope distribution; Z/π is a
//                                                    normalised microfacet density)
//   G(v) = v / (r - r v + v)                       (Schlick's self-shadowing factor)
// Isotropic: Schlick's azimuthal factor A(w) = 1. Units: 1/sr; multiply by irradiance.
#ifndef SCHLICK_BRDF_GLSL
#define SCHLICK_BRDF_GLSL

const float SCHLICK_PI = 3.14159265358979;

float schlickFresnel(float f0, float u) {
    float m = 1.0 - u;
    return f0 + (1.0 - f0) * (m * m) * (m * m) * m;
}

float schlickDistribution(float t, float roughness) {
    float d = 1.0 + roughness * t * t - t * t;
    return roughness / (d * d);
}

float schlickShadowing(float v, float roughness) {
    return v / (roughness - roughness * v + v);
}

// The BRDF for unit vectors `normal`, `toLight`, `toViewer` (any common frame); 0 when the
// light is below the surface.
vec3 schlickBrdf(vec3 albedo, float roughness, float f0, vec3 normal, vec3 toLight,
                 vec3 toViewer) {
    float lightCos = dot(normal, toLight);
    if (lightCos <= 0.0) {
        return vec3(0.0);
    }
    float r = clamp(roughness, 0.02, 1.0);
    // Pixels whose normal faces slightly away from the camera (interpolated normals at
    // silhouettes) are treated as seen at grazing incidence.
    float viewCos = max(dot(normal, toViewer), 1e-3);
    vec3 halfway = normalize(toLight + toViewer);
    float t = max(dot(normal, halfway), 0.0);
    float u = max(dot(toViewer, halfway), 0.0);
    float fresnel = schlickFresnel(f0, u);
    float specular = fresnel * schlickShadowing(viewCos, r) * schlickShadowing(lightCos, r) *
                     schlickDistribution(t, r) / (4.0 * SCHLICK_PI * viewCos * lightCos);
    return albedo * ((1.0 - fresnel) / SCHLICK_PI) + vec3(specular);
}

#endif
