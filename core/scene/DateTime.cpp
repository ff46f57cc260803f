#include "sylva/core/scene/DateTime.h"

#include <chrono>
#include <cstdio>

namespace sylva {
namespace {

// Digits at [position, position + count) as a number; nullopt if any is not a digit.
std::optional<int> digits(std::string_view text, std::size_t position, std::size_t count) {
    if (position + count > text.size()) {
        return std::nullopt;
    }
    int value = 0;
    for (std::size_t i = position; i < position + count; ++i) {
        if (text[i] < '0' || text[i] > '9') {
            return std::nullopt;
        }
        value = value * 10 + (text[i] - '0');
    }
    return value;
}

}  // namespace

Result<DateTime> DateTime::parse(std::string_view text) {
    auto invalid = [&](const std::string& why) {
        return Error{"invalid date/time '" + std::string(text) + "': " + why};
    };
    DateTime result;
    std::size_t position = 0;
    if (text.size() >= 10 && text[4] == '-') {
        auto year = digits(text, 0, 4);
        auto month = digits(text, 5, 2);
        auto day = digits(text, 8, 2);
        if (!year || !month || !day || text[7] != '-') {
            return invalid("expected YYYY-MM-DD");
        }
        const std::chrono::year_month_day date{std::chrono::year{*year},
                                               std::chrono::month{static_cast<unsigned>(*month)},
                                               std::chrono::day{static_cast<unsigned>(*day)}};
        if (!date.ok()) {
            return invalid("no such day");
        }
        result.year_ = year;
        result.month_ = month;
        result.day_ = day;
        position = 10;
        if (position == text.size()) {
            return result;
        }
        if (text[position] != 'T') {
            return invalid("expected 'T' after the date");
        }
        ++position;
    }
    auto hour = digits(text, position, 2);
    auto minute = digits(text, position + 3, 2);
    if (!hour || !minute || text[position + 2] != ':') {
        return invalid("expected hh:mm");
    }
    position += 5;
    int second = 0;
    if (position < text.size() && text[position] == ':') {
        auto parsed = digits(text, position + 1, 2);
        if (!parsed) {
            return invalid("expected hh:mm:ss");
        }
        second = *parsed;
        position += 3;
    }
    if (*hour > 23 || *minute > 59 || second > 59) {
        return invalid("time of day out of range");
    }
    result.hour_ = hour;
    result.minute_ = minute;
    result.second_ = second;
    if (position == text.size()) {
        return result;
    }
    if (text[position] == 'Z' && position + 1 == text.size()) {
        result.offsetMinutes_ = 0;
        return result;
    }
    if ((text[position] == '+' || text[position] == '-') && position + 6 == text.size() &&
        text[position + 3] == ':') {
        auto offsetHours = digits(text, position + 1, 2);
        auto offsetMinutes = digits(text, position + 4, 2);
        if (!offsetHours || !offsetMinutes || *offsetHours > 14 || *offsetMinutes > 59) {
            return invalid("UTC offset out of range");
        }
        const int sign = text[position] == '-' ? -1 : 1;
        result.offsetMinutes_ = sign * (*offsetHours * 60 + *offsetMinutes);
        return result;
    }
    return invalid("expected a UTC offset like +02:00 or Z after the time");
}

Result<double> DateTime::unixSeconds() const {
    if (!hasDate()) {
        return Error{"time " + text() + " has no date"};
    }
    if (!hasTime()) {
        return Error{"date " + text() + " has no time of day"};
    }
    if (!hasZone()) {
        return Error{"time " + text() + " has no zone: add a UTC offset such as " + text() +
                     "+00:00 or Z"};
    }
    const std::chrono::sys_days days{std::chrono::year{*year_} /
                                     std::chrono::month{static_cast<unsigned>(*month_)} /
                                     std::chrono::day{static_cast<unsigned>(*day_)}};
    const double dayStart = static_cast<double>(days.time_since_epoch().count()) * 86400.0;
    return dayStart + *hour_ * 3600.0 + *minute_ * 60.0 + *second_ - *offsetMinutes_ * 60.0;
}

DateTime DateTime::withTimeOf(const DateTime& time) const {
    DateTime combined = *this;
    combined.hour_ = time.hour_;
    combined.minute_ = time.minute_;
    combined.second_ = time.second_;
    if (time.offsetMinutes_) {
        combined.offsetMinutes_ = time.offsetMinutes_;
    }
    return combined;
}

std::string DateTime::text() const {
    char buffer[64];
    std::string out;
    if (hasDate()) {
        std::snprintf(buffer, sizeof buffer, "%04d-%02d-%02d", *year_, *month_, *day_);
        out += buffer;
    }
    if (hasTime()) {
        std::snprintf(buffer, sizeof buffer, "%s%02d:%02d:%02d", hasDate() ? "T" : "", *hour_,
                      *minute_, *second_);
        out += buffer;
        if (hasZone()) {
            const int offset = *offsetMinutes_;
            const int magnitude = offset < 0 ? -offset : offset;
            std::snprintf(buffer, sizeof buffer, "%c%02d:%02d", offset < 0 ? '-' : '+',
                          magnitude / 60, magnitude % 60);
            out += buffer;
        }
    }
    return out;
}

}  // namespace sylva
