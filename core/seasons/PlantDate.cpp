#include "sylva/core/seasons/PlantDate.h"

#include <cstdio>

namespace sylva {
namespace {

constexpr int kDaysBeforeMonth[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
constexpr int kDaysInMonth[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};

// "'text' " + rest, built by appends (GCC 12 warns falsely on operator+ chains here).
std::string quoted(std::string_view text, std::string_view rest) {
    std::string message = "'";
    message.append(text);
    message.append("' ");
    message.append(rest);
    return message;
}

bool isLeap(int year) {
    return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

bool twoDigits(std::string_view text, std::size_t at, int& value) {
    if (at + 2 > text.size() || text[at] < '0' || text[at] > '9' || text[at + 1] < '0' ||
        text[at + 1] > '9') {
        return false;
    }
    value = (text[at] - '0') * 10 + (text[at + 1] - '0');
    return true;
}

}  // namespace

Result<PlantDate> PlantDate::make(int year, int month, int day) {
    if (month < 1 || month > 12 || day < 1 ||
        day > kDaysInMonth[month - 1] + (month == 2 && isLeap(year) ? 1 : 0)) {
        char text[64];
        std::snprintf(text, sizeof text, "%04d-%02d-%02d", year, month, day);
        return Error{std::string("no such date: ") + text};
    }
    PlantDate date;
    date.year_ = year;
    date.month_ = month;
    date.day_ = day;
    return date;
}

Result<PlantDate> PlantDate::parse(std::string_view text) {
    int century = 0, decade = 0, month = 0, day = 0;
    if (text.size() < 10 || !twoDigits(text, 0, century) || !twoDigits(text, 2, decade) ||
        text[4] != '-' || !twoDigits(text, 5, month) || text[7] != '-' ||
        !twoDigits(text, 8, day) || (text.size() > 10 && text[10] != 'T')) {
        return Error{quoted(text, "is not a date (expected 2027-03-01)")};
    }
    return make(century * 100 + decade, month, day);
}

Result<PlantDate> PlantDate::fromDateTime(const DateTime& time) {
    if (!time.hasDate()) {
        return Error{quoted(time.text(), "has no date (expected 2027-03-01)")};
    }
    return parse(time.text());
}

Result<double> PlantDate::parseMonthDay(std::string_view text) {
    int month = 0, day = 0;
    if (text.size() != 5 || !twoDigits(text, 0, month) || text[2] != '-' ||
        !twoDigits(text, 3, day) || month < 1 || month > 12 || day < 1 ||
        day > kDaysInMonth[month - 1]) {
        return Error{quoted(text, "is not a day of the year (expected month-day, e.g. \"04-20\")")};
    }
    return double(kDaysBeforeMonth[month - 1] + day - 1);
}

long long PlantDate::daysSinceEpoch() const {
    // Days from civil (H. Hinnant, "chrono-compatible low-level date algorithms").
    const long long y = year_ - (month_ <= 2 ? 1 : 0);
    const long long era = (y >= 0 ? y : y - 399) / 400;
    const long long yearOfEra = y - era * 400;
    const long long dayOfYear = (153 * (month_ + (month_ > 2 ? -3 : 9)) + 2) / 5 + day_ - 1;
    const long long dayOfEra = yearOfEra * 365 + yearOfEra / 4 - yearOfEra / 100 + dayOfYear;
    return era * 146097 + dayOfEra - 719468;
}

double PlantDate::dayOfYear() const {
    if (month_ == 2 && day_ == 29) {
        return kDaysBeforeMonth[1] + 27.5;
    }
    return kDaysBeforeMonth[month_ - 1] + day_ - 1;
}

double PlantDate::yearsSince(const PlantDate& earlier) const {
    return double(daysSinceEpoch() - earlier.daysSinceEpoch()) / kDaysPerYear;
}

std::string PlantDate::text() const {
    char text[32];
    std::snprintf(text, sizeof text, "%04d-%02d-%02d", year_, month_, day_);
    return text;
}

}  // namespace sylva
