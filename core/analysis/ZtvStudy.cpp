#include "sylva/core/analysis/ZtvStudy.h"

#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "StudyBlock.h"
#include "sylva/core/geo/ProjectedCoordinates.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/sources/GdalDatasetPool.h"

namespace sylva {

namespace {

constexpr double kRadian = 180.0 / 3.14159265358979323846;

Status readTargets(const BlockReader& reader, const std::string& wkt, ZtvStudy& study) {
    const Value* targets = reader.block().find("targets") ? reader.value("targets") : nullptr;
    const ValueList* list = targets ? targets->get<ValueList>() : nullptr;
    if (list == nullptr || list->empty())
        return Status::success();
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

// `proposal`: every model an objects source places, at its highest point (ProposalTargets).
Status readProposal(const ProjectModel& model, const BlockReader& reader, ZtvStudy& study) {
    const Value* proposal = reader.block().find("proposal") ? reader.value("proposal") : nullptr;
    const ValueList* list = proposal ? proposal->get<ValueList>() : nullptr;
    if (list == nullptr)
        return Status::success();
    ProjectSources sources(model);
    for (const Value& item : *list) {
        const Reference* reference = item.get<Reference>();
        const Block* block = reference ? model.findSource(reference->name) : nullptr;
        const std::string where = item.location.toString() + ": ztv '" + study.name + "': ";
        if (block == nullptr || block->kind != "objects")
            return Error{where + (block ? "'" + reference->name + "' is a " + block->kind +
                                              " source; proposal targets come from objects "
                                              "sources (placed models)"
                                        : std::string("a proposal target must be a source"))};
        auto built = sources.find(reference->name);
        const MeshSource* meshes = built ? MeshSource::from(*built) : nullptr;
        if (meshes == nullptr)
            return Error{where + (built ? "'" + reference->name + "' gives no meshes"
                                        : built.error().message)};
        auto tops = proposalTops(reference->name, *meshes, sources.provider());
        if (!tops)
            return Error{where + tops.error().message};
        for (ProposalTop& top : *tops) {
            auto xy = ProjectedCoordinates::fromGeodetic(study.crsWkt, top.latitude, top.longitude);
            if (!xy)
                return Error{where + top.label + ": " + xy.error().message};
            if (!study.grid.containsCentreHull(xy->x, xy->y))
                return Error{where + top.label + " lies outside the extent (at " +
                             formatMetres(xy->x) + " E, " + formatMetres(xy->y) +
                             " N in the elevation raster's CRS)"};
            top.x = xy->x;
            top.y = xy->y;
            study.targets.push_back({top.x, top.y, top.height});
            study.proposal.push_back(top);
        }
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
    auto grid = gridOf(reader, *info, projectCrsOf(model), force ? 1e300 : ZtvStudy::kMaxCells);
    if (!grid)
        return grid.error();
    study.grid = *grid;
    if (Status ok = readTargets(reader, study.crsWkt, study); !ok)
        return ok.error();
    if (Status ok = readProposal(model, reader, study); !ok)
        return ok.error();
    if (study.targets.empty() && study.proposal.empty())
        return Error{reader.where("targets") + "ztv '" + study.name +
                     "' has no target: give `targets` or `proposal`"};
    study.options.observerHeight = reader.optionalNumber("observer_height").value_or(2.0);
    study.options.curvature = reader.boolean("curvature", true);
    study.options.refraction = reader.optionalNumber("refraction").value_or(0.13);
    if (Status ok = readScreens(model, reader, "ztv '" + study.name + "'", study.grid, study.crsWkt,
                                study.screens);
        !ok)
        return ok.error();
    study.output = reader.string("output", "out/{name}.tif");
    for (std::size_t at; (at = study.output.find("{name}")) != std::string::npos;)
        study.output.replace(at, 6, study.name);
    return study;
}

}  // namespace sylva
