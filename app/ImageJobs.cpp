#include "ImageJobs.h"

#include <algorithm>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/geo/SolarPosition.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/terrain/ElevationQuery.h"
#include "sylva/core/terrain/LevelVisibility.h"

namespace sylva::app {

Result<RenderSetup> makeRenderSetup(const ProjectModel& model, int overrideWidth,
                                    int overrideHeight) {
    BlockReader renderBlock(model.render, SchemaRegistry::builtin().find("render"));
    RenderSetup setup;
    render::RenderSettings& settings = setup.settings;
    if (overrideWidth > 0) {
        settings.width = overrideWidth;
        settings.height = overrideHeight;
    } else if (const Value* resolution = renderBlock.value("resolution")) {
        const ValueList* list = resolution->get<ValueList>();
        if (list == nullptr || list->size() != 2 || !(*list)[0].get<Quantity>() ||
            !(*list)[1].get<Quantity>()) {
            return Error{renderBlock.where("resolution") + "resolution must be [width, height]"};
        }
        settings.width = static_cast<int>((*list)[0].get<Quantity>()->value);
        settings.height = static_cast<int>((*list)[1].get<Quantity>()->value);
        if (settings.width < 1 || settings.height < 1 || settings.width > 16384 ||
            settings.height > 16384) {
            return Error{renderBlock.where("resolution") +
                         "resolution must be within 1..16384 pixels"};
        }
    }
    const GeoPosition sun = renderBlock.geo("sun").value_or(GeoPosition{0.4, 0.35, std::nullopt});
    setup.defaultSun = Ellipsoid::surfaceNormal(sun.latitude, sun.longitude);
    settings.sunDirection = setup.defaultSun;
    settings.atmosphere = renderBlock.boolean("atmosphere", true);
    settings.ocean = renderBlock.boolean("ocean", true);
    settings.exposure = renderBlock.optionalNumber("exposure").value_or(1.0);
    setup.terrain.maxLevel = static_cast<int>(renderBlock.optionalNumber("max_level").value_or(24));
    setup.cacheMegabytes =
        static_cast<std::size_t>(renderBlock.optionalNumber("cache_mb").value_or(1024));
    const Value* vegetationValue = renderBlock.value("vegetation");
    const std::string vegetation = vegetationValue && vegetationValue->get<Word>()
                                       ? vegetationValue->get<Word>()->text
                                       : "lod";
    settings.vegetation.method = vegetation == "mesh"         ? VegetationMethod::Mesh
                                 : vegetation == "billboards" ? VegetationMethod::Billboard
                                                              : VegetationMethod::Lod;
    settings.vegetation.quality = renderBlock.optionalNumber("vegetation_quality").value_or(1.0);
    settings.vegetation.maximumDistance =
        renderBlock.optionalNumber("vegetation_distance").value_or(6000.0);
    return setup;
}

Result<JobView> viewForJob(const ProjectModel& model, const RenderJob& job,
                           const TerrainLayers& layers, TileProvider& tiles,
                           const RenderSetup& setup,
                           const std::map<std::string, CameraPath>& paths) {
    const Block* cameraBlock = job.camera.empty() ? nullptr : model.findCamera(job.camera);
    const Block* pathBlock = job.path.empty() ? nullptr : model.findPath(job.path);
    SYLVA_CHECK(cameraBlock != nullptr || (pathBlock != nullptr && paths.count(job.path) == 1));
    double eye = 100.0;
    double fov = 1.0;
    if (cameraBlock) {
        BlockReader camera(*cameraBlock, SchemaRegistry::builtin().find("camera"));
        eye = camera.optionalNumber("eye_height").value_or(100.0);
        fov = camera.optionalNumber("fov").value_or(1.0);
    }
    const ElevationQuery query(*layers.elevation, tiles);
    const Camera::TerrainHeight terrainHeight = [&](double latitude,
                                                    double longitude) -> Result<double> {
        // The ground as the finest ring level under an eye-height camera draws it.
        const LevelRange levels =
            LevelVisibility::visibleLevels(eye, eye, setup.terrain.maxTerrainHeight, fov,
                                           setup.settings.height, setup.terrain.maxLevel);
        Result<double> height = query.groundHeight(latitude, longitude, levels.finest);
        if (height && setup.settings.ocean) {
            return std::max(height.value(), 0.0);
        }
        return height;
    };
    JobView view;
    view.what = cameraBlock ? cameraBlock->location.toString() + ": camera '" + job.camera + "'"
                            : pathBlock->location.toString() + ": path '" + job.path + "' frame " +
                                  std::to_string(job.frame);
    Result<Camera> camera = cameraBlock ? Camera::fromBlock(*cameraBlock, terrainHeight)
                                        : paths.at(job.path).sample(job.pathTime, terrainHeight);
    if (!camera) {
        return camera.error();
    }
    view.camera = camera.value();
    view.sun = setup.defaultSun;
    if (job.time) {
        const SunPosition position = SolarPosition::at(job.unixSeconds);
        view.sun = Ellipsoid::surfaceNormal(position.subsolarLatitude, position.subsolarLongitude);
    }
    return view;
}

Status writeRenderedImage(const std::filesystem::path& path, render::Image& image,
                          const ImageMetadata& metadata) {
    if (ImageWriter::isExr(path)) {
        LinearImage radiance;
        radiance.width = image.width;
        radiance.height = image.height;
        radiance.pixels = std::move(image.radiance);
        return ImageWriter::writeLinear(path, radiance, metadata);
    }
    return ImageWriter::writeRgba8(path, image.width, image.height, image.pixels, metadata);
}

}  // namespace sylva::app
