#include "sylva/core/scene/DateTime.h"

#include <gtest/gtest.h>

namespace sylva {
namespace {

TEST(DateTimeTest, ParsesTheLanguageForms) {
    auto full = DateTime::parse("2024-06-21T09:00:00-03:00");
    ASSERT_TRUE(full.ok());
    EXPECT_TRUE(full.value().hasDate() && full.value().hasTime() && full.value().hasZone());
    EXPECT_EQ(full.value().unixSeconds().value(), 1718971200.0);  // 12:00 UTC
    EXPECT_EQ(full.value().text(), "2024-06-21T09:00:00-03:00");

    EXPECT_EQ(DateTime::parse("2024-06-21T12:00Z").value().unixSeconds().value(), 1718971200.0);
    EXPECT_EQ(DateTime::parse("2000-02-29T23:59:59+00:00").value().unixSeconds().value(),
              951868799.0);

    auto date = DateTime::parse("2024-12-24");
    ASSERT_TRUE(date.ok());
    EXPECT_FALSE(date.value().hasTime());
    auto time = DateTime::parse("14:30:00+01:00");
    ASSERT_TRUE(time.ok());
    EXPECT_FALSE(time.value().hasDate());
    EXPECT_EQ(date.value().withTimeOf(time.value()).text(), "2024-12-24T14:30:00+01:00");
}

TEST(DateTimeTest, ExactErrors) {
    EXPECT_EQ(DateTime::parse("2024-13-01T10:00").error().message,
              "invalid date/time '2024-13-01T10:00': no such day");
    EXPECT_EQ(DateTime::parse("2023-02-29").error().message,
              "invalid date/time '2023-02-29': no such day");
    EXPECT_EQ(DateTime::parse("25:61").error().message,
              "invalid date/time '25:61': time of day out of range");
    EXPECT_EQ(DateTime::parse("2024-06-21T10:00+15:00").error().message,
              "invalid date/time '2024-06-21T10:00+15:00': UTC offset out of range");
    EXPECT_EQ(DateTime::parse("2024-06-21T10:00:00").value().unixSeconds().error().message,
              "time 2024-06-21T10:00:00 has no zone: add a UTC offset such as "
              "2024-06-21T10:00:00+00:00 or Z");
    EXPECT_EQ(DateTime::parse("10:00").value().unixSeconds().error().message,
              "time 10:00:00 has no date");
    EXPECT_EQ(DateTime::parse("2024-06-21").value().unixSeconds().error().message,
              "date 2024-06-21 has no time of day");
}

}  // namespace
}  // namespace sylva
