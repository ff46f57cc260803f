#include "sylva/core/tiles/TileKey.h"

#include <gtest/gtest.h>

#include <numbers>

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(TileKey, ColumnsAndRowsPerLevelAndReduction) {
    EXPECT_EQ(TileKey::columns(0, 0), 2);
    EXPECT_EQ(TileKey::rows(0), 1);
    EXPECT_EQ(TileKey::columns(0, 1), 1);
    EXPECT_EQ(TileKey::columns(3, 0), 16);
    EXPECT_EQ(TileKey::columns(3, 2), 4);
    EXPECT_EQ(TileKey::columns(3, 4), 1);
    EXPECT_EQ(TileKey::rows(3), 8);
    const TileKey key{5, 1, 12, 7};
    EXPECT_EQ(key.columns(), 32);
    EXPECT_EQ(key.rows(), 32);
}

TEST(TileKey, BoundsInRadians) {
    const TileKey first{0, 0, 0, 0};
    EXPECT_DOUBLE_EQ(first.west(), -kPi);
    EXPECT_DOUBLE_EQ(first.east(), 0.0);
    EXPECT_DOUBLE_EQ(first.north(), kPi / 2);
    EXPECT_DOUBLE_EQ(first.south(), -kPi / 2);

    const TileKey key{2, 0, 3, 1};  // 8 x 4 tiles of 45 degrees
    EXPECT_DOUBLE_EQ(key.west(), -kPi + 3 * kPi / 4);
    EXPECT_DOUBLE_EQ(key.east(), -kPi + 4 * kPi / 4);
    EXPECT_DOUBLE_EQ(key.north(), kPi / 4);
    EXPECT_DOUBLE_EQ(key.south(), 0.0);

    const TileKey reduced{2, 2, 1, 0};  // 2 columns of 180 degrees
    EXPECT_DOUBLE_EQ(reduced.west(), 0.0);
    EXPECT_DOUBLE_EQ(reduced.east(), kPi);

    const TileKey last{4, 0, 31, 15};
    EXPECT_DOUBLE_EQ(last.east(), kPi);
    EXPECT_DOUBLE_EQ(last.south(), -kPi / 2);
}

TEST(TileKey, ParentContainsChild) {
    EXPECT_EQ((TileKey{3, 0, 5, 3}.parent()), (TileKey{2, 0, 2, 1}));
    EXPECT_EQ((TileKey{3, 1, 5, 6}.parent()), (TileKey{2, 1, 2, 3}));
    // The reduction has to shrink with the level: columns stay the same.
    EXPECT_EQ((TileKey{2, 3, 0, 3}.parent()), (TileKey{1, 2, 0, 1}));
    EXPECT_EQ((TileKey{0, 0, 1, 0}.parent()), (TileKey{0, 0, 1, 0}));
    for (int level = 1; level <= 6; ++level) {
        for (int k = 0; k <= level + 1; ++k) {
            for (int x = 0; x < TileKey::columns(level, k); ++x) {
                for (int y = 0; y < TileKey::rows(level); ++y) {
                    const TileKey child{level, k, x, y};
                    const TileKey parent = child.parent();
                    ASSERT_TRUE(parent.valid()) << child.toString();
                    EXPECT_EQ(parent.level, level - 1);
                    EXPECT_LE(parent.west(), child.west() + 1e-12) << child.toString();
                    EXPECT_GE(parent.east(), child.east() - 1e-12) << child.toString();
                    EXPECT_GE(parent.north(), child.north() - 1e-12) << child.toString();
                    EXPECT_LE(parent.south(), child.south() + 1e-12) << child.toString();
                }
            }
        }
    }
}

TEST(TileKey, Valid) {
    EXPECT_TRUE((TileKey{0, 0, 1, 0}.valid()));
    EXPECT_TRUE((TileKey{0, 1, 0, 0}.valid()));
    EXPECT_FALSE((TileKey{0, 0, 2, 0}.valid()));
    EXPECT_FALSE((TileKey{0, 0, 0, 1}.valid()));
    EXPECT_FALSE((TileKey{0, 2, 0, 0}.valid()));
    EXPECT_FALSE((TileKey{-1, 0, 0, 0}.valid()));
    EXPECT_FALSE((TileKey{31, 0, 0, 0}.valid()));
    EXPECT_FALSE((TileKey{3, 0, -1, 0}.valid()));
    EXPECT_TRUE((TileKey{3, 4, 0, 7}.valid()));
    EXPECT_FALSE((TileKey{3, 4, 1, 7}.valid()));
    EXPECT_FALSE((TileKey{3, 5, 0, 0}.valid()));
}

TEST(TileKey, DeepestLevelHasPositiveColumnCount) {
    EXPECT_GT(TileKey::columns(TileKey::kMaxLevel, 0), 0);
    EXPECT_TRUE((TileKey{TileKey::kMaxLevel, 0, 0, 0}.valid()));
}

TEST(TileKey, ToString) {
    EXPECT_EQ((TileKey{5, 1, 12, 7}.toString()), "L5/k1/x12/y7");
    EXPECT_EQ((TileKey{}.toString()), "L0/k0/x0/y0");
}

}  // namespace
}  // namespace sylva
