#include "sylva/core/atmosphere/AtmosphereParameters.h"

#include <cmath>
#include <string>

namespace sylva {

Result<AtmosphereParameters> AtmosphereParameters::fromVisibility(double visibilityMetres,
                                                                  double hazeHeightMetres) {
    AtmosphereParameters parameters;
    if (!(visibilityMetres > 0.0)) {
        return Error{
            "visibility must be positive (the distance at which a black object's "
            "contrast falls to 2 %)"};
    }
    if (visibilityMetres > kMaximumVisibility) {
        return Error{"visibility " + std::to_string(int(visibilityMetres / 1000)) +
                     " km is clearer than air without aerosols allows (at most " +
                     std::to_string(int(kMaximumVisibility / 1000)) + " km)"};
    }
    if (!(hazeHeightMetres >= 100.0 && hazeHeightMetres <= 20000.0)) {
        return Error{"haze height must be within 100 m .. 20 km"};
    }
    const double extinction = kKoschmiederConstant / visibilityMetres;
    const double aerosol = extinction - parameters.rayleighScattering.y;
    const double albedo = parameters.mieScattering / parameters.mieExtinction;
    parameters.mieExtinction = aerosol;
    parameters.mieScattering = aerosol * albedo;
    parameters.mieScaleHeight = hazeHeightMetres;
    return parameters;
}

double AtmosphereParameters::groundExtinctionGreen() const {
    // Ozone's density is 0 below ozoneCentre - ozoneHalfWidth (10 km), so it adds nothing
    // at the ground.
    return rayleighScattering.y + mieExtinction;
}

}  // namespace sylva
