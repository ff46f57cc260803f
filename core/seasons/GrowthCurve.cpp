#include "sylva/core/seasons/GrowthCurve.h"

#include <algorithm>
#include <cstdio>

#include "sylva/core/base/Check.h"

namespace sylva {
namespace {

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

// The field `name` of a record: its value, or nullptr.
const Value* field(const ValueObject& record, std::string_view name) {
    for (const auto& [key, value] : record) {
        if (key == name) {
            return &value;
        }
    }
    return nullptr;
}

Error locatedAt(const Value& value, SourceLocation* problem, std::string message) {
    if (problem != nullptr) {
        *problem = value.location;
    }
    return Error{std::move(message)};
}

// One non-negative number field (absent: nullopt); `bad` is set when it is not one.
std::optional<double> nonNegative(const ValueObject& record, std::string_view name,
                                  const Value*& bad) {
    const Value* value = field(record, name);
    if (value == nullptr) {
        return std::nullopt;
    }
    const Quantity* quantity = value->get<Quantity>();
    if (quantity == nullptr || !(quantity->value >= 0.0)) {
        bad = value;
        return std::nullopt;
    }
    return quantity->value;
}

Result<GrowthCurve::Point> readPoint(const Value& item, SourceLocation* problem) {
    const ValueObject* record = item.get<ValueObject>();
    if (record == nullptr) {
        return locatedAt(item, problem,
                         "growth: a point is a record { age = 15, size = 60%, crown = 55% }");
    }
    GrowthCurve::Point point;
    const Value* bad = nullptr;
    const std::optional<double> age = nonNegative(*record, "age", bad);
    const std::optional<double> height = nonNegative(*record, "height", bad);
    const std::optional<double> size = nonNegative(*record, "size", bad);
    point.crownFraction = nonNegative(*record, "crown", bad);
    if (bad != nullptr) {
        return locatedAt(*bad, problem, "growth: ages, heights and fractions must not be negative");
    }
    if (!age) {
        return locatedAt(item, problem, "growth: every point needs an `age` in years");
    }
    if (height.has_value() == size.has_value()) {
        return locatedAt(item, problem,
                         "growth: give a point either `height` (metres) or `size` (a fraction "
                         "of the model's height)");
    }
    point.age = *age;
    point.heightMetres = height;
    point.sizeFraction = size.value_or(1.0);
    return point;
}

}  // namespace

GrowthCurve GrowthCurve::standard() {
    std::vector<Point> points(4);
    const double ages[4] = {0.0, 5.0, 15.0, 40.0};
    const double sizes[4] = {0.10, 0.35, 0.70, 1.0};
    for (int i = 0; i < 4; ++i) {
        points[i].age = ages[i];
        points[i].sizeFraction = sizes[i];
    }
    return fromPoints(std::move(points));
}

GrowthCurve GrowthCurve::fromPoints(std::vector<Point> points) {
    SYLVA_CHECK(!points.empty());
    for (std::size_t i = 1; i < points.size(); ++i) {
        SYLVA_CHECK(points[i].age > points[i - 1].age);
    }
    GrowthCurve curve;
    curve.points_ = std::move(points);
    return curve;
}

Result<GrowthCurve> GrowthCurve::read(const Value& value, SourceLocation* problem) {
    const ValueList* list = value.get<ValueList>();
    if (list == nullptr || list->empty()) {
        return locatedAt(value, problem,
                         "growth: a list of points [{ age = 0, size = 10% }, ...] is needed");
    }
    std::vector<Point> points;
    for (const Value& item : *list) {
        Result<Point> point = readPoint(item, problem);
        if (!point) {
            return point.error();
        }
        if (!points.empty() && point.value().age <= points.back().age) {
            return locatedAt(item, problem,
                             "growth: ages must increase, but age " + number(point.value().age) +
                                 " follows age " + number(points.back().age));
        }
        points.push_back(point.value());
    }
    return fromPoints(std::move(points));
}

std::optional<GrowthScale> GrowthCurve::at(double ageYears, double modelHeight) const {
    if (ageYears < 0.0) {
        return std::nullopt;
    }
    SYLVA_CHECK(modelHeight > 0.0 && !points_.empty());
    const auto scaleOf = [&](const Point& p) {
        GrowthScale scale;
        scale.height = p.heightMetres ? *p.heightMetres / modelHeight : p.sizeFraction;
        scale.crown = p.crownFraction.value_or(scale.height);
        return scale;
    };
    if (ageYears <= points_.front().age) {
        return scaleOf(points_.front());
    }
    if (ageYears >= points_.back().age) {
        return scaleOf(points_.back());
    }
    const auto next = std::upper_bound(points_.begin(), points_.end(), ageYears,
                                       [](double age, const Point& p) { return age < p.age; });
    const Point& a = *(next - 1);
    const Point& b = *next;
    const double t = (ageYears - a.age) / (b.age - a.age);
    const GrowthScale sa = scaleOf(a), sb = scaleOf(b);
    GrowthScale scale;
    scale.height = sa.height + (sb.height - sa.height) * t;
    scale.crown = sa.crown + (sb.crown - sa.crown) * t;
    return scale;
}

}  // namespace sylva
