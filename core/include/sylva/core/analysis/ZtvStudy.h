// ZtvStudy: a `ztv` block of the project (core/model AnalysisSchema.cpp) turned into what
// computeViewshed needs: the DEM file, the analysis grid in the DEM's CRS, the targets
// transformed into that CRS (from WGS84 geodetic positions, as the DSL stores them) and
// the options. planZtv opens the DEM (header only) to check the block against it.
//
// Failures are user errors, returned as Result errors that start with the attribute's
// file:line:col and the block ("p.sylva:12:5: ztv 'mast': "): an elevation that is not a
// raster file, a DEM that is not projected, an extent that is malformed or reaches outside
// the DEM, a grid of more than kMaxCells cells, a target outside the extent, a screen
// that is neither a features, raster nor plants source, no target at all (neither `targets`
// nor `proposal`), a proposal source that is not an objects source or places nothing.
#pragma once

#include <string>
#include <vector>

#include "sylva/core/analysis/ElevationGrid.h"
#include "sylva/core/analysis/ProposalTargets.h"
#include "sylva/core/analysis/ScreeningSurface.h"
#include "sylva/core/analysis/Viewshed.h"
#include "sylva/core/base/Result.h"
#include "sylva/core/model/ProjectModel.h"

namespace sylva {

struct ZtvStudy {
    std::string name;
    std::string demPath;  // the raster file, absolute or relative to the current folder
    GridGeometry grid;    // in the DEM's CRS (metres)
    std::string crsWkt;   // the DEM's CRS
    std::vector<ViewshedTarget> targets;  // `targets`, then one per `proposal` top
    std::vector<ProposalTop> proposal;    // `proposal`, already among `targets` (for labels)
    ViewshedOptions options;
    std::string output;  // `output` with {name} replaced, relative to the output folder
    std::vector<ScreenLayer> screens;  // `screening`; empty: the bare-earth ZTV

    static constexpr double kMaxCells = 25.0e6;
};

// force: no limit on the number of cells (sylva analyse --force).
Result<ZtvStudy> planZtv(const ProjectModel& model, const Block& block, bool force = false);

}  // namespace sylva
