// AtmosphereParameters: the physical atmosphere of the shading (Hillaire 2020, "A Scalable
// and Production Ready Sky and Atmosphere Rendering Technique", EGSR; §3 and Table 1 for
// the Earth values; the density profiles are those of Bruneton & Neyret 2008).
//
// Units: lengths in metres, scattering/absorption/extinction coefficients per metre, one
// value per RGB channel (the 680, 550 and 440 nm wavelengths of Hillaire's Table 1;
// green = 550 nm, the photopic peak used for visibility). The planet is the WGS84
// ellipsoid made a sphere of radius a by scaling z by a/b (as the shaders do), so the
// bottom radius is WGS84 a.
#pragma once

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"

namespace sylva {

struct AtmosphereParameters {
    double bottomRadius = 6378137.0;  // WGS84 a (the ellipsoid scaled to a sphere)
    double topRadius = 6378137.0 + 100000.0;
    glm::dvec3 rayleighScattering{5.802e-6, 13.558e-6, 33.1e-6};
    double rayleighScaleHeight = 8000.0;
    // Aerosols (Mie): extinction and scattering at ground level, grey.
    double mieScattering = 3.996e-6;
    double mieExtinction = 4.440e-6;
    double mieScaleHeight = 1200.0;
    double mieAsymmetry = 0.8;  // Cornette-Shanks g
    // Ozone: absorption only, a tent profile of density 1 at ozoneCentre falling to 0 at
    // ±ozoneHalfWidth.
    glm::dvec3 ozoneAbsorption{0.650e-6, 1.881e-6, 0.085e-6};
    double ozoneCentre = 25000.0;
    double ozoneHalfWidth = 15000.0;
    double groundAlbedo = 0.1;  // of the planet for the multiple-scattering LUT
    // Solar illuminance at the top of the atmosphere, lux (photometric: the shading
    // works in cd/m^2 so exposure can follow EV100; white in linear sRGB).
    double sunIlluminance = 128000.0;
    double sunAngularRadius = 0.004675;  // radians (0.2678 degrees)
    double sunLimbDarkening = 0.6;       // u of I(mu) = 1 - u (1 - mu)

    // Koschmieder: the meteorological range V is where a black object's contrast against
    // the horizon sky falls to 2 %, so the ground-level extinction at 550 nm is
    // -ln(0.02) / V = 3.912 / V. Rayleigh supplies 13.558e-6 /m of it (V = 288 km
    // alone); aerosols the rest, with the single-scattering albedo of Hillaire's values
    // (0.9). `hazeHeight` is the aerosols' scale height. Fails (message without a
    // location; the caller adds it) when V is not positive or clearer than pure Rayleigh
    // air, or the haze height is outside 100 m .. 20 km.
    static Result<AtmosphereParameters> fromVisibility(double visibilityMetres,
                                                       double hazeHeightMetres = 1200.0);
    static constexpr double kKoschmiederConstant = 3.912;   // -ln(0.02)
    static constexpr double kMaximumVisibility = 280000.0;  // metres (below 288 km)

    // Ground-level extinction at 550 nm (green), per metre.
    double groundExtinctionGreen() const;
    // Visibility per Koschmieder from the ground-level extinction, metres.
    double visibility() const { return kKoschmiederConstant / groundExtinctionGreen(); }

    bool operator==(const AtmosphereParameters&) const = default;
};

}  // namespace sylva
