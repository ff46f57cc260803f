// JobView: what turns one Image job of a view series into the inputs of
// SceneRenderer::render — the camera (a camera block, or the job's path sampled at its
// time, with eye heights above the ground that the finest ring level under the camera
// draws, from the CPU elevation query) and the sun (the NOAA position for the job's time,
// else the render block's fixed sun). Shared by `sylva render`, `sylva watch` and a
// viewer, so all three see one camera for one job.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/scene/CameraPath.h"
#include "sylva/core/scene/ViewSeries.h"
#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/core/tiles/TileProvider.h"
#include "sylva/render/batch/RenderSetup.h"

namespace sylva::render {

struct JobView {
    Camera camera;
    glm::dvec3 sun{0.0, 0.0, 1.0};  // ECEF unit vector to the sun
    // "file:line:col: camera 'x'" or "...: path 'p' frame 12": prefix of messages.
    std::string what;

    // The camera and sun of Image job `job` of `model` (whose cameras and paths the job
    // names); `path` is the job's path, built from its block (null for camera jobs).
    // Ground heights are read through `tiles` from the scenario's elevation layer.
    // Errors (a camera below the terrain, an unreadable tile) are located at the camera
    // or path block.
    static Result<JobView> forJob(const ProjectModel& model, const RenderJob& job,
                                  const TerrainLayers& layers, TileProvider& tiles,
                                  const RenderSetup& setup, const CameraPath* path);

    // The setup's settings with this view's sun; linear radiance is read back when the
    // job writes EXR; a camera with a print format (output_size, dpi) sets the image size.
    RenderSettings settingsFor(const RenderSetup& setup, const RenderJob& job) const;
};

}  // namespace sylva::render
