#include "sylva/core/scene/FrameHoles.h"

#include <cmath>
#include <cstddef>

#include "sylva/core/base/Check.h"
#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {

FrameHoles FrameHoles::count(const Camera& camera, const std::vector<float>& depth, int width,
                             int height, double minimumDistance) {
    SYLVA_CHECK(depth.size() == std::size_t(width) * std::size_t(height));
    const double scale = Ellipsoid::kSemiMajorAxis / Ellipsoid::kSemiMinorAxis;
    const glm::dvec3 origin(camera.position.x, camera.position.y, camera.position.z * scale);
    const double inner = Ellipsoid::kSemiMajorAxis - kDepth;
    const double tangent = std::tan(camera.verticalFov / 2);
    const double aspect = double(width) / height;
    FrameHoles count;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const glm::dvec3 view((2.0 * (x + 0.5) / width - 1.0) * tangent * aspect,
                                  (1.0 - 2.0 * (y + 0.5) / height) * tangent, -1.0);
            glm::dvec3 direction = camera.axes * glm::normalize(view);
            direction.z *= scale;
            // |origin + t direction|² = (a − kDepth)²: where the ray reaches kDepth under
            // the surface (of the sphere the ellipsoid becomes), if it does ahead.
            const double qa = glm::dot(direction, direction);
            const double qb = 2.0 * glm::dot(origin, direction);
            const double qc = glm::dot(origin, origin) - inner * inner;
            const double discriminant = qb * qb - 4 * qa * qc;
            if (discriminant < 0.0) {
                continue;
            }
            const double t = (-qb - std::sqrt(discriminant)) / (2 * qa);
            if (t <= minimumDistance) {
                continue;
            }
            ++count.deepRays;
            if (depth[std::size_t(y) * width + x] <= 0.0f) {
                if (count.holes++ == 0) {
                    count.firstX = x;
                    count.firstY = y;
                }
            }
        }
    }
    return count;
}

}  // namespace sylva
