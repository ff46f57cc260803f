// The location plan (core/scene LocationMap) and the proposal's extent (ProposalExtent),
// against closed forms: the overhead camera shows 256 / radius pixels per metre on a
// 512-pixel map (its height is radius / tan 20°), north up; the wedge's edges run along
// heading ± HFOV/2; a level pinhole camera sees a pixel column at bearing heading +
// atan(dx / f) and a surface at axial distance z at range z / cos of the ray's angle.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scene/LocationMap.h"
#include "sylva/core/scene/ProposalExtent.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

Camera viewpoint(double heading) {
    Camera c;
    c.geodetic = {-7.9668 * kDegree, -34.9042 * kDegree, 51.5};
    c.position = Ellipsoid::toEcef(c.geodetic);
    c.axes = Camera::axesFromAngles(c.geodetic, heading, 0.0, 0.0);
    c.verticalFov = 30.0 * kDegree;
    return c;
}

bool painted(const RgbaImage& map, double x, double y) {
    const std::uint8_t* p = map.at(int(x), int(y));
    return !(p[0] == 90 && p[1] == 120 && p[2] == 60);
}

TEST(LocationMap, WedgeRunsAlongTheEdgeBearingsNorthUp) {
    const double radius = 3000.0, heading = 60.0 * kDegree, fov = 53.5 * kDegree;
    const Camera view = viewpoint(heading);
    const Camera overhead = LocationMap::overhead(view, 50.0, radius);
    EXPECT_NEAR(overhead.geodetic.height, 50.0 + radius / std::tan(20.0 * kDegree), 1e-6);
    RgbaImage map(512, 512, 90, 120, 60);
    LocationMap::draw(map, overhead, view, fov, radius);
    const double pixelsPerMetre = 256.0 / radius;
    auto at = [&](double bearing, double metres) {
        return glm::dvec2(256.0 + std::sin(bearing) * metres * pixelsPerMetre,
                          256.0 - std::cos(bearing) * metres * pixelsPerMetre);
    };
    for (double metres : {600.0, 1200.0, 2000.0}) {
        for (double edge : {heading - fov / 2.0, heading + fov / 2.0}) {
            const glm::dvec2 p = at(edge, metres);
            EXPECT_TRUE(painted(map, p.x, p.y)) << metres << " m at " << edge / kDegree << "°";
        }
        // Inside the wedge (the view's centre line) and behind the viewpoint: ground.
        const glm::dvec2 centre = at(heading, metres);
        const glm::dvec2 behind = at(heading + std::numbers::pi, metres);
        EXPECT_FALSE(painted(map, centre.x, centre.y)) << metres;
        EXPECT_FALSE(painted(map, behind.x, behind.y)) << metres;
    }
    EXPECT_TRUE(painted(map, 256, 256));  // the viewpoint marker
}

TEST(LocationMap, ScaleBarLengthsAreRound) {
    EXPECT_EQ(LocationMap::scaleLength(3000.0), 1000.0);
    EXPECT_EQ(LocationMap::scaleLength(1500.0), 500.0);
    EXPECT_EQ(LocationMap::scaleLength(700.0), 200.0);
    EXPECT_EQ(LocationMap::scaleLength(20000.0), 5000.0);
}

TEST(ProposalExtent, NearestRangeAndBearingsOfAPixelBand) {
    constexpr int w = 320, h = 180;
    const double heading = 355.0 * kDegree;  // the band spans north: no wrap in the extent
    const Camera camera = viewpoint(heading);
    const double near = 0.5, axial = 500.0;
    PixelMask mask(w * h, 0);
    std::vector<float> depth(w * h, 0.0f);
    for (int x = 100; x < 220; ++x) {
        mask[90 * w + x] = 1;
        depth[90 * w + x] = float(near / axial);
    }
    const std::optional<ProposalExtent> extent =
        ProposalExtent::measure(mask, depth, near, camera, w, h);
    ASSERT_TRUE(extent.has_value());
    const double f = (h / 2.0) / std::tan(15.0 * kDegree);
    const double left = std::atan((100.5 - 160.0) / f), right = std::atan((219.5 - 160.0) / f);
    EXPECT_NEAR(extent->horizontalExtent, right - left, 1e-9);
    auto compass = [](double a) {
        return std::fmod(a + 4 * std::numbers::pi, 2 * std::numbers::pi);
    };
    EXPECT_NEAR(extent->leftBearing, compass(heading + left), 1e-9);
    EXPECT_NEAR(extent->rightBearing, compass(heading + right), 1e-9);
    // Nearest: the column nearest the axis (x = 159 or 160: 0.5 px off), range z / cos.
    const glm::dvec3 ray = glm::normalize(glm::dvec3(0.5 / f, -0.5 / f, -1.0));
    EXPECT_NEAR(extent->nearestDistance, axial / -ray.z, 1e-3);
    const glm::dvec3 edge = glm::normalize(glm::dvec3(-59.5 / f, -0.5 / f, -1.0));
    EXPECT_NEAR(extent->farthestDistance, axial / -edge.z, 1e-3);
    EXPECT_FALSE(ProposalExtent::measure(PixelMask(w * h, 0), depth, near, camera, w, h));
}

}  // namespace
}  // namespace sylva
