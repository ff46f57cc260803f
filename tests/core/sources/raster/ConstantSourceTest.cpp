#include "sylva/core/sources/raster/ConstantSource.h"

#include <gtest/gtest.h>

#include "sylva/core/scheduler/TileEvaluator.h"

namespace sylva {
namespace {

TEST(ConstantSource, ElevationAndColourFillEveryTexel) {
    const ConstantSource height("h", -12.5);
    const ConstantSource colour("c", glm::vec4(0.25f, 0.5f, 0.75f, 1.0f));
    EXPECT_EQ(height.output(), PortType::Elevation);
    EXPECT_EQ(height.channels(), 1);
    EXPECT_EQ(colour.output(), PortType::Image);
    EXPECT_EQ(colour.channels(), 4);
    EXPECT_NE(height.contentHash(), ConstantSource("h", -12.0).contentHash());
    TileEvaluator evaluator(TileFormat{8, 2});
    TileKey key;
    key.level = 3;
    key.x = 5;
    key.y = 2;
    const ImageTile& h = *evaluator.tile(height, key).value();
    const ImageTile& c = *evaluator.tile(colour, key).value();
    for (int iy = -2; iy < 10; ++iy) {
        for (int ix = -2; ix < 10; ++ix) {
            EXPECT_EQ(h.at(ix, iy, 0), -12.5f);
            EXPECT_EQ(c.at(ix, iy, 0), 0.25f);
            EXPECT_EQ(c.at(ix, iy, 1), 0.5f);
            EXPECT_EQ(c.at(ix, iy, 2), 0.75f);
            EXPECT_EQ(c.at(ix, iy, 3), 1.0f);
        }
    }
}

}  // namespace
}  // namespace sylva
