#include "sylva/core/analysis/ZtvStudy.h"

#include <ogr_srs_api.h>

#include <cmath>
#include <filesystem>

#include "StudyBlock.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/sources/GdalDatasetPool.h"

namespace sylva {

namespace {

constexpr double kRadian = 180.0 / 3.14159265358979323846;

Status readTargets(const BlockReader& reader, const std::string& wkt, ZtvStudy& study) {
    const Value* targets = reader.value("targets");
    const ValueList* list = targets ? targets->get<ValueList>() : nullptr;
    if (list == nullptr || list->empty())
        return Error{reader.where("targets") + "a ztv needs at least one target"};
    auto transform = GdalDatasetPool::fromLonLat(wkt);
    if (!transform)
        return Error{reader.where("elevation") + transform.error().message};
    for (const Value& item : *list) {
        const ValueObject* object = item.get<ValueObject>();
        SYLVA_CHECK(object != nullptr);
        const GeoPosition* position = nullptr;
        double height = 0.0;
        for (const auto& [key, value] : *object) {
            if (key == "position")
                position = value.get<GeoPosition>();
            if (key == "height")
                height = value.get<Quantity>()->value;
        }
        SYLVA_CHECK(position != nullptr);
        double x = position->longitude * kRadian, y = position->latitude * kRadian;
        if (OCTTransform(static_cast<OGRCoordinateTransformationH>(*transform), 1, &x, &y,
                         nullptr) == 0)
            return Error{item.location.toString() + ": ztv '" + study.name +
                         "': the target cannot be converted to the elevation raster's CRS"};
        if (!study.grid.containsCentreHull(x, y))
            return Error{item.location.toString() + ": ztv '" + study.name +
                         "': the target lies outside the extent (at " + formatMetres(x) + " E, " +
                         formatMetres(y) + " N in the elevation raster's CRS)"};
        study.targets.push_back({x, y, height});
    }
    return Status::success();
}

}  // namespace

Result<ZtvStudy> planZtv(const ProjectModel& model, const Block& block, bool force) {
    const BlockReader reader(block, SchemaRegistry::builtin().find("ztv"));
    ZtvStudy study;
    study.name = block.name;
    auto dem = demPathOf(model, reader);
    if (!dem)
        return dem.error();
    study.demPath = *dem;
    auto info = readRasterInfo(study.demPath);
    if (!info)
        return Error{reader.where("elevation") + info.error().message};
    if (!info->projected)
        return Error{reader.where("elevation") + study.demPath +
                     ": the DEM needs a projected CRS in metres (warp it, e.g. gdalwarp -t_srs "
                     "EPSG:32632)"};
    study.crsWkt = info->crsWkt;
    auto grid = gridOf(reader, *info, force ? 1e300 : ZtvStudy::kMaxCells);
    if (!grid)
        return grid.error();
    study.grid = *grid;
    if (Status ok = readTargets(reader, study.crsWkt, study); !ok)
        return ok.error();
    study.options.observerHeight = reader.optionalNumber("observer_height").value_or(2.0);
    study.options.curvature = reader.boolean("curvature", true);
    study.options.refraction = reader.optionalNumber("refraction").value_or(0.13);
    if (Status ok = readScreens(model, reader, "ztv '" + study.name + "'", study.screens); !ok)
        return ok.error();
    study.output = reader.string("output", "out/{name}.tif");
    for (std::size_t at; (at = study.output.find("{name}")) != std::string::npos;)
        study.output.replace(at, 6, study.name);
    return study;
}

}  // namespace sylva
