// GrowthCurve: piecewise-linear interpolation by age (checked against hand-computed
// values), absent before planting, the last size after the last age, metres converted
// by the model's height; malformed curves are errors located at the offending value.
#include <gtest/gtest.h>

#include <memory>

#include "sylva/core/seasons/GrowthCurve.h"

namespace sylva {
namespace {

Value number(double value, Dimension dimension = Dimension::None, std::uint32_t line = 1) {
    Value v;
    v.data = Quantity{value, dimension};
    v.location.file = std::make_shared<const std::string>("p.sylva");
    v.location.line = line;
    v.location.column = 7;
    return v;
}

Value point(double age, const char* heightKey, double height, std::uint32_t line) {
    ValueObject record;
    record.emplace_back("age", number(age, Dimension::None, line));
    record.emplace_back(
        heightKey,
        number(height, std::string(heightKey) == "height" ? Dimension::Length : Dimension::Ratio,
               line));
    Value v;
    v.data = record;
    v.location = number(0, Dimension::None, line).location;
    return v;
}

Value curve(std::vector<Value> points) {
    Value v;
    v.data = ValueList(std::move(points));
    return v;
}

TEST(GrowthCurve, InterpolatesLinearlyBetweenAges) {
    Result<GrowthCurve> read = GrowthCurve::read(
        curve({point(0, "size", 0.1, 1), point(10, "height", 6.0, 2), point(30, "size", 1.0, 3)}));
    ASSERT_TRUE(read) << read.error().message;
    const GrowthCurve& c = read.value();
    const double modelHeight = 12.0;
    EXPECT_FALSE(c.at(-0.01, modelHeight));  // not planted yet
    EXPECT_DOUBLE_EQ(c.at(0.0, modelHeight)->height, 0.1);
    EXPECT_DOUBLE_EQ(c.at(5.0, modelHeight)->height, 0.1 + (0.5 - 0.1) * 0.5);
    EXPECT_DOUBLE_EQ(c.at(10.0, modelHeight)->height, 0.5);  // 6 m of 12 m
    EXPECT_DOUBLE_EQ(c.at(20.0, modelHeight)->height, 0.75);
    EXPECT_DOUBLE_EQ(c.at(80.0, modelHeight)->height, 1.0);
    EXPECT_DOUBLE_EQ(c.at(20.0, modelHeight)->crown, 0.75);  // crown follows the height
}

TEST(GrowthCurve, StandardCurveAtFifteenYears) {
    EXPECT_DOUBLE_EQ(GrowthCurve::standard().at(15.0, 10.0)->height, 0.70);
}

TEST(GrowthCurve, NonIncreasingAgesAreLocatedErrors) {
    SourceLocation problem;
    Result<GrowthCurve> read = GrowthCurve::read(
        curve({point(0, "size", 0.1, 1), point(10, "size", 0.5, 2), point(10, "size", 0.6, 3)}),
        &problem);
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error().message, "growth: ages must increase, but age 10 follows age 10");
    EXPECT_EQ(problem.toString(), "p.sylva:3:7");
}

TEST(GrowthCurve, NegativeHeightsAreLocatedErrors) {
    SourceLocation problem;
    Result<GrowthCurve> read = GrowthCurve::read(curve({point(0, "height", -1.0, 4)}), &problem);
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error().message, "growth: ages, heights and fractions must not be negative");
    EXPECT_EQ(problem.line, 4u);
}

}  // namespace
}  // namespace sylva
