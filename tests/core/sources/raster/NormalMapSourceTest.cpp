#include "sylva/core/sources/raster/NormalMapSource.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scheduler/TileEvaluator.h"

namespace sylva {
namespace {

// Elevation given as a function of (latitude, longitude) in radians.
class FunctionElevation final : public Source {
public:
    FunctionElevation(std::uint64_t tag, std::function<double(double, double)> f)
        : Source("f", "function", PortType::Elevation, 1), f_(std::move(f)) {
        setParameterHash(tag);
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        for (int iy = -format.border; iy < format.size + format.border; ++iy) {
            for (int ix = -format.border; ix < format.size + format.border; ++ix) {
                tile->at(ix, iy, 0) =
                    static_cast<float>(f_(tile->texelLatitude(iy), tile->texelLongitude(ix)));
            }
        }
        return TilePointer(std::move(tile));
    }

private:
    std::function<double(double, double)> f_;
};

TEST(NormalMapSource, ConstantHeightGivesTheEllipsoidNormal) {
    const FunctionElevation flat(1, [](double, double) { return 1234.0; });
    const NormalMapSource normals("n", &flat, 3.0);
    TileEvaluator evaluator(TileFormat{16, 2});
    for (const TileKey key : {TileKey{3, 0, 2, 1}, TileKey{3, 0, 15, 7}, TileKey{2, 0, 4, 0}}) {
        Result<TilePointer> tile = evaluator.tile(normals, key);
        ASSERT_TRUE(tile) << tile.error().message;
        const ImageTile& n = *tile.value();
        ASSERT_EQ(n.channels(), 3);
        for (int iy = -n.border(); iy < n.size() + n.border(); ++iy) {
            for (int ix = -n.border(); ix < n.size() + n.border(); ++ix) {
                const glm::dvec3 up =
                    Ellipsoid::surfaceNormal(n.texelLatitude(iy), n.texelLongitude(ix));
                EXPECT_NEAR(n.at(ix, iy, 0), up.x, 1e-6)
                    << key.toString() << " " << ix << "," << iy;
                EXPECT_NEAR(n.at(ix, iy, 1), up.y, 1e-6);
                EXPECT_NEAR(n.at(ix, iy, 2), up.z, 1e-6);
            }
        }
    }
}

TEST(NormalMapSource, LinearSlopeInLatitudeTiltsByAtanK) {
    const TileKey key{6, 0, 70, 20};  // northern hemisphere, ~2.8 degrees
    ImageTile probe(key, 16, 2, 1);
    const int centreRow = 8;
    const double lat0 = probe.texelLatitude(centreRow);
    ASSERT_GT(lat0, 0.0);
    for (double k : {0.05, 0.3, -0.2}) {
        // h rises northwards by k metres per metre of meridian arc (near lat0).
        const FunctionElevation ramp(static_cast<std::uint64_t>(k * 1000 + 5000),
                                     [k, lat0](double lat, double) {
                                         return k * (lat - lat0) * Ellipsoid::meridionalRadius(lat);
                                     });
        const NormalMapSource normals("n", &ramp, 1.0);
        TileEvaluator evaluator(TileFormat{16, 2});
        Result<TilePointer> tile = evaluator.tile(normals, key);
        ASSERT_TRUE(tile) << tile.error().message;
        const ImageTile& n = *tile.value();
        for (int ix = 0; ix < n.size(); ++ix) {
            const double lon = n.texelLongitude(ix);
            const glm::dmat3 frame = Ellipsoid::localFrame(lat0, lon);
            const glm::dvec3 normal(n.at(ix, centreRow, 0), n.at(ix, centreRow, 1),
                                    n.at(ix, centreRow, 2));
            const double tilt = std::acos(std::clamp(glm::dot(normal, frame[2]), -1.0, 1.0));
            EXPECT_NEAR(tilt, std::atan(std::abs(k)), 1e-4) << "k " << k << " ix " << ix;
            // Rising to the north: the normal leans south (towards the equator here);
            // falling to the north: it leans towards the pole. No east component.
            EXPECT_NEAR(glm::dot(normal, frame[1]), -std::sin(std::atan(k)), 1e-4);
            EXPECT_NEAR(glm::dot(normal, frame[0]), 0.0, 1e-5);
        }
    }
}

TEST(NormalMapSource, ContentHashDependsOnInputAndExaggeration) {
    const FunctionElevation a(1, [](double, double) { return 0.0; });
    const FunctionElevation b(2, [](double, double) { return 0.0; });
    EXPECT_EQ(NormalMapSource("x", &a, 1.0).contentHash(),
              NormalMapSource("y", &a, 1.0).contentHash());
    EXPECT_NE(NormalMapSource("x", &a, 1.0).contentHash(),
              NormalMapSource("x", &b, 1.0).contentHash());
    EXPECT_NE(NormalMapSource("x", &a, 1.0).contentHash(),
              NormalMapSource("x", &a, 2.0).contentHash());
}

}  // namespace
}  // namespace sylva
