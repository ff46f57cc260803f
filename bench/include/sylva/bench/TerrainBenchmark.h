// TerrainBenchmark: `sylva bench terrain`. A scripted flight from 800 km down to 50 m
// (the altitudes of seed 001 Table 4.1) over a DEM, rendered by the spherical
// clipmap at 1280x720, against a brute-force full-resolution grid mesh of the same
// DEM, and the same flight over a DEM with 16x the samples (triangles must not grow).
// Needs a current GL 4.5 context.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/render/gl/ShaderLibrary.h"

namespace sylva::bench {

struct TerrainBenchmarkOptions {
    int width = 1280;
    int height = 720;
    int demSamples = 4096;     // per side of the base DEM
    double demDegrees = 4.0;   // side of the DEM, degrees of latitude and longitude
    int framesPerSegment = 6;  // frames between successive altitudes of the flight
    int bruteForceFrames = 5;  // brute-force frames sampled along the flight
    std::string framesFolder;  // if set, each clipmap frame is written there as flight_NNN.png
    // Frames wait until every level's tiles are ready (as batch rendering does); the
    // default draws the levels that are ready while the Scheduler's workers produce
    // the rest (seed 001 §4.7), as an interactive viewer would.
    bool waitForTiles = false;
    std::size_t cacheBytes = 256u << 20;  // the Scheduler's tile cache budget
};

struct TerrainBenchmarkResult {
    std::map<std::string, double> metrics;
    std::vector<std::pair<double, std::pair<int, int>>>
        levelsPerAltitude;     // altitude -> (coarsest, finest)
    std::string json() const;  // {"suite":"terrain","metrics":{...},"levels_rendered":[...]}
};

Result<TerrainBenchmarkResult> runTerrainBenchmark(const render::ShaderLibrary& library,
                                                   const TerrainBenchmarkOptions& options);

}  // namespace sylva::bench
