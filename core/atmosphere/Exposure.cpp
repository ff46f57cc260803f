#include "sylva/core/atmosphere/Exposure.h"

#include <algorithm>
#include <cmath>

namespace sylva {

double ev100FromIlluminance(double lux) {
    constexpr double kSensitivity = 100.0;
    constexpr double kIncidentCalibration = 250.0;  // ISO 2720, flat receptor
    return std::log2(std::max(lux, 1e-3) * kSensitivity / kIncidentCalibration);
}

double exposureScale(double ev100) {
    return 1.0 / (1.2 * std::exp2(ev100));
}

double luminance(const glm::dvec3& rgb) {
    return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
}

}  // namespace sylva
