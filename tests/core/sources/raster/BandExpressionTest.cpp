#include "sylva/core/sources/raster/BandExpression.h"

#include <gtest/gtest.h>

namespace sylva {
namespace {

std::optional<int> names(std::string_view name) {
    if (name == "x")
        return 0;
    if (name == "y")
        return 1;
    if (name == "nir")
        return 2;
    if (name == "red")
        return 3;
    return std::nullopt;
}

double eval(std::string_view text, std::array<double, 4> v = {2, 3, 0.6, 0.2}) {
    Result<BandExpression> e = BandExpression::parse(text, names);
    EXPECT_TRUE(e) << (e ? "" : e.error().message);
    return e ? e->evaluate(v.data()) : -1e9;
}

std::string error(std::string_view text) {
    Result<BandExpression> e = BandExpression::parse(text, names);
    return e ? std::string("(parsed)") : e.error().message;
}

TEST(BandExpression, ArithmeticPrecedenceAndFunctions) {
    EXPECT_DOUBLE_EQ(eval("1 + 2 * 3"), 7);
    EXPECT_DOUBLE_EQ(eval("(1 + 2) * 3"), 9);
    EXPECT_DOUBLE_EQ(eval("-x ^ 2"), -4);
    EXPECT_DOUBLE_EQ(eval("2 ^ 3 ^ 2"), 512);  // right associative
    EXPECT_DOUBLE_EQ(eval("x - y - 1"), -2);
    EXPECT_DOUBLE_EQ(eval("y / x"), 1.5);
    EXPECT_DOUBLE_EQ(eval("x / 0"), 0);
    EXPECT_DOUBLE_EQ(eval("min(x, y) + max(x, y)"), 5);
    EXPECT_DOUBLE_EQ(eval("abs(x - y) + sqrt(4) + sqrt(-1)"), 3);
    EXPECT_DOUBLE_EQ(eval("clamp(y, 0, 2.5)"), 2.5);
    EXPECT_DOUBLE_EQ(eval("1.5e1"), 15);
}

TEST(BandExpression, ComparisonsAndLogic) {
    EXPECT_DOUBLE_EQ(eval("x < y"), 1);
    EXPECT_DOUBLE_EQ(eval("x >= y"), 0);
    EXPECT_DOUBLE_EQ(eval("x == 2 && y != 2"), 1);
    EXPECT_DOUBLE_EQ(eval("x > 5 || y > 5"), 0);
    EXPECT_DOUBLE_EQ(eval("not x > 5 and !(y > 5)"), 1);
    EXPECT_DOUBLE_EQ(eval("x + 1 > y"), 0);
    EXPECT_DOUBLE_EQ(eval("(nir - red) / (nir + red) > 0.35"), 1);
    EXPECT_DOUBLE_EQ(eval("(nir - red) / (nir + red)"), 0.5);
}

TEST(BandExpression, ErrorsNameTheProblemAndColumn) {
    EXPECT_EQ(error(""), "empty expression");
    EXPECT_EQ(error("x +"), "unexpected end of expression at column 4");
    EXPECT_EQ(error("x + green"), "unknown name 'green' at column 5");
    EXPECT_EQ(error("(x + y"), "expected ')' at column 7");
    EXPECT_EQ(error("x y"), "unexpected 'y' at column 3");
    EXPECT_EQ(error("exp(x)"), "unknown function 'exp' at column 1");
    EXPECT_EQ(error("min(x)"), "min() takes 2 arguments at column 6");
    EXPECT_EQ(error("x # 2"), "unexpected '#' at column 3");
    EXPECT_EQ(error("system(\"rm\")"), "unknown function 'system' at column 1");
}

}  // namespace
}  // namespace sylva
