#include "sylva/core/scene/CameraPath.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

Value quantity(double value, Dimension dimension) {
    Value v;
    v.data = Quantity{value, dimension};
    return v;
}

struct KeySpec {
    KeySpec(double atSeconds, double latitude, double longitude, std::optional<double> heightMetres,
            std::optional<double> eyeHeightMetres = std::nullopt, double heading = 0)
        : at(atSeconds),
          latitudeDegrees(latitude),
          longitudeDegrees(longitude),
          height(heightMetres),
          eyeHeight(eyeHeightMetres),
          headingDegrees(heading) {}
    double at;
    double latitudeDegrees, longitudeDegrees;
    std::optional<double> height;
    std::optional<double> eyeHeight;
    double headingDegrees;
};

Block pathBlock(const std::vector<KeySpec>& specs, const char* interpolate = "catmull_rom",
                double fps = 25) {
    Block block;
    block.keyword = "path";
    block.name = "flight";
    auto file = std::make_shared<const std::string>("test.sylva");
    ValueList keys;
    std::uint32_t line = 10;
    for (const KeySpec& spec : specs) {
        ValueObject object;
        object.emplace_back("at", quantity(spec.at, Dimension::Time));
        Value position;
        position.data = GeoPosition{spec.latitudeDegrees * kDegree, spec.longitudeDegrees * kDegree,
                                    spec.height};
        object.emplace_back("position", position);
        if (spec.eyeHeight) {
            object.emplace_back("eye_height", quantity(*spec.eyeHeight, Dimension::Length));
        }
        object.emplace_back("heading", quantity(spec.headingDegrees * kDegree, Dimension::Angle));
        Value key;
        key.data = std::move(object);
        key.location = SourceLocation{file, line++, 5, 1};
        keys.push_back(std::move(key));
    }
    Value keysValue;
    keysValue.data = std::move(keys);
    keysValue.location = SourceLocation{file, 9, 12, 1};
    block.attributes.push_back({"keys", keysValue, keysValue.location});
    Value mode;
    mode.data = Word{interpolate};
    block.attributes.push_back({"interpolate", mode, {}});
    block.attributes.push_back({"fps", quantity(fps, Dimension::None), {}});
    block.location = SourceLocation{file, 8, 6, 6};
    return block;
}

const Camera::TerrainHeight kFlat = [](double, double) -> Result<double> { return 0.0; };

Camera sampleOk(const CameraPath& path, double t, const Camera::TerrainHeight& terrain = kFlat) {
    Result<Camera> camera = path.sample(t, terrain);
    EXPECT_TRUE(camera.ok()) << (camera.ok() ? "" : camera.error().message);
    return camera.ok() ? camera.value() : Camera{};
}

TEST(CameraPathTest, LinearFollowsTheGreatCircle) {
    auto path =
        CameraPath::fromBlock(pathBlock({{0, 0, 0, 1000.0}, {10, 0, 90, 3000.0}}, "linear"));
    ASSERT_TRUE(path.ok());
    const Camera middle = sampleOk(path.value(), 5.0);
    EXPECT_NEAR(middle.geodetic.latitude, 0.0, 1e-12);
    EXPECT_NEAR(middle.geodetic.longitude / kDegree, 45.0, 1e-9);
    EXPECT_NEAR(middle.geodetic.height, 2000.0, 1e-6);
    EXPECT_EQ(path.value().frameCount(), 251);
}

TEST(CameraPathTest, CrossesTheAntimeridianAndThePoleTheShortWay) {
    auto across = CameraPath::fromBlock(
        pathBlock({{0, 10, 179, 500.0}, {4, 10, -179, 500.0}}, "catmull_rom"));
    ASSERT_TRUE(across.ok());
    for (double t = 0; t <= 4.0; t += 0.25) {
        EXPECT_GE(std::abs(sampleOk(across.value(), t).geodetic.longitude / kDegree), 179.0 - 1e-9)
            << t;
    }
    auto overPole =
        CameraPath::fromBlock(pathBlock({{0, 89, 0, 500.0}, {4, 89, 180, 500.0}}, "linear"));
    ASSERT_TRUE(overPole.ok());
    EXPECT_NEAR(sampleOk(overPole.value(), 2.0).geodetic.latitude / kDegree, 90.0, 1e-6);
}

TEST(CameraPathTest, CatmullRomPassesThroughKeysWithContinuousVelocity) {
    auto path = CameraPath::fromBlock(pathBlock({{0, -8.0, -34.9, 800.0},
                                                 {3, -8.01, -34.85, 400.0},
                                                 {5, -7.98, -34.83, 200.0},
                                                 {9, -8.0, -34.8, 900.0}}));
    ASSERT_TRUE(path.ok());
    const Camera atKey = sampleOk(path.value(), 3.0);
    EXPECT_NEAR(atKey.geodetic.latitude / kDegree, -8.01, 1e-9);
    EXPECT_NEAR(atKey.geodetic.longitude / kDegree, -34.85, 1e-9);
    EXPECT_NEAR(atKey.geodetic.height, 400.0, 1e-6);
    for (double key : {3.0, 5.0}) {
        const double h = 1e-3;
        const glm::dvec3 before =
            (sampleOk(path.value(), key).position - sampleOk(path.value(), key - h).position) / h;
        const glm::dvec3 after =
            (sampleOk(path.value(), key + h).position - sampleOk(path.value(), key).position) / h;
        // Speeds are ~1-3 km/s here; the one-sided differences differ by O(h * acceleration).
        EXPECT_LT(glm::length(after - before), 0.01 * glm::length(before)) << key;
    }
    // No jump between consecutive frames anywhere.
    double largest = 0;
    for (int i = 1; i < path.value().frameCount(); ++i) {
        const glm::dvec3 a = sampleOk(path.value(), path.value().frameTime(i - 1)).position;
        const glm::dvec3 b = sampleOk(path.value(), path.value().frameTime(i)).position;
        largest = std::max(largest, glm::length(b - a));
    }
    EXPECT_LT(largest, 200.0);  // metres per 1/25 s at < 5 km/s
}

TEST(CameraPathTest, EyeHeightFollowsTheTerrain) {
    const Camera::TerrainHeight hills = [](double latitude, double longitude) -> Result<double> {
        return 300.0 + 200.0 * std::sin(latitude * 5000.0) * std::cos(longitude * 3000.0);
    };
    auto path = CameraPath::fromBlock(pathBlock(
        {{0, 45.0, 7.0, std::nullopt, 1.7}, {20, 45.02, 7.03, std::nullopt, 1.7}}, "catmull_rom"));
    ASSERT_TRUE(path.ok());
    for (double t = 0; t <= 20.0; t += 0.7) {
        const Camera camera = sampleOk(path.value(), t, hills);
        const double ground = hills(camera.geodetic.latitude, camera.geodetic.longitude).value();
        EXPECT_NEAR(camera.geodetic.height - ground, 1.7, 1e-9) << t;
    }
}

TEST(CameraPathTest, HeadingTurnsTheShortWayWithTheHorizonLevel) {
    auto path = CameraPath::fromBlock(pathBlock(
        {{0, 40, 10, 100.0, std::nullopt, 350}, {2, 40, 10, 100.0, std::nullopt, 10}}, "linear"));
    ASSERT_TRUE(path.ok());
    const Camera middle = sampleOk(path.value(), 1.0);
    const glm::dmat3 frame =
        Ellipsoid::localFrame(middle.geodetic.latitude, middle.geodetic.longitude);
    const glm::dvec3 forward = glm::transpose(frame) * -middle.axes[2];  // east, north, up
    EXPECT_NEAR(std::atan2(forward.x, forward.y) / kDegree, 0.0, 1e-6);  // due north
    const glm::dvec3 right = glm::transpose(frame) * middle.axes[0];
    EXPECT_NEAR(right.z, 0.0, 1e-9);  // no roll
}

TEST(CameraPathTest, ExactErrors) {
    auto one = CameraPath::fromBlock(pathBlock({{0, 0, 0, 100.0}}));
    ASSERT_FALSE(one.ok());
    EXPECT_EQ(one.error().message,
              "test.sylva:9:12: path 'flight': a path needs at least two keys");
    auto backwards = CameraPath::fromBlock(pathBlock({{0, 0, 0, 100.0}, {0, 0, 1, 100.0}}));
    ASSERT_FALSE(backwards.ok());
    EXPECT_EQ(backwards.error().message,
              "test.sylva:11:5: path 'flight': key times must ascend (this key is not after the "
              "one before)");
    auto noHeight = CameraPath::fromBlock(pathBlock({{0, 0, 0, 100.0}, {1, 0, 1, std::nullopt}}));
    ASSERT_FALSE(noHeight.ok());
    EXPECT_EQ(noHeight.error().message,
              "test.sylva:11:5: path 'flight': the key needs a height: write geo(lat, lon, height) "
              "or set eye_height");
    auto low = CameraPath::fromBlock(pathBlock({{0, 0, 0, 100.0}, {2, 0, 0.01, 100.0}}, "linear"));
    ASSERT_TRUE(low.ok());
    const Camera::TerrainHeight mountain = [](double, double longitude) -> Result<double> {
        return longitude > 0.005 * kDegree ? 150.0 : 0.0;
    };
    Result<Camera> below = low.value().sample(1.5, mountain);
    ASSERT_FALSE(below.ok());
    EXPECT_EQ(below.error().message,
              "path 'flight': at 1.50 s the camera is 50.0 m below the terrain");
}

}  // namespace
}  // namespace sylva
