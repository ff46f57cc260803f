#include "sylva/core/analysis/ShadowStudy.h"

#include <ogr_srs_api.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "PolygonLayer.h"
#include "StudyBlock.h"
#include "sylva/core/geo/SolarPosition.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/scene/DateTime.h"
#include "sylva/core/sources/GdalDatasetPool.h"

namespace sylva {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Hours of a local clock time written "14:30:00".
Result<double> clockHours(const BlockReader& reader, const char* attribute, double fallback) {
    if (reader.block().find(attribute) == nullptr)
        return fallback;
    auto time = DateTime::parse(reader.string(attribute, ""));
    if (!time || time->hasDate() || !time->hasTime())
        return Error{reader.where(attribute) + "'" + attribute +
                     "' must be a time of day (06:00:00)"};
    auto midnight = DateTime::parse("1970-01-01T00:00:00+00:00");
    auto seconds = midnight->withTimeOf(*time).unixSeconds();
    if (!seconds)
        return Error{reader.where(attribute) + seconds.error().message};
    return *seconds / 3600.0;
}

Status readDates(const BlockReader& reader, ShadowStudy& study) {
    const Value* dates = reader.value("dates");
    const ValueList* list = dates ? dates->get<ValueList>() : nullptr;
    if (list == nullptr || list->empty())
        return Error{reader.where("dates") + "a shadow_study needs at least one date"};
    for (const Value& item : *list) {
        const std::string* text = item.get<std::string>();
        auto date = text ? DateTime::parse(*text) : Result<DateTime>(Error{"not a date"});
        if (!date || !date->hasDate() || date->hasTime())
            return Error{item.location.toString() + ": shadow_study '" + study.name +
                         "': a date is a plain day (2024-06-21)"};
        study.dates.push_back(*text);
    }
    return Status::success();
}

// The site's centre in longitude/latitude (radians), for the sun's direction.
Status siteCentre(const BlockReader& reader, ShadowStudy& study) {
    OGRSpatialReferenceH grid = OSRNewSpatialReference(study.crsWkt.c_str());
    OGRSpatialReferenceH wgs84 = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(wgs84, 4326);
    OSRSetAxisMappingStrategy(grid, OAMS_TRADITIONAL_GIS_ORDER);
    OSRSetAxisMappingStrategy(wgs84, OAMS_TRADITIONAL_GIS_ORDER);
    OGRCoordinateTransformationH transform = OCTNewCoordinateTransformation(grid, wgs84);
    double x = study.grid.originX + 0.5 * study.grid.width * study.grid.cellWidth;
    double y = study.grid.originY - 0.5 * study.grid.height * study.grid.cellHeight;
    const bool ok = transform != nullptr && OCTTransform(transform, 1, &x, &y, nullptr) != 0;
    if (transform != nullptr)
        OCTDestroyCoordinateTransformation(transform);
    OSRDestroySpatialReference(grid);
    OSRDestroySpatialReference(wgs84);
    if (!ok)
        return Error{reader.where("elevation") + "the DEM's CRS cannot be converted to lon/lat"};
    study.longitude = x * kPi / 180.0;
    study.latitude = y * kPi / 180.0;
    return Status::success();
}

Status readWindow(const BlockReader& reader, ShadowStudy& study) {
    auto start = clockHours(reader, "from", 0.0);
    if (!start)
        return start.error();
    auto end = clockHours(reader, "to", 24.0);
    if (!end)
        return end.error();
    study.dayStartHours = *start;
    study.dayEndHours = *end == 0.0 ? 24.0 : *end;
    if (!(study.dayEndHours > study.dayStartHours))
        return Error{reader.where("to") + "the day window is empty ('to' must follow 'from')"};
    study.stepMinutes = reader.optionalNumber("step_minutes").value_or(60.0);
    const double frames = (study.dayEndHours - study.dayStartHours) * 60.0 / study.stepMinutes;
    if (!(study.stepMinutes > 0.0) || frames > 1440.0)
        return Error{reader.where("step_minutes") + "the step gives more than 1440 frames a day"};
    study.utcOffsetHours = reader.optionalNumber("utc_offset")
                               .value_or(std::round(study.longitude * 180.0 / kPi / 15.0));
    return Status::success();
}

// The `site` reference: its features source's data set, read in the DEM's CRS.
Result<std::vector<PolygonFeature>> readSite(const ProjectModel& model, const BlockReader& reader,
                                             const std::string& demWkt, ShadowStudy& study) {
    const std::optional<std::string> name = reader.reference("site");
    const Block* source = name ? model.findSource(*name) : nullptr;
    if (source == nullptr || source->kind != "features")
        return Error{reader.where("site") + "the site must be a features source (polygons)"};
    const BlockReader sourceReader(*source, SchemaRegistry::builtin().find("source", "features"));
    PolygonLayerRequest request;
    request.path = projectRelative(model, sourceReader.string("file"));
    request.layer = sourceReader.string("layer", "");
    request.role = "a site";
    study.sitePath = request.path;
    auto polygons = readPolygons(request, demWkt);
    if (!polygons)
        return Error{reader.where("site") + polygons.error().message};
    if (polygons->empty())
        return Error{reader.where("site") + request.path + ": the site holds no polygons"};
    return polygons;
}

// The site's cells on the study's grid; fails when the site covers no cell centre.
Status rasterizeSite(const BlockReader& reader, const std::vector<PolygonFeature>& polygons,
                     ShadowStudy& study) {
    auto burnt = rasterizePolygons(polygons, study.grid, study.crsWkt, study.sitePath);
    if (!burnt)
        return Error{reader.where("site") + burnt.error().message};
    study.site.resize(burnt->size());
    for (std::size_t i = 0; i < burnt->size(); ++i)
        study.siteCells += (study.site[i] = (*burnt)[i] > 0.0f ? 1 : 0);
    if (study.siteCells == 0)
        return Error{reader.where("site") + study.sitePath +
                     ": the site covers no cell centre of the grid (outside the extent or "
                     "smaller than a cell of " +
                     formatMetres(study.grid.cellWidth) + ")"};
    return Status::success();
}

// The grid: `extent`/`extent_geo`, else the site's box grown by `site_margin`, else the DEM.
Status readGrid(const ProjectModel& model, const BlockReader& reader, const RasterInfo& dem,
                bool force, ShadowStudy& study) {
    std::optional<std::vector<PolygonFeature>> site;
    std::optional<std::array<double, 4>> around;
    if (reader.block().find("site") != nullptr) {
        auto polygons = readSite(model, reader, dem.crsWkt, study);
        if (!polygons)
            return polygons.error();
        const double margin = reader.optionalNumber("site_margin").value_or(250.0);
        std::array<double, 4> box = polygonBounds(*polygons);
        const GridGeometry& d = dem.geometry;
        if (box[2] < d.originX || box[0] > d.originX + d.width * d.cellWidth ||
            box[3] < d.originY - d.height * d.cellHeight || box[1] > d.originY)
            return Error{reader.where("site") + study.sitePath +
                         ": the site lies outside the elevation raster"};
        around = std::array<double, 4>{box[0] - margin, box[1] - margin, box[2] + margin,
                                       box[3] + margin};
        site = std::move(*polygons);
    }
    auto grid =
        gridOf(reader, dem, projectCrsOf(model), force ? 1e300 : ShadowStudy::kMaxCells, around);
    if (!grid)
        return grid.error();
    study.grid = *grid;
    if (site)
        return rasterizeSite(reader, *site, study);
    return Status::success();
}

// The caster grid: the grid grown by `shadow_reach` on every side in whole cells, clipped to
// the DEM (a shadow needs ground to fall from).
Status readCasterGrid(const BlockReader& reader, const RasterInfo& dem, bool force,
                      ShadowStudy& study) {
    const double reach = reader.optionalNumber("shadow_reach").value_or(5000.0);
    const GridGeometry& g = study.grid;
    const GridGeometry& d = dem.geometry;
    // Whole cells of the grid between its edges and the DEM's, at most `reach`.
    const auto cells = [](double room, double size, double reachCells) {
        return int(std::max(0.0, std::min(std::floor(room / size + 1e-9), reachCells)));
    };
    const double acrossX = std::ceil(reach / g.cellWidth - 1e-9);
    const double acrossY = std::ceil(reach / g.cellHeight - 1e-9);
    const int west = cells(g.originX - d.originX, g.cellWidth, acrossX);
    const int east = cells(d.originX + d.width * d.cellWidth - (g.originX + g.width * g.cellWidth),
                           g.cellWidth, acrossX);
    const int north = cells(d.originY - g.originY, g.cellHeight, acrossY);
    const int south =
        cells(g.originY - g.height * g.cellHeight - (d.originY - d.height * d.cellHeight),
              g.cellHeight, acrossY);
    GridGeometry caster = g;
    caster.originX -= west * g.cellWidth;
    caster.originY += north * g.cellHeight;
    caster.width += west + east;
    caster.height += north + south;
    const double total = double(caster.width) * double(caster.height);
    if (!force && total > ShadowStudy::kMaxCasterCells) {
        char text[200];
        std::snprintf(text, sizeof text,
                      "the study's grid grown by shadow_reach has %.0f cells, more than %.0f: "
                      "lower shadow_reach or coarsen the resolution (or --force)",
                      total, ShadowStudy::kMaxCasterCells);
        return Error{reader.where("shadow_reach") + text};
    }
    study.casterGrid = caster;
    study.casterWindow = {west, north, g.width, g.height};
    return Status::success();
}

}  // namespace

Result<ShadowStudy> planShadowStudy(const ProjectModel& model, const Block& block, bool force) {
    const BlockReader reader(block, SchemaRegistry::builtin().find("shadow_study"));
    ShadowStudy study;
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
                     ": the DEM needs a projected CRS in metres"};
    study.crsWkt = info->crsWkt;
    if (Status ok = readGrid(model, reader, *info, force, study); !ok)
        return ok.error();
    if (Status ok = readCasterGrid(reader, *info, force, study); !ok)
        return ok.error();
    study.sunHoursTarget = reader.optionalNumber("sun_hours_target").value_or(2.0);
    const std::string what = "shadow_study '" + study.name + "'";
    // Screens over the caster grid: a wood or a building outside the extent casts too.
    if (Status ok = readScreens(model, reader, what, study.casterGrid, study.crsWkt, study.screens);
        !ok)
        return ok.error();
    if (Status ok = readDates(reader, study); !ok)
        return ok.error();
    if (Status ok = siteCentre(reader, study); !ok)
        return ok.error();
    if (Status ok = readWindow(reader, study); !ok)
        return ok.error();
    study.output = reader.string("output", "out/{name}");
    for (std::size_t at; (at = study.output.find("{name}")) != std::string::npos;)
        study.output.replace(at, 6, study.name);
    return study;
}

namespace {

void summarizeSite(const ShadowStudy& study, ShadowDay& day) {
    if (study.site.size() != day.sunHours.size())
        return;
    double sum = 0.0;
    std::size_t cells = 0, atTarget = 0;
    for (std::size_t i = 0; i < day.sunHours.size(); ++i)
        if (study.site[i] != 0 && !std::isnan(day.sunHours[i])) {
            sum += day.sunHours[i];
            ++cells;
            // The hours are sums of step weights in float: allow their rounding.
            atTarget += day.sunHours[i] >= study.sunHoursTarget - 1e-4 ? 1 : 0;
        }
    if (cells == 0)
        return;
    day.siteMeanSunHours = sum / double(cells);
    day.siteShareAtTarget = double(atTarget) / double(cells);
}

}  // namespace

Result<ShadowDay> computeShadowDay(const ShadowCaster& caster, const ShadowStudy& study,
                                   const std::string& date) {
    auto day = DateTime::parse(date + "T00:00:00+00:00");
    if (!day)
        return day.error();
    auto midnightUtc = day->unixSeconds();
    if (!midnightUtc)
        return midnightUtc.error();
    ShadowDay out;
    out.date = date;
    const CellWindow& window = caster.window();
    const std::size_t cells = std::size_t(window.width) * std::size_t(window.height);
    out.sunHours.assign(cells, 0.0f);
    const double step = study.stepMinutes / 60.0;  // hours
    const int count = int(std::floor((study.dayEndHours - study.dayStartHours) / step + 1e-9)) + 1;
    for (int k = 0; k < count; ++k) {
        const double local = study.dayStartHours + k * step;
        ShadowFrame frame;
        frame.unixSeconds = *midnightUtc + (local - study.utcOffsetHours) * 3600.0;
        const SunDirection sun =
            SolarPosition::seenFrom(frame.unixSeconds, study.latitude, study.longitude);
        frame.azimuth = sun.azimuth;
        frame.elevation = sun.elevation;
        char label[16];
        const int minutes = int(std::lround(local * 60.0));
        std::snprintf(label, sizeof label, "%02d:%02d", minutes / 60, minutes % 60);
        frame.label = label;
        frame.lit = caster.sunlitCells(sun.azimuth, sun.elevation);
        // Trapezoid weights: half a step at both ends of the window.
        const double weight = (k == 0 || k == count - 1) && count > 1 ? 0.5 * step : step;
        for (std::size_t i = 0; i < cells; ++i)
            out.sunHours[i] += frame.lit[i] ? float(weight) : 0.0f;
        out.frames.push_back(std::move(frame));
    }
    for (int row = 0; row < window.height; ++row)
        for (int col = 0; col < window.width; ++col)
            if (std::isnan(caster.ground().at(window.col + col, window.row + row)))
                out.sunHours[std::size_t(row) * std::size_t(window.width) + std::size_t(col)] =
                    std::numeric_limits<float>::quiet_NaN();
    summarizeSite(study, out);
    return out;
}

}  // namespace sylva
