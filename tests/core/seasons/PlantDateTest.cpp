// PlantDate: calendar arithmetic checked against Python's datetime (proleptic
// Gregorian): (date(2000,1,1) - date(1970,1,1)).days = 10957 and so on.
#include <gtest/gtest.h>

#include "sylva/core/seasons/PlantDate.h"

namespace sylva {
namespace {

PlantDate date(const char* text) {
    Result<PlantDate> parsed = PlantDate::parse(text);
    EXPECT_TRUE(parsed) << text;
    return parsed ? parsed.value() : PlantDate();
}

TEST(PlantDate, DaysSinceEpochMatchPythonDatetime) {
    EXPECT_EQ(date("1970-01-01").daysSinceEpoch(), 0);
    EXPECT_EQ(date("2000-01-01").daysSinceEpoch(), 10957);
    EXPECT_EQ(date("1969-12-31").daysSinceEpoch(), -1);
    EXPECT_EQ(date("2024-02-29").daysSinceEpoch(), 19782);
    EXPECT_EQ(date("2042-03-01").daysSinceEpoch() - date("2027-03-01").daysSinceEpoch(), 5479);
    EXPECT_NEAR(date("2042-03-01").yearsSince(date("2027-03-01")), 5479 / 365.2425, 1e-12);
}

TEST(PlantDate, DayOfYearInANonLeapCalendar) {
    EXPECT_EQ(date("2026-01-01").dayOfYear(), 0.0);
    EXPECT_EQ(date("2026-04-15").dayOfYear(), 104.0);  // tm_yday - 1 in Python
    EXPECT_EQ(date("2026-07-15").dayOfYear(), 195.0);
    EXPECT_EQ(date("2024-03-01").dayOfYear(), 59.0);  // leap years use the same table
    EXPECT_EQ(date("2024-02-29").dayOfYear(), 58.5);
    EXPECT_EQ(date("2026-12-31").dayOfYear(), 364.0);
    EXPECT_EQ(PlantDate::parseMonthDay("04-15").value(), 104.0);
    EXPECT_EQ(PlantDate::parseMonthDay("12-31").value(), 364.0);
}

TEST(PlantDate, MalformedDatesAreErrorsQuotingTheText) {
    EXPECT_EQ(PlantDate::parse("2027-02-30").error().message, "no such date: 2027-02-30");
    EXPECT_EQ(PlantDate::parse("2027-3-1").error().message,
              "'2027-3-1' is not a date (expected 2027-03-01)");
    EXPECT_EQ(PlantDate::parseMonthDay("13-01").error().message,
              "'13-01' is not a day of the year (expected month-day, e.g. \"04-20\")");
    EXPECT_FALSE(PlantDate::parseMonthDay("02-29"));
    EXPECT_FALSE(PlantDate::parseMonthDay("4-20"));
    Result<DateTime> timeOnly = DateTime::parse("14:30:00");
    ASSERT_TRUE(timeOnly);
    EXPECT_FALSE(PlantDate::fromDateTime(timeOnly.value()));
    Result<DateTime> full = DateTime::parse("2024-09-15T08:30:00-03:00");
    ASSERT_TRUE(full);
    EXPECT_EQ(PlantDate::fromDateTime(full.value()).value().text(), "2024-09-15");
}

}  // namespace
}  // namespace sylva
