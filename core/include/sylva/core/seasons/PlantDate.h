// PlantDate: a calendar day (proleptic Gregorian, no time of day, no zone) for the
// seasons and growth of plants: the render date, a planting date, and days of the year
// of a phenology table ("04-20"). Plants change over days, so the hours and the zone of
// a view's time are dropped (the date as written, in the view's own zone).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "sylva/core/base/Result.h"
#include "sylva/core/scene/DateTime.h"

namespace sylva {

class PlantDate {
public:
    static constexpr double kDaysPerYear = 365.2425;   // mean Gregorian year
    static constexpr double kDaysInYearTable = 365.0;  // days of year of a non-leap year

    PlantDate() = default;
    // Fails (naming the fields) for month 13, 30 February and the like.
    static Result<PlantDate> make(int year, int month, int day);
    // The date part of a DateTime; fails when it has none (a time of day only).
    static Result<PlantDate> fromDateTime(const DateTime& time);
    // "2027-03-01" (also the date part of "2027-03-01T10:00:00+01:00").
    static Result<PlantDate> parse(std::string_view text);
    // A day of the year written "MM-DD" ("04-20"): 0-based day in a non-leap year
    // (01-01 → 0, 12-31 → 364). Fails with a message quoting the text when it is not
    // two-digit month and day of a real date (02-29 is refused: no year has it always).
    static Result<double> parseMonthDay(std::string_view text);

    int year() const { return year_; }
    int month() const { return month_; }
    int day() const { return day_; }
    // Days since 1970-01-01 (negative before).
    long long daysSinceEpoch() const;
    // 0-based day in a non-leap year calendar (29 February counts as 28 February + ½).
    double dayOfYear() const;
    // Years from `earlier` to this date, in mean Gregorian years (negative before it).
    double yearsSince(const PlantDate& earlier) const;
    std::string text() const;  // "2027-03-01"

private:
    int year_ = 1970, month_ = 1, day_ = 1;
};

}  // namespace sylva
