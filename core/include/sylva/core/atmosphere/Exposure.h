// Exposure of a physical camera (Lagarde & de Rousiers 2014, "Moving Frostbite to
// Physically Based Rendering", §5.1): EV100 from incident-light metering (ISO 2720:
// EV100 = log2(E S / C), S = 100, C = 250 lux for a flat receptor) and the scale that
// maps luminance (cd/m^2) to the tone mapper's input, 1 / L_max with the
// saturation-based L_max = 1.2 * 2^EV100.
#pragma once

#include <glm/glm.hpp>

namespace sylva {

// EV100 metered from an illuminance in lux (clamped below at 1e-3 lux, starlight).
double ev100FromIlluminance(double lux);
// Scale applied to luminance for a camera at `ev100`.
double exposureScale(double ev100);
// Photometric luminance (Y) of a linear-sRGB triple (Rec. 709 weights).
double luminance(const glm::dvec3& rgb);

}  // namespace sylva
