// Phenology: the leaf state by date and latitude follows the table (analytic values of
// the piecewise-linear calendar), inverts south of the equator and stays evergreen in
// the tropics.
#include <gtest/gtest.h>

#include <numbers>

#include "sylva/core/seasons/Phenology.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

PlantDate on(int year, int month, int day) {
    return PlantDate::make(year, month, day).value();
}

TEST(Phenology, DeciduousIsLeafOffInJanuaryAndLeafOnInJuly) {
    const Phenology table = Phenology::preset(LeafHabit::Deciduous);
    EXPECT_EQ(table.at(on(2026, 1, 15), 50 * kDegree).leafFraction, 0.0f);
    EXPECT_EQ(table.at(on(2026, 7, 15), 50 * kDegree).leafFraction, 1.0f);
    EXPECT_EQ(table.at(on(2026, 7, 15), 50 * kDegree).autumn, 0.0f);
    // Half way through leaf-out (day 104 → 140): half the leaves.
    EXPECT_NEAR(table.onDay(122.0).leafFraction, 0.5, 1e-6);
    // Autumn: colour full at the middle of colouring → leaf_fall, leaves still on.
    const double middle = 0.5 * (table.colouring + table.leafFall);
    EXPECT_NEAR(table.onDay(middle).autumn, 1.0, 1e-6);
    EXPECT_NEAR(table.onDay(middle).leafFraction, 1.0, 1e-6);
    EXPECT_NEAR(table.onDay(0.5 * (table.colouring + middle)).autumn, 0.5, 1e-6);
    EXPECT_NEAR(table.onDay(0.5 * (middle + table.leafFall)).leafFraction, 0.5, 1e-6);
    EXPECT_EQ(table.onDay(table.leafFall).leafFraction, 0.0f);
}

TEST(Phenology, SouthernHemisphereIsHalfAYearLater) {
    const Phenology table = Phenology::preset(LeafHabit::Deciduous);
    EXPECT_EQ(table.at(on(2026, 1, 15), -45 * kDegree).leafFraction, 1.0f);
    EXPECT_EQ(table.at(on(2026, 7, 15), -45 * kDegree).leafFraction, 0.0f);
    // Any day: the south's state is the north's half a year on.
    for (int month = 1; month <= 12; ++month) {
        const PlantDate date = on(2026, month, 10);
        double shifted = date.dayOfYear() + 182.5;
        shifted -= shifted >= 365.0 ? 365.0 : 0.0;
        EXPECT_FLOAT_EQ(table.at(date, -45 * kDegree).leafFraction,
                        table.onDay(shifted).leafFraction)
            << month;
    }
}

TEST(Phenology, TropicsAreEvergreenUnlessTheTableSaysOtherwise) {
    Phenology table = Phenology::preset(LeafHabit::Deciduous);
    EXPECT_EQ(table.at(on(2026, 1, 15), 8 * kDegree).leafFraction, 1.0f);
    EXPECT_EQ(table.at(on(2026, 7, 15), -8 * kDegree).leafFraction, 1.0f);
    EXPECT_EQ(table.at(on(2026, 10, 25), -8 * kDegree).autumn, 0.0f);
    // Between 20° and 26° the seasonal state blends in linearly.
    EXPECT_NEAR(table.at(on(2026, 1, 15), 23 * kDegree).leafFraction, 0.5, 1e-6);
    table.seasonalInTropics = true;
    EXPECT_EQ(table.at(on(2026, 1, 15), 8 * kDegree).leafFraction, 0.0f);
}

TEST(Phenology, EvergreenAndPalmKeepTheirLeaves) {
    for (LeafHabit habit : {LeafHabit::Evergreen, LeafHabit::Palm}) {
        const Phenology table = Phenology::preset(habit);
        for (int month = 1; month <= 12; ++month) {
            const LeafState state = table.at(on(2026, month, 1), 52 * kDegree);
            EXPECT_EQ(state.leafFraction, 1.0f);
            EXPECT_EQ(state.autumn, 0.0f);
        }
    }
    EXPECT_EQ(Phenology::habitOfPlantPreset("oak"), LeafHabit::Deciduous);
    EXPECT_EQ(Phenology::habitOfPlantPreset("conifer"), LeafHabit::Evergreen);
    EXPECT_EQ(Phenology::habitOfPlantPreset("palm"), LeafHabit::Palm);
}

TEST(Phenology, DaysOutOfOrderFailValidation) {
    Phenology table = Phenology::preset(LeafHabit::Deciduous);
    EXPECT_TRUE(table.validate());
    table.fullLeaf = table.leafOut - 1;
    EXPECT_EQ(table.validate().error().message,
              "leaf_out must not come after full_leaf (days of the northern-hemisphere year, "
              "January to December)");
}

}  // namespace
}  // namespace sylva
