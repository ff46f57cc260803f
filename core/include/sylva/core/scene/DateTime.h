// DateTime: a date, a time of day, or both, with an optional UTC offset, as the project
// language writes them (the canonical forms of the DSL's lexer: 2024-06-21,
// 2024-06-21T14:30:00, 2024-06-21T14:30:00-03:00, 14:30:00; `Z` is +00:00).
// Views combine dates and times into instants for the sun (SolarPosition).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "sylva/core/base/Result.h"

namespace sylva {

class DateTime {
public:
    // Fails with a message naming the text when it is not one of the forms above or a
    // field is out of range (month 13, 25:00, 30 February).
    static Result<DateTime> parse(std::string_view text);

    bool hasDate() const { return year_.has_value(); }
    bool hasTime() const { return hour_.has_value(); }
    bool hasZone() const { return offsetMinutes_.has_value(); }

    // Seconds since 1970-01-01T00:00:00Z. Needs a date, a time and a zone; the error
    // says which is missing.
    Result<double> unixSeconds() const;
    // The same date with another time of day (and that time's zone, if it has one).
    DateTime withTimeOf(const DateTime& time) const;

    // Canonical text, as parsed: "2024-06-21T14:30:00-03:00".
    std::string text() const;

private:
    std::optional<int> year_, month_, day_;
    std::optional<int> hour_, minute_, second_;
    std::optional<int> offsetMinutes_;  // east of UTC
};

}  // namespace sylva
