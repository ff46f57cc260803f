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

#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {

// The depth of a rendered image (for wirelines: WirelineMasks::fromDepths): reversed-Z,
// depth = near / distance, 0 where nothing is drawn, rows top to bottom. A planar image's
// distance is along the view axis (SceneRenderer::depth), a panorama's along each pixel's
// ray (PanoramaFaces::resampleDepth); two renders of one camera compare either way.
struct RenderedDepth {
    std::vector<float> depth;
    double near = 0.0;  // metres
};

class PanoramaRenderer {
public:
    // The image of `camera` at settings.width × settings.height; with `depth` (may be
    // null) also its depth buffer (the last sample's when settings.samples > 1).
    static Result<Image> render(SceneRenderer& scene, const TerrainLayers& layers,
                                TileProvider& provider, const Camera& camera,
                                const RenderSettings& settings, RenderedDepth* depth = nullptr);
};

}  // namespace sylva::render
