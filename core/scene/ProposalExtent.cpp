#include "sylva/core/scene/ProposalExtent.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scene/ImageProjection.h"

namespace sylva {

std::optional<ProposalExtent> ProposalExtent::measure(const PixelMask& mask,
                                                      const std::vector<float>& depth, double near,
                                                      const Camera& camera, int width, int height) {
    const std::size_t size = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    SYLVA_CHECK(mask.size() == size && depth.size() == size && near > 0.0);
    const ImageProjection projection(camera, width, height);
    const Geodetic& at = camera.geodetic;
    const glm::dvec3 east(-std::sin(at.longitude), std::cos(at.longitude), 0.0);
    const glm::dvec3 north = glm::cross(Ellipsoid::surfaceNormal(at.latitude, at.longitude), east);
    const double heading = camera.heading();
    double nearest = std::numeric_limits<double>::infinity();
    double farthest = 0.0;
    double left = std::numeric_limits<double>::infinity();
    double right = -std::numeric_limits<double>::infinity();
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            if (mask[i] == 0 || depth[i] <= 0.0f) {
                continue;
            }
            const glm::dvec2 pixel(x + 0.5, y + 0.5);
            const glm::dvec3 view = projection.viewDirection(pixel);
            const double range = near / double(depth[i]) / -view.z;
            nearest = std::min(nearest, range);
            farthest = std::max(farthest, range);
            const glm::dvec3 ray = projection.ecefDirection(pixel);
            const double bearing = std::atan2(glm::dot(ray, east), glm::dot(ray, north));
            // Relative to the heading, so a view across north does not wrap.
            const double relative = std::remainder(bearing - heading, 2.0 * std::numbers::pi);
            left = std::min(left, relative);
            right = std::max(right, relative);
        }
    }
    if (!std::isfinite(nearest)) {
        return std::nullopt;
    }
    auto compass = [](double angle) {
        const double wrapped = std::remainder(angle, 2.0 * std::numbers::pi);
        return wrapped < 0.0 ? wrapped + 2.0 * std::numbers::pi : wrapped;
    };
    ProposalExtent extent;
    extent.nearestDistance = nearest;
    extent.farthestDistance = farthest;
    extent.leftBearing = compass(heading + left);
    extent.rightBearing = compass(heading + right);
    extent.horizontalExtent = right - left;
    return extent;
}

}  // namespace sylva
