// PlantsBenchmark: `sylva bench plants`, the offline plant tools: the generator's oak
// preset with 27,000 leaves generated, written as .glb (into a temporary folder, removed
// afterwards), imported with its skeleton and with the skeleton reconstructed, and a
// billboard cloud of the oak with 5,000 leaves. Medians of `runs` runs, milliseconds of
// wall time; `triangles` counts the 27k oak's leaf and branch triangles.
#pragma once

#include <string>

#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/base/Result.h"

namespace sylva::bench {

struct PlantsBenchmarkOptions {
    int runs = 3;
};

struct PlantsBenchmarkResult {
    // generate_oak_27k_ms, write_glb_ms, import_glb_ms, import_reconstruct_skeleton_ms,
    // billboard_cloud_oak_5k_ms, triangles
    MetricList metrics;
    std::string json() const;  // {"suite":"plants","metrics":{...}}, values with 3 decimals
};

// Fails with the first error of the generator, the writer, the importer or the builder.
Result<PlantsBenchmarkResult> runPlantsBenchmark(const PlantsBenchmarkOptions& options);

}  // namespace sylva::bench
