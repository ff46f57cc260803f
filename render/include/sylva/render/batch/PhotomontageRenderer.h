// PhotomontageRenderer: the GL half of a `photo` block (issue 18; LI TGN 06/19 Types 2, 3
// and 4). For the camera of the photograph — its block, fitted to the photograph
// (PhotoViewpoint::fitCamera: EXIF lens, aspect) and solved from the control points when
// there are any (CameraMatcher) — it renders the baseline scenario and the proposed
// scenario at the photograph's pixel size with one sun and exposure, reads back both
// depth buffers and makes:
//   montage   the photograph with the proposal's visible pixels (ProposalMask::fromDepths)
//             from the proposed render laid over it (Type 3; Type 4 with control points);
//   wireline  the photograph with the proposal's silhouette and the terrain skyline
//             drawn as lines (a "photowire");
//   model     the rendered baseline with the same lines (Type 2 wireline over the model);
// and the proposal's nearest distance and horizontal extent (ProposalExtent), and with a
// sheet the location plan: the proposed scenario from straight above the viewpoint with the
// field-of-view wedge (LocationMap), out to 1.25 × the farthest proposal pixel's range
// (2 km without a visible proposal).
// Planar cameras only (a photograph). One sample per pixel: the masks come from the depth
// of the render they are cut from. Needs the batch renderer's GL context (it makes it).
//
// Errors (Result, nothing written here): PhotoViewpoint's located ones, a scenario whose
// graph fails, a camera below the terrain, a tile that fails to compute.
#pragma once

#include <optional>
#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/Image.h"
#include "sylva/core/image/ProposalMask.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/scene/CameraMatcher.h"
#include "sylva/core/scene/PhotoViewpoint.h"
#include "sylva/core/scene/ProposalExtent.h"
#include "sylva/core/scene/ViewpointRecord.h"
#include "sylva/render/batch/BatchRenderer.h"

namespace sylva::render {

struct PhotomontageResult {
    Camera camera;                     // the camera rendered (matched when there are points)
    std::optional<CameraMatch> match;  // the solve and its residuals
    RgbaImage montage, wireline, model;
    // With `photo { annotated = true }`: the photograph with the Type 1 annotations
    // (ViewAnnotation: viewpoint id, bearing scale, the proposal's extent and parts);
    // empty otherwise.
    RgbaImage annotated;
    RgbaImage proposed;    // the proposed scenario's render (for the sheet and tests)
    PixelMask proposal;    // the proposal's visible pixels
    PixelMask silhouette;  // its outline
    PixelMask skyline;     // the baseline's skyline
    glm::dvec3 sun{0.0, 0.0, 1.0};
    double ev100 = 0.0;
    std::optional<ProposalExtent> extent;  // nearest distance and bearings (none: hidden)
    // With `photo { sheet = true }`: the location plan (LocationMap, the proposed scenario
    // from above, kMapPixels square) spanning ±mapRadius metres.
    RgbaImage locationMap;
    double mapRadius = 0.0;
};

class PhotomontageRenderer {
public:
    static constexpr int kMapPixels = 512;

    static Result<PhotomontageResult> render(BatchRenderer& batch, const PhotoViewpoint& photo,
                                             const Photo& picture);
    // The viewpoint record of a rendered photomontage (the camera as matched, the proposed
    // scenario's data sources, the proposal's distance and extent, the match's rms, the
    // project hash over every block).
    static ViewpointRecord record(BatchRenderer& batch, const PhotoViewpoint& photo,
                                  const PhotomontageResult& result);
};

}  // namespace sylva::render
