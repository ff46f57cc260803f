#include "sylva/core/scene/Camera.h"

#include <gtest/gtest.h>

#include <memory>
#include <numbers>

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
const auto kFile = std::make_shared<const std::string>("cam.sylva");

Value geo(double latDeg, double lonDeg, std::optional<double> height) {
    Value v;
    v.data = GeoPosition{latDeg * kDegree, lonDeg * kDegree, height};
    return v;
}
Value quantity(double value, Dimension dimension) {
    Value v;
    v.data = Quantity{value, dimension};
    return v;
}

Block camera(std::vector<std::pair<std::string, Value>> attributes) {
    Block block;
    block.keyword = "camera";
    block.name = "cam";
    block.location = {kFile, 3, 8, 3};
    std::uint32_t line = 4;
    for (auto& [name, value] : attributes) {
        value.location = {kFile, line, 17, 1};
        block.attributes.push_back({name, value, {kFile, line, 5, std::uint32_t(name.size())}});
        ++line;
    }
    return block;
}

Result<double> noTerrain(double, double) {
    return Error{"no terrain in this test"};
}

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(Camera, HeadingZeroPitchZeroLooksNorthAlongTheHorizon) {
    const Block block = camera({{"position", geo(45, 10, 1000.0)},
                                {"heading", quantity(0, Dimension::Angle)},
                                {"pitch", quantity(0, Dimension::Angle)},
                                {"fov", quantity(60 * kDegree, Dimension::Angle)}});
    Result<Camera> result = Camera::fromBlock(block, noTerrain);
    ASSERT_TRUE(result) << result.error().message;
    const Camera& c = result.value();
    const glm::dmat3 frame = Ellipsoid::localFrame(45 * kDegree, 10 * kDegree);
    expectNear(-c.axes[2], frame[1], 1e-12);  // forward = north
    expectNear(c.axes[1], frame[2], 1e-12);   // up = local up
    expectNear(c.axes[0], frame[0], 1e-12);   // right = east
    EXPECT_NEAR(c.verticalFov, 60 * kDegree, 1e-15);
    EXPECT_DOUBLE_EQ(c.geodetic.height, 1000.0);
    expectNear(c.position, Ellipsoid::toEcef({45 * kDegree, 10 * kDegree, 1000.0}), 1e-6);

    // heading 90 deg looks east, pitch -90 deg straight down.
    Result<Camera> east =
        Camera::fromBlock(camera({{"position", geo(45, 10, 1000.0)},
                                  {"heading", quantity(90 * kDegree, Dimension::Angle)}}),
                          noTerrain);
    ASSERT_TRUE(east) << east.error().message;
    expectNear(-east->axes[2], frame[0], 1e-12);
    Result<Camera> down =
        Camera::fromBlock(camera({{"position", geo(45, 10, 1000.0)},
                                  {"pitch", quantity(-90 * kDegree, Dimension::Angle)}}),
                          noTerrain);
    ASSERT_TRUE(down) << down.error().message;
    expectNear(-down->axes[2], -frame[2], 1e-12);
}

TEST(Camera, LookAtPointsAtTheTarget) {
    const Block block = camera({{"position", geo(25, 15, 800e3)}, {"look_at", geo(22, 12, 100.0)}});
    Result<Camera> result = Camera::fromBlock(block, noTerrain);
    ASSERT_TRUE(result) << result.error().message;
    const glm::dvec3 target = Ellipsoid::toEcef({22 * kDegree, 12 * kDegree, 100.0});
    expectNear(-result->axes[2], glm::normalize(target - result->position), 1e-12);
    // Orthonormal, and "up" has no downward tilt against the local up.
    const glm::dmat3 axes = result->axes;
    EXPECT_NEAR(glm::dot(axes[0], axes[1]), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(axes[0]), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(axes[0], Ellipsoid::surfaceNormal(25 * kDegree, 15 * kDegree)), 0.0,
                1e-12);

    // A target without height stands on the terrain from the callback.
    double asked = 0;
    Result<Camera> onGround = Camera::fromBlock(
        camera({{"position", geo(25, 15, 800e3)}, {"look_at", geo(22, 12, std::nullopt)}}),
        [&](double lat, double) -> Result<double> {
            asked = lat;
            return 250.0;
        });
    ASSERT_TRUE(onGround);
    EXPECT_DOUBLE_EQ(asked, 22 * kDegree);
    const glm::dvec3 groundTarget = Ellipsoid::toEcef({22 * kDegree, 12 * kDegree, 250.0});
    expectNear(-onGround->axes[2], glm::normalize(groundTarget - onGround->position), 1e-12);
}

TEST(Camera, EyeHeightAddsToTheTerrainHeight) {
    const Block block = camera({{"position", geo(33.25, 2.25, std::nullopt)},
                                {"eye_height", quantity(1.7, Dimension::Length)}});
    double askedLat = 0, askedLon = 0;
    Result<Camera> result = Camera::fromBlock(block, [&](double lat, double lon) -> Result<double> {
        askedLat = lat;
        askedLon = lon;
        return 812.5;
    });
    ASSERT_TRUE(result) << result.error().message;
    EXPECT_DOUBLE_EQ(askedLat, 33.25 * kDegree);
    EXPECT_DOUBLE_EQ(askedLon, 2.25 * kDegree);
    EXPECT_DOUBLE_EQ(result->geodetic.height, 814.2);

    // The terrain callback's error is passed on, located at eye_height.
    Result<Camera> failing = Camera::fromBlock(block, noTerrain);
    ASSERT_FALSE(failing);
    EXPECT_EQ(
        failing.error().message,
        "cam.sylva:5:17: camera 'cam': cannot find the terrain height: no terrain in this test");
}

TEST(Camera, MissingHeightOrPositionIsAnError) {
    Result<Camera> noHeight =
        Camera::fromBlock(camera({{"position", geo(10, 10, std::nullopt)}}), noTerrain);
    ASSERT_FALSE(noHeight);
    // Without a height the viewpoint stands 1.5 m above the terrain, which it must find.
    EXPECT_EQ(noHeight.error().message,
              "cam.sylva:4:17: camera 'cam': cannot find the terrain height: no terrain in this "
              "test");
    Result<Camera> standing =
        Camera::fromBlock(camera({{"position", geo(10, 10, std::nullopt)}}),
                          [](double, double) -> Result<double> { return 80.0; });
    ASSERT_TRUE(standing) << standing.error().message;
    EXPECT_DOUBLE_EQ(standing->geodetic.height, 81.5);
    EXPECT_DOUBLE_EQ(standing->eyeHeight, 1.5);
    EXPECT_DOUBLE_EQ(standing->groundHeight, 80.0);
    Result<Camera> noPosition =
        Camera::fromBlock(camera({{"fov", quantity(1.0, Dimension::Angle)}}), noTerrain);
    ASSERT_FALSE(noPosition);
    EXPECT_NE(noPosition.error().message.find("cam.sylva:3:8: camera 'cam': missing 'position'"),
              std::string::npos)
        << noPosition.error().message;
}

}  // namespace
}  // namespace sylva
