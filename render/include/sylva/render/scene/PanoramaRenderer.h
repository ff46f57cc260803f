// PanoramaRenderer: renders a camera in any projection (Camera::projection) through
// SceneRenderer. Planar cameras render directly (fitted to the image: a horizontal field
// of view gives the vertical one; lens shift makes the frustum off-axis). Cylindrical and
// equirectangular cameras render their planar faces (PanoramaFaces::plan: strips about
// the vertical axis, or a cube) and resample them per output pixel with its exact
// direction (ImageProjection), so column bearings are exact and nothing is stitched by
// eye.
//
// Needs the GL context of `scene`. Errors are SceneRenderer's (the camera below the
// terrain, a failing tile); nothing is written.
#pragma once

#include "sylva/core/base/Result.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {

class PanoramaRenderer {
public:
    // The image of `camera` at settings.width × settings.height.
    static Result<Image> render(SceneRenderer& scene, const TerrainLayers& layers,
                                TileProvider& provider, const Camera& camera,
                                const RenderSettings& settings);
};

}  // namespace sylva::render
