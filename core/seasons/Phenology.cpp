#include "sylva/core/seasons/Phenology.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "sylva/core/image/ColorSpace.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
// Seasonality fades in between these latitudes (the tropic lines are at ±23.44°).
constexpr double kTropicsEvergreen = 20.0 * kDegree;
constexpr double kTropicsSeasonal = 26.0 * kDegree;

double ramp(double x, double from, double to) {
    return to > from ? std::clamp((x - from) / (to - from), 0.0, 1.0) : (x >= to ? 1.0 : 0.0);
}

}  // namespace

Phenology Phenology::preset(LeafHabit habit) {
    Phenology table;
    table.habit = habit;
    if (habit == LeafHabit::Deciduous) {
        table.autumnColour = glm::vec3(srgbToLinear(0xB8 / 255.0f), srgbToLinear(0x5A / 255.0f),
                                       srgbToLinear(0x1E / 255.0f));
    } else {
        table.winterLeaves = 1.0;
    }
    return table;
}

const std::vector<std::string>& Phenology::habitNames() {
    static const std::vector<std::string> names = {"deciduous", "evergreen", "palm"};
    return names;
}

std::optional<LeafHabit> Phenology::habitNamed(std::string_view name) {
    if (name == "deciduous") {
        return LeafHabit::Deciduous;
    }
    if (name == "evergreen") {
        return LeafHabit::Evergreen;
    }
    if (name == "palm") {
        return LeafHabit::Palm;
    }
    return std::nullopt;
}

std::string Phenology::habitName(LeafHabit habit) {
    return habitNames()[static_cast<std::size_t>(habit)];
}

LeafHabit Phenology::habitOfPlantPreset(std::string_view preset) {
    if (preset == "oak" || preset == "birch" || preset == "bush") {
        return LeafHabit::Deciduous;
    }
    if (preset == "palm") {
        return LeafHabit::Palm;
    }
    return LeafHabit::Evergreen;
}

Status Phenology::validate() const {
    const double days[4] = {leafOut, fullLeaf, colouring, leafFall};
    const char* names[4] = {"leaf_out", "full_leaf", "colouring", "leaf_fall"};
    for (int i = 0; i < 4; ++i) {
        if (!(days[i] >= 0.0 && days[i] < PlantDate::kDaysInYearTable)) {
            return Error{std::string(names[i]) + " is not a day of the year"};
        }
        if (i > 0 && days[i] < days[i - 1]) {
            return Error{std::string(names[i - 1]) + " must not come after " + names[i] +
                         " (days of the northern-hemisphere year, January to December)"};
        }
    }
    if (!(winterLeaves >= 0.0 && winterLeaves <= 1.0)) {
        return Error{"winter_leaves must be within 0 % and 100 %"};
    }
    return Status::success();
}

LeafState Phenology::onDay(double day) const {
    LeafState state;
    const double winter = winterLeaves;
    // Autumn: the colour turns in the first half, the leaves fall in the second.
    const double middle = 0.5 * (colouring + leafFall);
    double share = 1.0, turned = 0.0;
    if (day < leafOut || day >= leafFall) {
        share = winter;
        turned = 1.0;
    } else if (day < fullLeaf) {
        const double grown = ramp(day, leafOut, fullLeaf);
        share = winter + (1.0 - winter) * grown;
        turned = 1.0 - grown;
    } else if (day >= colouring) {
        turned = ramp(day, colouring, middle);
        share = 1.0 - (1.0 - winter) * ramp(day, middle, leafFall);
    } else {
        turned = 0.0;
    }
    state.leafFraction = static_cast<float>(std::clamp(share, 0.0, 1.0));
    if (autumnColour) {
        state.autumn = static_cast<float>(turned);
        state.autumnColour = *autumnColour;
    }
    return state;
}

LeafState Phenology::at(const PlantDate& date, double latitude) const {
    double day = date.dayOfYear();
    if (latitude < 0.0) {  // southern hemisphere: half a year later
        day = std::fmod(day + 0.5 * PlantDate::kDaysInYearTable, PlantDate::kDaysInYearTable);
    }
    LeafState seasonal = onDay(day);
    if (seasonalInTropics) {
        return seasonal;
    }
    const float amount =
        static_cast<float>(ramp(std::abs(latitude), kTropicsEvergreen, kTropicsSeasonal));
    seasonal.leafFraction = 1.0f + (seasonal.leafFraction - 1.0f) * amount;
    seasonal.autumn *= amount;
    return seasonal;
}

}  // namespace sylva
