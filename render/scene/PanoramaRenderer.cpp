#include "sylva/render/scene/PanoramaRenderer.h"

#include <utility>
#include <vector>

#include "sylva/core/scene/PanoramaFaces.h"

namespace sylva::render {

Result<Image> PanoramaRenderer::render(SceneRenderer& scene, const TerrainLayers& layers,
                                       TileProvider& provider, const Camera& camera,
                                       const RenderSettings& settings, RenderedDepth* depth) {
    if (camera.projection == CameraProjection::Planar) {
        Result<Image> image = scene.render(
            layers, provider, camera.fitted(settings.width, settings.height), settings);
        if (image && depth != nullptr) {
            *depth = {scene.depth(), scene.near()};
        }
        return image;
    }
    const std::vector<PanoramaFace> faces =
        PanoramaFaces::plan(camera, settings.width, settings.height);
    std::vector<RgbaImage> colour(faces.size());
    std::vector<LinearImage> radiance(faces.size());
    std::vector<std::vector<float>> faceDepths(depth != nullptr ? faces.size() : 0);
    std::vector<double> faceNears(faceDepths.size());
    for (std::size_t i = 0; i < faces.size(); ++i) {
        RenderSettings faceSettings = settings;
        faceSettings.width = faces[i].width;
        faceSettings.height = faces[i].height;
        Result<Image> image = scene.render(layers, provider, faces[i].camera, faceSettings);
        if (!image) {
            return image.error();
        }
        colour[i].width = radiance[i].width = image.value().width;
        colour[i].height = radiance[i].height = image.value().height;
        colour[i].pixels = std::move(image.value().pixels);
        radiance[i].pixels = std::move(image.value().radiance);
        if (depth != nullptr) {
            faceDepths[i] = scene.depth();
            faceNears[i] = scene.near();
        }
    }
    std::vector<const RgbaImage*> colourFaces;
    std::vector<const LinearImage*> radianceFaces;
    for (std::size_t i = 0; i < faces.size(); ++i) {
        colourFaces.push_back(&colour[i]);
        radianceFaces.push_back(&radiance[i]);
    }
    Image out;
    out.width = settings.width;
    out.height = settings.height;
    out.pixels =
        PanoramaFaces::resample(camera, settings.width, settings.height, faces, colourFaces).pixels;
    if (settings.linearOutput) {
        out.radiance =
            PanoramaFaces::resample(camera, settings.width, settings.height, faces, radianceFaces)
                .pixels;
    }
    if (depth != nullptr) {
        std::vector<const std::vector<float>*> depthFaces;
        for (const std::vector<float>& face : faceDepths) {
            depthFaces.push_back(&face);
        }
        depth->near = faceNears.front();
        depth->depth = PanoramaFaces::resampleDepth(camera, settings.width, settings.height, faces,
                                                    depthFaces, faceNears, depth->near);
    }
    return out;
}

}  // namespace sylva::render
