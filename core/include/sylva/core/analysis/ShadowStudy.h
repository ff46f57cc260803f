// ShadowStudy: a `shadow_study` block of the project (core/model AnalysisSchema.cpp):
// for each date, shadow maps at every time step of a day window and the hours of direct
// sun per cell, on the DEM plus screens (buildings, canopy) as a surface model
// (ShadowCaster). The sun's direction is the NOAA solar position (SolarPosition) seen
// from the site's centre at each instant.
//
// Time: the dates are local days at `utcOffsetHours`; the window [dayStart, dayEnd]
// (hours of local clock time) is sampled at dayStart, dayStart + step, ... ≤ dayEnd
// (the frames). Hours of direct sun per cell integrate the lit samples by the
// trapezoid rule over the window (a sample below the horizon counts as shadow).
//
// The caster grid: the grid grown by `shadow_reach` on every side (whole cells of the
// grid's size, clipped to the DEM), read with its screens, so that a ridge, a building
// or a wood outside the study's extent still shades it when the sun is low. Shadows are
// computed for the grid's cells only.
//
// The site (optional): the polygons of a features source rasterized on the grid (a cell
// whose centre lies inside is a site cell). Without `extent`/`extent_geo` the grid is the
// polygons' box grown by `site_margin`, clipped to the DEM. Per date the study reports the
// site's mean hours of direct sun and the share of its cells with at least
// `sunHoursTarget` hours (BRE 209, "Site layout planning for daylight and sunlight",
// 2022: at least half of an amenity area should receive 2 hours of sun on 21 March).
//
// planShadowStudy failures are user errors that start with the attribute's
// file:line:col and the block: those of the ztv (elevation, extent, resolution,
// screening), a caster grid of more than kMaxCasterCells (lower `shadow_reach`), a date that is not
// a plain date, a window that is empty, a step that does not divide into at most 1440 frames, a
// site that is not a features source, whose data set cannot be read, holds no polygons, lies
// outside the DEM or covers no cell centre of the grid.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "sylva/core/analysis/ElevationGrid.h"
#include "sylva/core/analysis/ScreeningSurface.h"
#include "sylva/core/analysis/ShadowCaster.h"
#include "sylva/core/base/Result.h"
#include "sylva/core/model/ProjectModel.h"

namespace sylva {

struct ShadowStudy {
    std::string name;
    std::string demPath;
    GridGeometry grid;  // the DEM's CRS
    std::string crsWkt;
    std::vector<ScreenLayer> screens;
    // The ground that casts shadows into the grid (the grid's CRS, aligned with its
    // cells): the grid's cell (c, r) is the caster grid's (c + casterWindow.col,
    // r + casterWindow.row). Width 0: the grid itself (studies built in code).
    GridGeometry casterGrid;
    CellWindow casterWindow;
    std::vector<std::string> dates;  // "2024-06-21"
    double stepMinutes = 60.0;
    double dayStartHours = 0.0, dayEndHours = 24.0;  // local clock time
    double utcOffsetHours = 0.0;
    double latitude = 0.0, longitude = 0.0;  // radians: the site's centre, for the sun
    std::string output;                      // folder, {name} replaced
    std::string sitePath;                    // the site's data set; empty: no site
    std::vector<std::uint8_t> site;          // per cell, 1 in the site; empty: no site
    std::size_t siteCells = 0;
    double sunHoursTarget = 2.0;  // hours of direct sun a site cell needs (the share)

    static constexpr double kMaxCells = 4.0e6;
    static constexpr double kMaxCasterCells = 6.4e7;  // the caster grid, without --force
};

// force: no limit on the number of cells (sylva analyse --force).
Result<ShadowStudy> planShadowStudy(const ProjectModel& model, const Block& block,
                                    bool force = false);

struct ShadowFrame {
    std::string label;                      // local clock time "08:30"
    double unixSeconds = 0.0;               // UTC
    double azimuth = 0.0, elevation = 0.0;  // the sun, radians
    std::vector<std::uint8_t> lit;          // per cell, 1 = direct sun
};

struct ShadowDay {
    std::string date;
    std::vector<ShadowFrame> frames;
    std::vector<float> sunHours;  // per cell, hours of direct sun in the window
    // Over the site's cells with data (NaN without a site): mean hours of direct sun, and
    // the share (0..1) of cells with at least ShadowStudy::sunHoursTarget hours.
    double siteMeanSunHours = std::numeric_limits<double>::quiet_NaN();
    double siteShareAtTarget = std::numeric_limits<double>::quiet_NaN();
};

// One date of the study, on the caster's window (the study's grid when the caster grid is
// larger). Fails when the date cannot be read.
Result<ShadowDay> computeShadowDay(const ShadowCaster& caster, const ShadowStudy& study,
                                   const std::string& date);

}  // namespace sylva
