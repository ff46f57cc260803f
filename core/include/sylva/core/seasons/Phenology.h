// Phenology: when a plant species has its leaves, and when they turn — the seasons of
// issue 21 item 3. Per species a small table: the habit (deciduous, evergreen,
// palm-like), four days of the year for the northern hemisphere (leaf-out starts, full
// leaf, autumn colouring starts, all leaves down), the share of leaves kept in winter and
// the autumn colour. at() turns a render date and latitude into a LeafState, which the
// vegetation renderer applies inside the level of detail (leaf ellipsoids thinned by
// their noise coverage and recoloured; leaf triangles of the close-up mesh dropped and
// recoloured), not as an image tint.
//
// The model (a simple thermal-time-free calendar, as planners' seasonal views use it:
// leaf-on / leaf-off / autumn by date, not by weather):
//   before leafOut and after leafFall: winterLeaves of the leaves (autumn-coloured);
//   leafOut → fullLeaf: the share grows linearly to 1, the old colour fades to green;
//   fullLeaf → colouring: full leaf, green;
//   colouring → leafFall: the colour turns in the first half, the leaves fall
//   (linearly to winterLeaves) in the second.
// Southern hemisphere (latitude < 0): the table's days shifted by half a year.
// Tropics: within ±20° latitude every species is evergreen (full leaf, green) unless its
// table sets seasonalInTropics; between 20° and 26° the seasonal state blends in linearly
// (no step at the tropic lines). Latitude is one per view (the camera's).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/seasons/PlantDate.h"

namespace sylva {

enum class LeafHabit { Deciduous, Evergreen, Palm };

// What the renderer draws of a species' leaves at one date.
struct LeafState {
    float leafFraction = 1.0f;     // share of the full-summer leaves present, [0, 1]
    float autumn = 0.0f;           // how far the leaves have turned to autumnColour, [0, 1]
    glm::vec3 autumnColour{0.0f};  // linear RGB (meaningful when autumn > 0)
};

struct Phenology {
    LeafHabit habit = LeafHabit::Deciduous;
    // Days of the year, 0-based in a non-leap year (PlantDate::parseMonthDay), for the
    // northern hemisphere; leafOut <= fullLeaf <= colouring <= leafFall.
    double leafOut = 104.0;                 // 04-15
    double fullLeaf = 140.0;                // 05-21
    double colouring = 267.0;               // 09-25
    double leafFall = 313.0;                // 11-10
    double winterLeaves = 0.0;              // share of leaves kept in winter, [0, 1]
    std::optional<glm::vec3> autumnColour;  // linear RGB; none: the colour never turns
    bool seasonalInTropics = false;

    // The built-in table of a habit: deciduous (dates above, autumn colour sRGB #B85A1E),
    // evergreen and palm (all leaves all year, no colour change).
    static Phenology preset(LeafHabit habit);
    static std::optional<LeafHabit> habitNamed(std::string_view name);
    static const std::vector<std::string>& habitNames();  // "deciduous", "evergreen", "palm"
    static std::string habitName(LeafHabit habit);
    // The default habit of a `plant_model` preset: oak, birch, bush → deciduous; conifer →
    // evergreen; palm → palm; anything else (imported files) → evergreen (no change).
    static LeafHabit habitOfPlantPreset(std::string_view preset);

    // Fails, naming the fields, when the days are out of order or out of [0, 365) or
    // winterLeaves is outside [0, 1].
    Status validate() const;

    // The state on `date` at `latitude` (radians).
    LeafState at(const PlantDate& date, double latitude) const;
    // The state on a northern-calendar day of the year (no hemisphere shift, no tropics).
    LeafState onDay(double dayOfYear) const;
};

}  // namespace sylva
