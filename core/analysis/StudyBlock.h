// StudyBlock: what the analysis blocks (`ztv`, `shadow_study`) read alike from the
// project: the DEM behind `elevation`, the grid from `extent` and `resolution`, the
// screens of `screening`. Private to core/analysis. Errors start with the attribute's
// file:line:col (BlockReader::where or the list item's location).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sylva/core/analysis/ElevationGrid.h"
#include "sylva/core/analysis/ScreeningSurface.h"
#include "sylva/core/base/Result.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/core/sources/vector/FeatureCollection.h"

namespace sylva {

std::string formatMetres(double v);  // "12.5 m"

// A project-relative file path made usable from the current folder.
std::string projectRelative(const ProjectModel& model, const std::string& file);

// The `elevation` reference: a raster source whose file is the DEM (its path).
Result<std::string> demPathOf(const ProjectModel& model, const BlockReader& reader);

// The project's `crs` (`project { crs }`), empty when it has none.
std::string projectCrsOf(const ProjectModel& model);

// The analysis grid in the DEM's CRS: `extent` (given in the project's CRS when the
// project has one, like [x, y] positions, else in the DEM's; another CRS is converted to
// the bounding box of the extent's corners and edge midpoints) or `extent_geo` (two
// corners in latitude/longitude, converted likewise), either of which must lie inside the
// DEM; without them `fallback` (a box in the DEM's CRS, clipped to the DEM) or the whole
// DEM; snapped to whole cells of `resolution` (default: the DEM's cell size); at most
// `maxCells` cells.
Result<GridGeometry> gridOf(const BlockReader& reader, const RasterInfo& dem,
                            const std::string& projectCrs, double maxCells,
                            const std::optional<std::array<double, 4>>& fallback = std::nullopt);

// The project's sources, built on first use (only blocks that screen with plants or take
// their targets from the proposal need them) and evaluated synchronously on the CPU.
class ProjectSources {
public:
    explicit ProjectSources(const ProjectModel& model) : model_(model) {}
    // The source `name` of the project's graph; fails with the graph's own error.
    Result<const Source*> find(const std::string& name);
    TileProvider& provider() { return evaluator_; }

private:
    const ProjectModel& model_;
    std::optional<SourceGraph> graph_;
    TileEvaluator evaluator_;
};

// The grid's area as WGS84 bounds (radians), widened by `marginMetres`.
Result<GeographicBounds> geographicAreaOf(const GridGeometry& grid, const std::string& crsWkt,
                                          double marginMetres);

// `screening`: features sources are building footprints (height attribute
// `screen_height_attribute`), raster sources canopy heights, plants sources their crowns
// over the grid (PlantCrowns). `what` names the block in errors ("ztv 'mast'").
Status readScreens(const ProjectModel& model, const BlockReader& reader, const std::string& what,
                   const GridGeometry& grid, const std::string& crsWkt,
                   std::vector<ScreenLayer>& screens);

}  // namespace sylva
