// GrowthCurve: the size of planted trees by age (issue 21 item 3), so a scenario dated
// years after planting shows the mitigation planting grown. A piecewise-linear table of
// points (age in years since planting; height as metres or as a fraction of the plant
// model's mature height; crown width as a fraction of the model's), written in a plants
// block as
//     growth = [{ age = 0, height = 1.5m, crown = 10% },
//               { age = 15, size = 60%, crown = 55% },
//               { age = 40, size = 100% }]
// (`size` is the height fraction; `crown` defaults to the height fraction of the point).
// Between points the fractions are interpolated linearly, before the first point the
// plant is absent (not planted yet: age < 0) or at the first point's size, after the
// last it keeps the last size. Instances are scaled by it at the render date: the model's
// up axis by the height fraction, its horizontal axes by the crown fraction.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/base/SourceLocation.h"
#include "sylva/core/model/Value.h"

namespace sylva {

// Scale factors of one instance's model axes at an age.
struct GrowthScale {
    double height = 1.0;  // up axis: fraction of the model's height
    double crown = 1.0;   // horizontal axes: fraction of the model's crown width
};

class GrowthCurve {
public:
    struct Point {
        double age = 0.0;                     // years since planting, increasing
        std::optional<double> heightMetres;   // height in metres, or
        double sizeFraction = 1.0;            // height as a fraction (when heightMetres is none)
        std::optional<double> crownFraction;  // none: the point's height fraction
    };

    // The default when a plants block has `planted` but no `growth`: a broadleaf nursery
    // standard planted at 10 % of the mature size, 35 % at 5 years, 70 % at 15, mature at
    // 40 (crown as height) — typical of landscape mitigation planting schedules.
    static GrowthCurve standard();

    // Reads the `growth` value (a list of records as above). Fails when a point has a
    // negative height or fraction, a missing or negative age, ages that do not increase,
    // or both or neither of `height` and `size`; `problem` (when given) receives the
    // location of the offending value, the message does not include it.
    static Result<GrowthCurve> read(const Value& value, SourceLocation* problem = nullptr);
    // A curve from points already checked (tests); SYLVA_CHECKs increasing ages.
    static GrowthCurve fromPoints(std::vector<Point> points);

    // The scale at `ageYears` for a model `modelHeight` metres tall (> 0); nullopt before
    // planting (ageYears < 0).
    std::optional<GrowthScale> at(double ageYears, double modelHeight) const;

    const std::vector<Point>& points() const { return points_; }

private:
    std::vector<Point> points_;
};

}  // namespace sylva
