// ElevationEditSource (`source x : elevation_edit`): an elevation input reshaped by
// polygons, for the landscape-planning scenarios of seed 001 ch. 8 (a dam or an
// embankment flattened to a crest height, a pit lowered, a cliff cut back to a slope):
//   flatten: the polygon becomes level at `height`;
//   raise / lower: the polygon moves up / down by `amount`;
//   slope: the polygon becomes the plane through its centroid at `height`, rising
//          with `gradient` (metres per metre) towards the azimuth `direction`;
//   level: the polygon becomes level at the mean height of the input under it (at every
//          vertex and the centroid, bilinear at pyramid level kLevelSampleLevel, the
//          grid buildings sample), plus `amount`: building plots, pads of turbines.
// Heights and amounts may come per feature from attributes (height_attribute,
// amount_attribute; numbers in metres). Edits apply in feature order.
//
// Weight: 1 inside the polygon; outside, within `feather` metres of its boundary,
// smoothstep(1 - d / feather) (d = distance in the local east/north metric of the
// texel, so feathers are right at any latitude); beyond, 0. Without a feather the
// edge weight is the texel's exact area coverage (anti-aliased). The result is
// h = h0 + w (target - h0) (flatten, slope) or h0 +- w amount (raise, lower).
// The slope plane uses local east/north metres about the centroid (a tangent-plane
// approximation: relative height error ~ (extent / Earth radius)², negligible for
// the kilometre-scale polygons this is for). Polygons only; lines and points, a
// missing attribute or a non-numeric value are errors naming file, feature and value.
// For `blend`, the edit covers what its input covers (BlendSource::coverageOf).
#pragma once

#include <string>

#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"
#include "sylva/core/sources/vector/FeatureSource.h"

namespace sylva {

struct ElevationEditParameters {
    enum class Mode { Flatten, Raise, Lower, Slope, Level } mode = Mode::Flatten;
    double height = 0.0;     // metres (flatten, slope)
    double amount = 0.0;     // metres (raise, lower, level)
    double gradient = 0.0;   // metres per metre (slope)
    double direction = 0.0;  // radians, azimuth of steepest ascent, clockwise from north
    double feather = 0.0;    // metres, outside the polygon
    std::string heightAttribute;
    std::string amountAttribute;
};

class ElevationEditSource final : public Source {
public:
    ElevationEditSource(std::string name, const Source* input, const FeatureSource* features,
                        ElevationEditParameters parameters);
    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

    const Source& input() const { return *input_; }

    // The pyramid level `level` samples the input at (texels of about 1.2 m).
    static constexpr int kLevelSampleLevel = 16;

private:
    // The mean input height under a polygon (`level` mode).
    Result<double> meanHeightUnder(const Feature& feature, TileProvider& provider) const;

    const Source* input_;
    const FeatureSource* features_;
    ElevationEditParameters parameters_;
};

}  // namespace sylva
