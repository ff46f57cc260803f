// ImpostorViewSet: the capture directions and texture resolutions of a species'
// view-direction impostors (seed 004 §3.2 and §3.4: billboards baked from the model from
// a fixed set of views over the upper hemisphere, at 64², 128² and 256² texels, the
// view whose creation angle differs least from the current one drawn at the resolution
// the distance calls for).
//
// The seed's five views (front, back, left, right, top) leave directions up to 45° from
// the nearest view; this set uses eight azimuths at the horizon, eight more (offset by
// half a step) at 40° elevation and the top view, which keeps it under 30° (the header's
// numbers are checked by ImpostorViewSetTest). The resolution is chosen by the plant's
// projected diameter in pixels instead of the seed's unspecified distance bands, so a
// texel never covers more than one pixel when it can be helped.
//
// Frame: the plant's model frame (metres, +Z up). Directions point from the plant toward
// the eye. Pure data; no failure modes.
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>

namespace sylva {

class ImpostorViewSet {
public:
    static constexpr std::array<int, 3> kResolutions{64, 128, 256};  // texels per side
    static constexpr int kAzimuths = 8;
    static constexpr double kRaisedElevation = 40.0;  // degrees, the second ring
    // The largest angle (degrees) between a direction of the upper hemisphere and its
    // nearest view in this set (seed 004's five views: 45°).
    static constexpr double kLargestViewGap = 30.0;

    // The 17 views: ring at 0°, ring at kRaisedElevation, top.
    static ImpostorViewSet upperHemisphere();

    const std::vector<glm::vec3>& directions() const { return directions_; }
    std::size_t size() const { return directions_.size(); }

    // The index of the view nearest to `towardEye` (any length > 0; directions below the
    // horizon take the nearest ring view).
    int nearest(const glm::vec3& towardEye) const;

    // The index into kResolutions for a plant `pixels` wide on screen: the smallest
    // resolution at least that wide (the largest when none is).
    static int resolutionLevel(double pixels);

private:
    std::vector<glm::vec3> directions_;
};

}  // namespace sylva
