// Seed 004 §3.2 (views over the upper hemisphere) and §3.4 (three resolutions).
#include "sylva/core/plantlod/ImpostorViewSet.h"

#include <cmath>
#include <numbers>

namespace sylva {

ImpostorViewSet ImpostorViewSet::upperHemisphere() {
    ImpostorViewSet set;
    const double step = 2.0 * std::numbers::pi / kAzimuths;
    const double raised = kRaisedElevation * std::numbers::pi / 180.0;
    for (int ring = 0; ring < 2; ++ring) {
        const double elevation = ring == 0 ? 0.0 : raised;
        for (int i = 0; i < kAzimuths; ++i) {
            const double azimuth = step * (double(i) + 0.5 * ring);
            set.directions_.emplace_back(float(std::cos(elevation) * std::cos(azimuth)),
                                         float(std::cos(elevation) * std::sin(azimuth)),
                                         float(std::sin(elevation)));
        }
    }
    set.directions_.emplace_back(0.0f, 0.0f, 1.0f);
    return set;
}

int ImpostorViewSet::nearest(const glm::vec3& towardEye) const {
    int best = 0;
    float bestDot = -2.0f;
    const glm::vec3 direction = glm::normalize(towardEye);
    for (std::size_t i = 0; i < directions_.size(); ++i) {
        const float d = glm::dot(direction, directions_[i]);
        if (d > bestDot) {
            bestDot = d;
            best = int(i);
        }
    }
    return best;
}

int ImpostorViewSet::resolutionLevel(double pixels) {
    for (std::size_t i = 0; i < kResolutions.size(); ++i) {
        if (pixels <= double(kResolutions[i])) {
            return int(i);
        }
    }
    return int(kResolutions.size()) - 1;
}

}  // namespace sylva
