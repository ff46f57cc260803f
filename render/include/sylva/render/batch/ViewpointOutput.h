// ViewpointOutput: the verified-view outputs of a camera image job — the viewpoint's
// record (ViewpointRecord: position, heights, bearing, fields of view, lens, print and
// viewing distance, time and sun, data sources, version, project hash) in the image's
// metadata, and with `views { sheet = true }` its sheet (PDF and PNG through
// ViewpointSheet) and JSON sidecar beside the image.
#pragma once

#include <optional>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/ImageMetadata.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/scene/ViewpointRecord.h"
#include "sylva/render/batch/BatchPlan.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {

class ViewpointOutput {
public:
    // Whether the job's views block asks for sheets; an error (located at `sheet`) when
    // it does and the camera has no print format.
    static Result<bool> wantsSheet(const BatchPlan& plan, const RenderJob& job,
                                   const Camera& camera);
    // The record of a camera job (nullopt for path frames); `tiles` serves the scenario's
    // mesh sources for the proposal's distance and extent (addProposal).
    static std::optional<ViewpointRecord> record(const BatchPlan& plan, const RenderJob& job,
                                                 const Camera& camera, int width, int height,
                                                 TileProvider& tiles);
    // The proposal's nearest distance, extent and bearings from the viewpoint of `camera`
    // (ProposalReach over `meshes`, the scenario's buildings and objects); nothing without
    // meshes. A mesh source's error was the render's already: the fields are then left out.
    static void addProposal(const Camera& camera, const std::vector<const MeshSource*>& meshes,
                            TileProvider& tiles, ViewpointInputs& inputs);
    // Writes NAME.json, NAME.sheet.pdf and NAME.sheet.png beside the job's output
    // (NAME: the output without its extension). Errors name the file.
    static Status writeSheet(const BatchPlan& plan, const RenderJob& job, const Camera& camera,
                             const Image& image, const ViewpointRecord& record);
};

}  // namespace sylva::render
