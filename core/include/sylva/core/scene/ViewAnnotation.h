// ViewAnnotation: the annotations of a Type 1 "annotated viewpoint photograph" (Landscape
// Institute TGN 06/19, Visual Representation of Development Proposals: the photograph with
// labels, bearings and the extent of the site; docs/verified-views.md),
// drawn into the image itself:
//   - along the top edge, on a light band: the viewpoint id, the view bearing and the
//     fields of view, and a bearing scale (ticks every 5° up to 60° of HFOV, 10° up to
//     180°, 30° beyond, each labelled with its bearing clockwise from true north);
//   - the proposal's horizontal extent (ViewProposal: ProposalReach's arc, from its
//     geometry, visible or not): a vertical line at each end's bearing, and its bearings
//     and width in words at the right of the top band when they fit beside the title;
//   - along the bottom edge: every placed model's origin (a turbine's tower foot) as a
//     tick labelled with its feature id, under a bracket over the extent.
// Every column comes from the camera model (ImageProjection), never from the image:
// a bearing's column is the pixel of the horizontal direction of that bearing at the
// viewpoint (exactly the bearing's column in a cylindrical panorama and in a level planar
// image; in a pitched or rolled planar image the column where that bearing meets the
// horizon), a part's column the pixel of its ECEF point. Marks outside the image are left
// out; a label that would touch the previous one is left out (small images label fewer
// ticks). Text is drawn with cairo's font machinery (real glyphs, as ViewpointSheet).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/image/Image.h"
#include "sylva/core/scene/Camera.h"

namespace sylva {

struct ViewMark {
    double column = 0.0;  // pixel position x: 0 the left edge, pixel i covers [i, i + 1)
    std::string label;
};

// The proposal as the annotations need it (the caller measures it: ProposalReach over
// ProposalReach::partsOf, core/analysis).
struct ViewProposal {
    // The smallest arc of bearings holding the proposal: radians clockwise from true north,
    // from leftBearing clockwise over horizontalExtent to rightBearing.
    double leftBearing = 0.0, rightBearing = 0.0, horizontalExtent = 0.0;
    std::vector<glm::dvec3> points;   // placed models' origins, ECEF metres
    std::vector<std::string> labels;  // one per point (e.g. its feature id)
};

struct ViewAnnotations {
    int width = 0, height = 0;  // of the image, pixels
    std::string title;          // "vp1  view 60.0°  HFOV 53.5° × 18.2°  planar"
    std::string extentText;     // "proposal 32.6°–76.8° (44.2°)"; empty without a proposal
    double bearingStep = 0.0;   // radians between bearing ticks
    std::vector<ViewMark> bearings;                    // the scale's ticks inside the image
    std::optional<ViewMark> extentLeft, extentRight;   // the extent's ends, when in the image
    std::optional<std::pair<double, double>> bracket;  // columns of the extent bracket
    std::vector<ViewMark> parts;                       // placed models' origins in the image
    // Layout (pixels): text size, the top band [0, topBand), the bottom band
    // [height − bottomBand, height); part ticks span rows [partTickTop, partTickBottom),
    // the extent lines [topBand, height − bottomBand).
    double fontSize = 0.0, topBand = 0.0, bottomBand = 0.0;
    double partTickTop = 0.0, partTickBottom = 0.0;
    double lineWidth = 0.0;  // of ticks and lines
};

class ViewAnnotation {
public:
    static constexpr std::uint8_t kMarkRed[3] = {220, 20, 20};  // extent and parts, sRGB

    // The annotations of `camera` (any projection) seen at width × height pixels, titled
    // with `id`; `proposal` may be null (no proposal marks). Labels missing from
    // proposal->labels are the points' 1-based indices.
    static ViewAnnotations plan(const Camera& camera, int width, int height, const std::string& id,
                                const ViewProposal* proposal);
    // `image` (sRGB 8-bit, treated as opaque) with `annotations` drawn into it; the sizes
    // must match (programmer error otherwise).
    static RgbaImage draw(const RgbaImage& image, const ViewAnnotations& annotations);
};

}  // namespace sylva
