// VectorBenchmark: `sylva bench vector`, the vector kinds' tile rates near Olinda:
//  - rasterize_tiles_per_s: `rasterize` of 300 random 64-gons (0.2–2 km radius, 20 m
//    outlines, a GeoJSON file written to the temporary folder) over a 0.5° square at
//    levels 11–13, one thread (TileEvaluator);
//  - plants_tiles_per_s_level14, plants_instances_per_tile: `plants` scattering (150
//    per hectare, 3 m spacing, two species, density 0.8) of the first 32 level-14
//    tiles of the same square.
// CPU only; rates in tiles per second of wall time.
#pragma once

#include <string>

#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/base/Result.h"

namespace sylva::bench {

struct VectorBenchmarkOptions {
    int polygons = 300;   // rasterized
    int plantTiles = 32;  // level-14 tiles scattered
};

struct VectorBenchmarkResult {
    MetricList metrics;        // in the order above
    std::string json() const;  // {"suite":"vector","metrics":{...}}, values with 3 decimals
};

// Fails when the temporary GeoJSON file cannot be written or read back, or a source
// cannot be made (the message says which).
Result<VectorBenchmarkResult> runVectorBenchmark(const VectorBenchmarkOptions& options);

}  // namespace sylva::bench
