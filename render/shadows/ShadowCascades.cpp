#include "sylva/render/shadows/ShadowCascades.h"

#include <algorithm>
#include <cmath>

#include "sylva/core/base/Check.h"

namespace sylva::render {
namespace {

// The smallest sphere around the frustum slice between view distances `near` and `far`
// (along the view axis) whose corners lie at lateral distance k × distance: its centre
// is on the axis at c = (near + far)(1 + k²)/2, or at `far` when the far face alone
// decides. Depends only on the distances and the field of view, so cascades keep their
// size whatever way the camera turns.
void sliceSphere(double near, double far, double k, double& center, double& radius) {
    const double k2 = k * k;
    center = std::min(0.5 * (near + far) * (1.0 + k2), far);
    radius = std::sqrt((far - center) * (far - center) + k2 * far * far);
}

// The camera-relative box centre and the projection of `cascade`'s Earth-fixed box
// (boxLight, radius) seen from `camera`.
void placeBox(ShadowCascade& cascade, const Camera& camera, const glm::dmat3& light) {
    const glm::dvec3 box = cascade.boxLight - light * camera.position;
    cascade.boxRelative = glm::transpose(light) * box;
    const double radius = cascade.radius;
    const double depthNear = box.z + 2.0 * radius;  // towards the sun
    const double depthFar = box.z - radius;
    glm::dmat4 projection(0.0);
    projection[0][0] = 1.0 / radius;
    projection[3][0] = -box.x / radius;
    projection[1][1] = 1.0 / radius;
    projection[3][1] = -box.y / radius;
    projection[2][2] = -1.0 / (depthNear - depthFar);
    projection[3][2] = depthNear / (depthNear - depthFar);
    projection[3][3] = 1.0;
    cascade.projection = projection;
}

ShadowCascade makeCascade(const Camera& camera, const glm::dmat3& light, double near, double far,
                          double k, const ShadowSettings& settings) {
    ShadowCascade cascade;
    cascade.nearDistance = near;
    cascade.farDistance = far;
    double center = 0, sphereRadius = 0;
    sliceSphere(near, far, k, center, sphereRadius);
    // The margin, plus one texel on either side: snapping to whole texels alone moves the
    // box by up to half a texel.
    const int resolution = settings.resolution;
    const double radius =
        sphereRadius * (1.0 + settings.recentreMargin) * resolution / (resolution - 2.0);
    const double texel = 2.0 * radius / resolution;
    cascade.radius = radius;
    cascade.sliceRadius = sphereRadius;
    cascade.texelSize = texel;
    // Cells of whole texels no wider than twice the slack between box and sphere: the
    // sphere's centre lies within half a cell of the snapped box centre on every axis,
    // so the box holds the sphere (in depth too: the range reaches a radius either way).
    const double slack = radius - sphereRadius;
    const double cellTexels =
        settings.recentreMargin > 0.0 ? std::max(1.0, std::floor(2.0 * slack / texel)) : 1.0;
    const double cell = cellTexels * texel;
    cascade.cellSize = cell;
    cascade.centerRelative = -center * camera.axes[2];  // the view axis is -z (back)
    // Snap in absolute light coordinates (double), then return to camera-relative ones:
    // the texel grid (and the cell grid, whole texels from the same origin) is fixed to
    // the Earth, not to the camera.
    const glm::dvec3 absolute = light * (camera.position + cascade.centerRelative);
    // Depth too (whole texels along the sun): a map's depths are then those of the
    // Earth-fixed box, whatever the camera's position, so ShadowMaps can keep a cascade's
    // depth while the box does not move.
    const glm::dvec3 snapped(std::floor(absolute.x / cell + 0.5) * cell,
                             std::floor(absolute.y / cell + 0.5) * cell,
                             std::floor(absolute.z / cell + 0.5) * cell);
    cascade.boxLight = snapped;
    placeBox(cascade, camera, light);
    return cascade;
}

}  // namespace

glm::dmat3 ShadowCascades::lightRotation(const glm::dvec3& sunDirection) {
    const glm::dvec3 z = glm::normalize(sunDirection);
    const glm::dvec3 reference = std::abs(z.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    const glm::dvec3 x = glm::normalize(glm::cross(reference, z));
    const glm::dvec3 y = glm::cross(z, x);
    // glm is column-major: the transpose of the matrix with columns x, y, z has them as rows.
    return glm::transpose(glm::dmat3(x, y, z));
}

std::vector<double> ShadowCascades::splits(const ShadowSettings& settings) {
    SYLVA_CHECK(settings.cascades >= 1 && settings.distance > settings.firstSplitStart);
    const int n = settings.cascades;
    const double start = settings.firstSplitStart;
    const double end = settings.distance;
    std::vector<double> out(std::size_t(n) + 1, 0.0);
    for (int i = 1; i < n; ++i) {
        const double fraction = double(i) / n;
        const double logarithmic = start * std::pow(end / start, fraction);
        const double uniform = start + (end - start) * fraction;
        out[std::size_t(i)] =
            settings.splitBlend * logarithmic + (1.0 - settings.splitBlend) * uniform;
    }
    out[std::size_t(n)] = end;
    return out;
}

std::vector<ShadowCascade> ShadowCascades::fit(const Camera& camera, double aspect,
                                               const glm::dvec3& sunDirection,
                                               const ShadowSettings& settings) {
    std::vector<ShadowCascade> cascades;
    if (!settings.enabled) {
        return cascades;
    }
    SYLVA_CHECK(settings.resolution >= 16 && aspect > 0 && settings.recentreMargin >= 0.0);
    const double tangentY = std::tan(camera.verticalFov / 2);
    const double k = std::hypot(tangentY, tangentY * aspect);
    const glm::dmat3 light = lightRotation(sunDirection);
    const std::vector<double> distances = splits(settings);
    for (std::size_t i = 0; i + 1 < distances.size(); ++i) {
        cascades.push_back(makeCascade(camera, light, distances[i], distances[i + 1], k, settings));
    }
    if (settings.terrainDistance > settings.distance) {
        ShadowCascade terrain =
            makeCascade(camera, light, 0.0, settings.terrainDistance, k, settings);
        terrain.terrainOnly = true;
        cascades.push_back(terrain);
    }
    return cascades;
}

ShadowCascade ShadowCascades::reexpressed(const ShadowCascade& cascade, const Camera& camera,
                                          const glm::dmat3& light) {
    ShadowCascade moved = cascade;
    // The slice's sphere follows the camera (on its view axis, at the same distance); the
    // box stays where its map was drawn, and may no longer hold the sphere: the shading
    // then falls through to the next cascade whose box holds the point.
    moved.centerRelative = -glm::length(cascade.centerRelative) * camera.axes[2];
    placeBox(moved, camera, light);
    return moved;
}

}  // namespace sylva::render
