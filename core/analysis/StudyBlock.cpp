#include "StudyBlock.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>

#include <ogr_srs_api.h>

#include "sylva/core/geo/ProjectedCoordinates.h"
#include "sylva/core/model/Schema.h"
#include "sylva/core/sources/plants/PlantsSource.h"

namespace sylva {

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

Result<const Source*> ProjectSources::find(const std::string& name) {
    if (!graph_) {
        auto graph = SourceGraph::build(model_);
        if (!graph)
            return graph.error();
        graph_.emplace(std::move(*graph));
    }
    const Source* source = graph_->find(name);
    if (source == nullptr)
        return Error{"no source '" + name + "' in the project's graph"};
    return source;
}

Result<GeographicBounds> geographicAreaOf(const GridGeometry& grid, const std::string& crsWkt,
                                          double marginMetres) {
    GeographicBounds area = GeographicBounds::empty();
    const double east = grid.originX + grid.width * grid.cellWidth;
    const double south = grid.originY - grid.height * grid.cellHeight;
    // Corners and edge midpoints: a projected rectangle's edges bow little in latitude
    // and longitude at study sizes; the margin covers the rest.
    for (double fx : {0.0, 0.5, 1.0})
        for (double fy : {0.0, 0.5, 1.0}) {
            auto point =
                ProjectedCoordinates::toGeodetic(crsWkt, grid.originX + fx * (east - grid.originX),
                                                 grid.originY + fy * (south - grid.originY));
            if (!point)
                return point.error();
            area.extend(glm::dvec2(point->longitude, point->latitude));
        }
    const double latitudeMargin = marginMetres / 6.35e6;
    const double longitudeMargin =
        latitudeMargin /
        std::max(0.01, std::cos(std::max(std::abs(area.north), std::abs(area.south))));
    area.west -= longitudeMargin;
    area.east += longitudeMargin;
    area.south -= latitudeMargin;
    area.north += latitudeMargin;
    return area;
}

namespace {

// A plants source's crowns over the grid, in the grid's CRS.
Status readPlantScreen(const std::string& name, const PlantsSource& plants, TileProvider& provider,
                       const GridGeometry& grid, const std::string& crsWkt,
                       const std::string& where, ScreenLayer& layer) {
    constexpr double kCrownMargin = 50.0;  // metres: crowns standing outside reach in
    auto area = geographicAreaOf(grid, crsWkt, kCrownMargin);
    if (!area)
        return Error{where + area.error().message};
    auto crowns = plantCrowns(name, plants, *area, provider);
    if (!crowns)
        return Error{where + crowns.error().message};
    for (PlantCrown& crown : *crowns) {
        auto xy = ProjectedCoordinates::fromGeodetic(crsWkt, crown.latitude, crown.longitude);
        if (!xy)
            return Error{where + xy.error().message};
        crown.x = xy->x;
        crown.y = xy->y;
    }
    layer.kind = ScreenLayer::Kind::Plants;
    layer.path = name;
    layer.crowns = std::move(*crowns);
    return Status::success();
}

}  // namespace

// `screening`: features sources are building footprints, raster sources canopy heights,
// plants sources their crowns.
Status readScreens(const ProjectModel& model, const BlockReader& reader, const std::string& what,
                   const GridGeometry& grid, const std::string& crsWkt,
                   std::vector<ScreenLayer>& screens) {
    const Value* screening = reader.block().find("screening") ? reader.value("screening") : nullptr;
    const ValueList* list = screening ? screening->get<ValueList>() : nullptr;
    if (list == nullptr)
        return Status::success();
    const std::string attribute = reader.string("screen_height_attribute", "height");
    std::optional<ProjectSources> sources;
    for (const Value& item : *list) {
        const Reference* reference = item.get<Reference>();
        const Block* source = reference ? model.findSource(reference->name) : nullptr;
        const std::string where = item.location.toString() + ": " + what + ": ";
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
        } else if (source->kind == "plants") {
            if (!sources)
                sources.emplace(model);
            auto built = sources->find(reference->name);
            const PlantsSource* plants = built ? PlantsSource::from(*built) : nullptr;
            if (plants == nullptr)
                return Error{where + (built ? "'" + reference->name + "' gives no plants"
                                            : built.error().message)};
            if (Status ok = readPlantScreen(reference->name, *plants, sources->provider(), grid,
                                            crsWkt, where, layer);
                !ok)
                return ok;
            screens.push_back(std::move(layer));
            continue;
        } else {
            return Error{where + "'" + reference->name + "' is a " + source->kind +
                         " source; a screen is a features source (building footprints with a "
                         "height), a raster source (canopy height) or a plants source (its "
                         "crowns)"};
        }
        layer.path = projectRelative(model, sourceReader.string("file"));
        screens.push_back(layer);
    }
    return Status::success();
}

// The project's `crs` (empty when the project has none).
std::string projectCrsOf(const ProjectModel& model) {
    const Attribute* crs = model.project.find("crs");
    const std::string* text = crs ? crs->value.get<std::string>() : nullptr;
    return text ? *text : std::string();
}

namespace {

bool sameCrs(const std::string& a, const std::string& b) {
    OGRSpatialReferenceH first = OSRNewSpatialReference(nullptr);
    OGRSpatialReferenceH second = OSRNewSpatialReference(nullptr);
    const bool same = OSRSetFromUserInput(first, a.c_str()) == OGRERR_NONE &&
                      OSRSetFromUserInput(second, b.c_str()) == OGRERR_NONE &&
                      OSRIsSame(first, second) != 0;
    OSRDestroySpatialReference(first);
    OSRDestroySpatialReference(second);
    return same;
}

// [west, south, east, north] in `fromCrs` as the bounding box, in `toCrs`, of its corners
// and edge midpoints (a rectangle in one projected CRS bows little in another at study
// sizes; the box holds the corners exactly).
Result<std::array<double, 4>> extentIn(const std::array<double, 4>& extent,
                                       const std::string& fromCrs, const std::string& toCrs) {
    std::array<double, 4> box = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (double fx : {0.0, 0.5, 1.0})
        for (double fy : {0.0, 0.5, 1.0}) {
            auto geodetic =
                ProjectedCoordinates::toGeodetic(fromCrs, extent[0] + fx * (extent[2] - extent[0]),
                                                 extent[1] + fy * (extent[3] - extent[1]));
            if (!geodetic)
                return geodetic.error();
            auto xy =
                ProjectedCoordinates::fromGeodetic(toCrs, geodetic->latitude, geodetic->longitude);
            if (!xy)
                return xy.error();
            box = {std::min(box[0], xy->x), std::min(box[1], xy->y), std::max(box[2], xy->x),
                   std::max(box[3], xy->y)};
        }
    return box;
}

}  // namespace

namespace {

using Box = std::array<double, 4>;  // west, south, east, north

// `extent` as a box in the DEM's CRS: four lengths in the project's CRS (or the DEM's).
Result<Box> lengthExtent(const BlockReader& reader, const RasterInfo& dem,
                         const std::string& projectCrs) {
    const ValueList* list = reader.value("extent")->get<ValueList>();
    if (list == nullptr || list->size() != 4)
        return Error{reader.where("extent") +
                     "extent needs four lengths [west, south, east, north]"};
    Box box = {(*list)[0].get<Quantity>()->value, (*list)[1].get<Quantity>()->value,
               (*list)[2].get<Quantity>()->value, (*list)[3].get<Quantity>()->value};
    if (!(box[2] > box[0] && box[3] > box[1]))
        return Error{reader.where("extent") + "extent must have west < east and south < north"};
    if (projectCrs.empty() || sameCrs(projectCrs, dem.crsWkt))
        return box;
    auto converted = extentIn(box, projectCrs, dem.crsWkt);
    if (!converted)
        return Error{reader.where("extent") + "the extent (in the project's crs '" + projectCrs +
                     "') cannot be converted to the DEM's CRS: " + converted.error().message};
    return *converted;
}

// `extent_geo` as a box in the DEM's CRS: two opposite corners in latitude/longitude (the
// DSL turns [x, y] corners in the project's CRS into geo positions too); the box holds the
// DEM-CRS images of the corners and edge midpoints of the latitude/longitude rectangle.
Result<Box> geoExtent(const BlockReader& reader, const RasterInfo& dem) {
    const ValueList* list = reader.value("extent_geo")->get<ValueList>();
    const GeoPosition* a = list && list->size() == 2 ? (*list)[0].get<GeoPosition>() : nullptr;
    const GeoPosition* b = list && list->size() == 2 ? (*list)[1].get<GeoPosition>() : nullptr;
    if (a == nullptr || b == nullptr)
        return Error{reader.where("extent_geo") +
                     "extent_geo needs two opposite corners [geo(south, west), geo(north, east)]"};
    const double south = std::min(a->latitude, b->latitude),
                 north = std::max(a->latitude, b->latitude);
    const double west = std::min(a->longitude, b->longitude),
                 east = std::max(a->longitude, b->longitude);
    if (!(north > south && east > west))
        return Error{reader.where("extent_geo") +
                     "the corners of extent_geo must differ in latitude and in longitude"};
    Box box = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (double fx : {0.0, 0.5, 1.0})
        for (double fy : {0.0, 0.5, 1.0}) {
            auto xy = ProjectedCoordinates::fromGeodetic(dem.crsWkt, south + fy * (north - south),
                                                         west + fx * (east - west));
            if (!xy)
                return Error{
                    reader.where("extent_geo") +
                    "the corners cannot be converted to the DEM's CRS: " + xy.error().message};
            box = {std::min(box[0], xy->x), std::min(box[1], xy->y), std::max(box[2], xy->x),
                   std::max(box[3], xy->y)};
        }
    return box;
}

std::string demBoundsText(const GridGeometry& d) {
    return formatMetres(d.originX) + " .. " + formatMetres(d.originX + d.width * d.cellWidth) +
           " east, " + formatMetres(d.originY - d.height * d.cellHeight) + " .. " +
           formatMetres(d.originY) + " north in the DEM's CRS";
}

}  // namespace

// The analysis grid: `extent` or `extent_geo`, else `fallback`, else the DEM, snapped to
// whole cells of `resolution`.
Result<GridGeometry> gridOf(const BlockReader& reader, const RasterInfo& dem,
                            const std::string& projectCrs, double maxCells,
                            const std::optional<std::array<double, 4>>& fallback) {
    const GridGeometry& d = dem.geometry;
    const Box whole = {d.originX, d.originY - d.height * d.cellHeight,
                       d.originX + d.width * d.cellWidth, d.originY};
    const bool hasExtent = reader.block().find("extent") != nullptr;
    const bool hasGeo = reader.block().find("extent_geo") != nullptr;
    if (hasExtent && hasGeo)
        return Error{reader.where("extent_geo") + "give either extent or extent_geo, not both"};
    Box box = whole;
    if (hasExtent || hasGeo) {
        auto given = hasExtent ? lengthExtent(reader, dem, projectCrs) : geoExtent(reader, dem);
        if (!given)
            return given.error();
        box = *given;
        const double tolerance = 1e-6 * d.cellWidth;
        if (box[0] < whole[0] - tolerance || box[1] < whole[1] - tolerance ||
            box[2] > whole[2] + tolerance || box[3] > whole[3] + tolerance)
            return Error{reader.where(hasExtent ? "extent" : "extent_geo") + "the extent " +
                         "reaches outside the elevation raster (" + demBoundsText(d) + ")"};
    } else if (fallback) {
        box = {std::max((*fallback)[0], whole[0]), std::max((*fallback)[1], whole[1]),
               std::min((*fallback)[2], whole[2]), std::min((*fallback)[3], whole[3])};
    }
    const double cell = reader.optionalNumber("resolution").value_or(d.cellWidth);
    GridGeometry grid{box[0],
                      box[3],
                      cell,
                      cell,
                      int(std::floor((box[2] - box[0]) / cell + 1e-9)),
                      int(std::floor((box[3] - box[1]) / cell + 1e-9))};
    if (grid.width < 2 || grid.height < 2)
        return Error{reader.where("resolution") + "the extent holds fewer than 2 × 2 cells of " +
                     formatMetres(cell)};
    if (double(grid.width) * double(grid.height) > maxCells)
        return Error{reader.where("resolution") + "the grid would have " +
                     std::to_string(grid.width) + " × " + std::to_string(grid.height) +
                     " cells, more than the limit of " + std::to_string(std::int64_t(maxCells)) +
                     "; choose a coarser resolution (or sylva analyse --force)"};
    return grid;
}

}  // namespace sylva
