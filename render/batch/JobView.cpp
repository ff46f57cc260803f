#include "sylva/render/batch/JobView.h"

#include <algorithm>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/geo/SolarPosition.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/terrain/ElevationQuery.h"
#include "sylva/core/terrain/LevelVisibility.h"

namespace sylva::render {

Result<JobView> JobView::forJob(const ProjectModel& model, const RenderJob& job,
                                const TerrainLayers& layers, TileProvider& tiles,
                                const RenderSetup& setup, const CameraPath* path) {
    const Block* cameraBlock = job.camera.empty() ? nullptr : model.findCamera(job.camera);
    const Block* pathBlock = job.path.empty() ? nullptr : model.findPath(job.path);
    SYLVA_CHECK(cameraBlock != nullptr || (pathBlock != nullptr && path != nullptr));
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
                                        : path->sample(job.pathTime, terrainHeight);
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

RenderSettings JobView::settingsFor(const RenderSetup& setup, const RenderJob& job) const {
    RenderSettings settings = setup.settings;
    settings.sunDirection = sun;
    if (!settings.plantDate && job.time) {  // render `date` wins; else the view's date
        if (Result<PlantDate> day = PlantDate::fromDateTime(*job.time)) {
            settings.plantDate = day.value();
        }
    }
    settings.linearOutput = ImageWriter::isExr(job.output);
    if (camera.print.valid()) {  // a print format fixes this camera's pixel size
        settings.width = camera.print.pixelsWide();
        settings.height = camera.print.pixelsHigh();
    }
    return settings;
}

}  // namespace sylva::render
