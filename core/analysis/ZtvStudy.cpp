#include "sylva/core/analysis/ZtvStudy.h"

#include <ogr_srs_api.h>

#include <cmath>
#include <filesystem>

#include "sylva/core/model/BlockReader.h"
#include "sylva/core/sources/GdalDatasetPool.h"

namespace sylva {

namespace {

constexpr double kRadian = 180.0 / 3.14159265358979323846;

std::string formatMetres(double v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.1f m", v);
    return text;
}

// The `elevation` reference: a raster source whose file is the DEM.
Result<std::string> demPathOf(const ProjectModel& model, const BlockReader& reader) {
    const std::optional<std::string> name = reader.reference("elevation");
    const Block* source = name ? model.findSource(*name) : nullptr;
    if (source == nullptr)
        return Error{reader.where("elevation") + "missing value for 'elevation'"};
    const BlockReader sourceReader(*source, SchemaRegistry::builtin().find("source", source->kind));
    const std::string file = source->kind == "raster" ? sourceReader.string("file") : "";
    if (file.empty())
        return Error{reader.where("elevation") + "'" + *name + "' is a " + source->kind +
                     " source; a ztv needs a raster source (a DEM file)"};
    const std::filesystem::path path(file);
    const std::filesystem::path folder =
        model.file.has_parent_path() ? model.file.parent_path() : std::filesystem::path(".");
    return (path.is_absolute() ? path : (folder / path).lexically_normal()).string();
}

std::string projectRelative(const ProjectModel& model, const std::string& file) {
    const std::filesystem::path path(file);
    const std::filesystem::path folder =
        model.file.has_parent_path() ? model.file.parent_path() : std::filesystem::path(".");
    return (path.is_absolute() ? path : (folder / path).lexically_normal()).string();
}

// `screening`: features sources are building footprints, raster sources canopy heights.
Status readScreens(const ProjectModel& model, const BlockReader& reader, ZtvStudy& study) {
    const Value* screening = reader.block().find("screening") ? reader.value("screening") : nullptr;
    const ValueList* list = screening ? screening->get<ValueList>() : nullptr;
    if (list == nullptr)
        return Status::success();
    const std::string attribute = reader.string("screen_height_attribute", "height");
    for (const Value& item : *list) {
        const Reference* reference = item.get<Reference>();
        const Block* source = reference ? model.findSource(reference->name) : nullptr;
        const std::string where = item.location.toString() + ": ztv '" + study.name + "': ";
        if (source == nullptr)
            return Error{where + "a screen must be a source"};
        const BlockReader sourceReader(*source,
                                       SchemaRegistry::builtin().find("source", source->kind));
        ScreenLayer layer;
        if (source->kind == "features") {
            layer.kind = ScreenLayer::Kind::Buildings;
            layer.layer = sourceReader.string("layer", "");
            layer.heightAttribute = attribute;
        } else if (source->kind == "raster") {
            layer.kind = ScreenLayer::Kind::Canopy;
        } else {
            return Error{where + "'" + reference->name + "' is a " + source->kind +
                         " source; a screen is a features source (building footprints with a "
                         "height) or a raster source (canopy height)"};
        }
        layer.path = projectRelative(model, sourceReader.string("file"));
        study.screens.push_back(layer);
    }
    return Status::success();
}

// The analysis grid: `extent` (default: the DEM) snapped to whole cells of `resolution`.
Result<GridGeometry> gridOf(const BlockReader& reader, const RasterInfo& dem) {
    const GridGeometry& d = dem.geometry;
    double west = d.originX, north = d.originY;
    double east = d.originX + d.width * d.cellWidth, south = d.originY - d.height * d.cellHeight;
    if (const Value* extent = reader.block().find("extent") ? reader.value("extent") : nullptr) {
        const ValueList* list = extent->get<ValueList>();
        if (list == nullptr || list->size() != 4)
            return Error{reader.where("extent") +
                         "extent needs four lengths [west, south, east, north]"};
        west = (*list)[0].get<Quantity>()->value;
        south = (*list)[1].get<Quantity>()->value;
        east = (*list)[2].get<Quantity>()->value;
        north = (*list)[3].get<Quantity>()->value;
        if (!(east > west && north > south))
            return Error{reader.where("extent") + "extent must have west < east and south < north"};
        const double tolerance = 1e-6 * d.cellWidth;
        if (west < d.originX - tolerance || north > d.originY + tolerance ||
            east > d.originX + d.width * d.cellWidth + tolerance ||
            south < d.originY - d.height * d.cellHeight - tolerance)
            return Error{
                reader.where("extent") + "the extent reaches outside the elevation raster (" +
                formatMetres(d.originX) + " .. " + formatMetres(d.originX + d.width * d.cellWidth) +
                " east, " + formatMetres(d.originY - d.height * d.cellHeight) + " .. " +
                formatMetres(d.originY) + " north)"};
    }
    const double cell = reader.optionalNumber("resolution").value_or(d.cellWidth);
    GridGeometry grid{west,
                      north,
                      cell,
                      cell,
                      int(std::floor((east - west) / cell + 1e-9)),
                      int(std::floor((north - south) / cell + 1e-9))};
    if (grid.width < 2 || grid.height < 2)
        return Error{reader.where("resolution") + "the extent holds fewer than 2 × 2 cells of " +
                     formatMetres(cell)};
    if (double(grid.width) * double(grid.height) > ZtvStudy::kMaxCells)
        return Error{reader.where("resolution") + "the grid would have " +
                     std::to_string(grid.width) + " × " + std::to_string(grid.height) +
                     " cells, more than the limit of 25 million; choose a coarser resolution"};
    return grid;
}

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

Result<ZtvStudy> planZtv(const ProjectModel& model, const Block& block) {
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
    auto grid = gridOf(reader, *info);
    if (!grid)
        return grid.error();
    study.grid = *grid;
    if (Status ok = readTargets(reader, study.crsWkt, study); !ok)
        return ok.error();
    study.options.observerHeight = reader.optionalNumber("observer_height").value_or(2.0);
    study.options.curvature = reader.boolean("curvature", true);
    study.options.refraction = reader.optionalNumber("refraction").value_or(0.13);
    if (Status ok = readScreens(model, reader, study); !ok)
        return ok.error();
    study.output = reader.string("output", "out/{name}.tif");
    for (std::size_t at; (at = study.output.find("{name}")) != std::string::npos;)
        study.output.replace(at, 6, study.name);
    return study;
}

}  // namespace sylva
