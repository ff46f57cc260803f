#include "sylva/core/scene/LocationMap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/BitmapFont.h"
#include "sylva/core/scene/ImageProjection.h"

namespace sylva {
namespace {

using Rgba = std::array<std::uint8_t, 4>;
constexpr Rgba kRed{220, 30, 30, 255};
constexpr Rgba kWhite{255, 255, 255, 255};
constexpr Rgba kBlack{0, 0, 0, 255};

void disc(RgbaImage& image, glm::dvec2 centre, double radius, const Rgba& colour) {
    const int x0 = int(std::floor(centre.x - radius)), x1 = int(std::ceil(centre.x + radius));
    const int y0 = int(std::floor(centre.y - radius)), y1 = int(std::ceil(centre.y + radius));
    for (int y = std::max(y0, 0); y <= std::min(y1, image.height - 1); ++y) {
        for (int x = std::max(x0, 0); x <= std::min(x1, image.width - 1); ++x) {
            if (glm::length(glm::dvec2(x + 0.5, y + 0.5) - centre) <= radius) {
                std::copy(colour.begin(), colour.end(), image.at(x, y));
            }
        }
    }
}

void segment(RgbaImage& image, glm::dvec2 a, glm::dvec2 b, double width, const Rgba& colour) {
    const double length = glm::length(b - a);
    const int steps = std::max(1, int(std::ceil(length * 2.0)));
    for (int i = 0; i <= steps; ++i) {
        disc(image, a + (b - a) * (double(i) / steps), width / 2.0, colour);
    }
}

// The ECEF point `distance` metres from the camera's ground point along `bearing`
// (radians clockwise from north), in the local tangent plane at `height`.
glm::dvec3 along(const Camera& viewpoint, double height, double bearing, double distance) {
    const Geodetic& at = viewpoint.geodetic;
    const glm::dvec3 east(-std::sin(at.longitude), std::cos(at.longitude), 0.0);
    const glm::dvec3 up = Ellipsoid::surfaceNormal(at.latitude, at.longitude);
    const glm::dvec3 north = glm::cross(up, east);
    const glm::dvec3 ground = Ellipsoid::toEcef({at.latitude, at.longitude, height});
    return ground + (east * std::sin(bearing) + north * std::cos(bearing)) * distance;
}

void northArrow(RgbaImage& map, int scale) {
    const double x = map.width - 18.0 * scale, top = 10.0 * scale, bottom = 34.0 * scale;
    segment(map, {x, bottom}, {x, top}, 2.0 * scale, kBlack);
    segment(map, {x, top}, {x - 5.0 * scale, top + 8.0 * scale}, 2.0 * scale, kBlack);
    segment(map, {x, top}, {x + 5.0 * scale, top + 8.0 * scale}, 2.0 * scale, kBlack);
    BitmapFont::draw(map, int(x) - 2 * scale, int(bottom) + 3 * scale, "N", scale, kBlack.data());
}

void scaleBar(RgbaImage& map, double pixelsPerMetre, double radius, int scale) {
    const double metres = LocationMap::scaleLength(radius);
    const double length = metres * pixelsPerMetre;
    const double x = 10.0 * scale, y = map.height - 12.0 * scale;
    fillPixels(map, int(x) - 3 * scale, int(y) - 14 * scale, int(x + length) + 3 * scale,
               int(y) + 6 * scale, kWhite);
    segment(map, {x, y}, {x + length, y}, 2.0 * scale, kBlack);
    segment(map, {x, y - 4.0 * scale}, {x, y + 2.0 * scale}, 1.5 * scale, kBlack);
    segment(map, {x + length, y - 4.0 * scale}, {x + length, y + 2.0 * scale}, 1.5 * scale, kBlack);
    char label[32];
    if (metres >= 1000.0) {
        std::snprintf(label, sizeof label, "%g KM", metres / 1000.0);
    } else {
        std::snprintf(label, sizeof label, "%g M", metres);
    }
    BitmapFont::draw(map, int(x), int(y) - 13 * scale, label, scale, kBlack.data());
}

}  // namespace

Camera LocationMap::overhead(const Camera& viewpoint, double groundHeight, double radius) {
    SYLVA_CHECK(radius > 0.0);
    Camera map;
    map.geodetic = {viewpoint.geodetic.latitude, viewpoint.geodetic.longitude,
                    groundHeight + radius / std::tan(kFieldOfView / 2.0)};
    map.position = Ellipsoid::toEcef(map.geodetic);
    // Pitch −90° with heading 0: the image's up is north.
    map.axes = Camera::axesFromAngles(map.geodetic, 0.0, -std::acos(0.0), 0.0);
    map.verticalFov = kFieldOfView;
    return map;
}

double LocationMap::scaleLength(double radius) {
    const double target = radius / 3.0;
    const double decade = std::pow(10.0, std::floor(std::log10(target)));
    for (double step : {5.0, 2.0, 1.0}) {
        if (step * decade <= target) {
            return step * decade;
        }
    }
    return decade;
}

void LocationMap::draw(RgbaImage& map, const Camera& overhead, const Camera& viewpoint,
                       double horizontalFov, double radius) {
    const ImageProjection projection(overhead, map.width, map.height);
    const double ground = overhead.geodetic.height - radius / std::tan(kFieldOfView / 2.0);
    const std::optional<glm::dvec2> centre =
        projection.pixelOfPoint(along(viewpoint, ground, 0.0, 0.0));
    SYLVA_CHECK(centre.has_value());
    const int scale = std::max(1, map.width / 256);
    const double heading = viewpoint.heading();
    auto at = [&](double bearing, double distance) {
        return projection.pixelOfPoint(along(viewpoint, ground, bearing, distance))
            .value_or(*centre);
    };
    const double reach = 0.85 * radius;
    // A white casing under the red lines keeps them visible on any ground.
    for (int pass = 0; pass < 2; ++pass) {
        const Rgba& colour = pass == 0 ? kWhite : kRed;
        const double width = (pass == 0 ? 4.0 : 2.0) * scale;
        segment(map, *centre, at(heading - horizontalFov / 2.0, reach), width, colour);
        segment(map, *centre, at(heading + horizontalFov / 2.0, reach), width, colour);
        const int arcSteps = 48;
        for (int i = 0; i < arcSteps; ++i) {
            const double b0 = heading - horizontalFov / 2.0 + horizontalFov * i / arcSteps;
            const double b1 = heading - horizontalFov / 2.0 + horizontalFov * (i + 1) / arcSteps;
            segment(map, at(b0, reach), at(b1, reach), width, colour);
        }
    }
    disc(map, *centre, 6.0 * scale, kWhite);
    disc(map, *centre, 4.0 * scale, kRed);
    northArrow(map, scale);
    scaleBar(map, projection.focalPixels() / (overhead.geodetic.height - ground), radius, scale);
}

}  // namespace sylva
