// PlantLodBenchmark: `sylva bench plantlod`, the plant LoD builder (seed 001 ch. 3)
// against the thesis: the generator's oak (seed 7) with the leaf counts of seed 001
// Table 3.1 built with buildPlantLod, its wall and CPU seconds compared with the
// thesis's precomputation minutes, and per level the primitive counts, image error
// (multi-scale RMSE) and GPU bytes; billboard clouds (seed 003) of the same models at
// five texel densities for the equal-memory comparison of Fig. 3.19 (19 kB).
//
// Metrics, in this order, per model (LABEL 1k, 5k, 10k, 27k; level k):
//   build_s_LABEL, cpu_s_LABEL, levels_LABEL, branch_segments_LABEL,
//   ellipsoids_lK_LABEL, lines_lK_LABEL, rmse_lK_LABEL, bytes_lK_LABEL (per level),
//   bbc_planes_lK_LABEL, bbc_rmse_lK_LABEL, bbc_bytes_lK_LABEL (per billboard level, at
//   the default density; with billboards);
// then speedup_vs_thesis_min (the smallest thesis time / build time) and, with
// billboards, rmse_lod_19kb and rmse_bbc_19kb (the lowest error within 19 kB).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantLodBuilder.h"

namespace sylva::bench {

// A model of seed 001 Table 3.1: leaf count, metric label and the thesis's
// precomputation time in minutes.
struct ThesisPlantModel {
    int leaves;
    const char* label;
    double thesisMinutes;
};

// The four models of Table 3.1 (1,000, 5,000, 10,000 and 27,000 leaves).
const std::vector<ThesisPlantModel>& thesisPlantModels();
// The model with `leaves` leaves, nullopt when the table has none.
std::optional<ThesisPlantModel> thesisPlantModel(int leaves);

struct PlantLodBenchmarkOptions {
    PlantLodOptions lod;                                         // the builder's options (threads)
    std::vector<ThesisPlantModel> models = thesisPlantModels();  // built in this order
    bool billboards = true;      // billboard clouds and the equal-memory comparison
    std::string montagePath;     // non-empty: a PNG of every level of every model and preset
    bool reportProgress = true;  // "plantlod: LABEL leaves in S s" on stderr per model
};

struct PlantLodBenchmarkResult {
    MetricList metrics;        // in the order above
    std::string json() const;  // {"suite":"plantlod","metrics":{...}}, values with 4 decimals
};

// Fails with the builder's or the image writer's error.
Result<PlantLodBenchmarkResult> runPlantLodBenchmark(const PlantLodBenchmarkOptions& options);

}  // namespace sylva::bench
