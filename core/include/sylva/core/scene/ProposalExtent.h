// ProposalExtent: what a viewpoint record says about the proposal (LI TGN 06/19 practice:
// "distance to the nearest part of the proposal and its horizontal extent in degrees"),
// measured on the render of a photomontage: over the proposal's visible pixels
// (ProposalMask), the nearest surface distance from the camera and the range of bearings.
//
// Distances come from the proposed render's reversed-Z depth (depth = near / distance
// along the view axis), turned into ranges along each pixel's ray (ImageProjection);
// bearings are the rays' directions in the local east/north frame at the camera.
// Pixel-centre sampling: the extent is exact to about a pixel's angle.
#pragma once

#include <optional>
#include <vector>

#include "sylva/core/image/ProposalMask.h"
#include "sylva/core/scene/Camera.h"

namespace sylva {

struct ProposalExtent {
    double nearestDistance = 0.0;   // metres from the camera to the nearest proposal pixel
    double farthestDistance = 0.0;  // ... and to the farthest (the location map's reach)
    double leftBearing = 0.0;       // radians clockwise from north, of the leftmost pixel
    double rightBearing = 0.0;      // ... and of the rightmost
    double horizontalExtent = 0.0;  // radians between them

    // nullopt when the mask is empty. `camera` is the one rendered (fitted to the image).
    static std::optional<ProposalExtent> measure(const PixelMask& mask,
                                                 const std::vector<float>& depth, double near,
                                                 const Camera& camera, int width, int height);
};

}  // namespace sylva
