// ImageJobs: what `sylva render` and `sylva watch` share to turn a RenderJob into the
// inputs of SceneRenderer::render — the render block's settings and, per job, the
// camera (a camera block, or a path sampled at the job's time, heights from the CPU
// elevation query) and the sun (NOAA position for the job's time, else the render
// block's fixed sun).
#pragma once

#include <map>
#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/scene/CameraPath.h"
#include "sylva/core/scene/ViewSeries.h"
#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::app {

struct RenderSetup {
    render::RenderSettings settings;
    render::TerrainSettings terrain;
    glm::dvec3 defaultSun{0.0, 0.0, 1.0};  // ECEF unit vector to the sun
    std::size_t cacheMegabytes = 1024;     // tile cache budget (render block cache_mb)
};

// From the project's render block; width/height > 0 override its resolution.
// Errors are located at the render block.
Result<RenderSetup> makeRenderSetup(const ProjectModel& model, int overrideWidth,
                                    int overrideHeight);

struct JobView {
    Camera camera;
    glm::dvec3 sun{0.0, 0.0, 1.0};
    std::string what;  // "file:line:col: camera 'x'" or "...: path 'p' frame 12", for messages
};

// The camera and sun of an Image job. `paths` holds the series' paths by name.
Result<JobView> viewForJob(const ProjectModel& model, const RenderJob& job,
                           const TerrainLayers& layers, TileProvider& tiles,
                           const RenderSetup& setup,
                           const std::map<std::string, CameraPath>& paths);

// Writes a rendered image to `path`: EXR paths get the linear radiance (half float; the
// image must have been rendered with RenderSettings::linearOutput, which this moves
// out), other paths the displayed 8-bit sRGB pixels. Errors name the path.
Status writeRenderedImage(const std::filesystem::path& path, render::Image& image,
                          const ImageMetadata& metadata = {});

}  // namespace sylva::app
