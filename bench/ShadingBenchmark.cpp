#include "sylva/bench/ShadingBenchmark.h"

#include "ShadowBenchmark.h"
#include "sylva/bench/BenchmarkMetrics.h"

namespace sylva::bench {

std::string ShadingBenchmarkResult::json() const {
    return metricsJson("shading", metrics, {NumberFormat::Notation::General, 6});
}

Result<ShadingBenchmarkResult> runShadingBenchmark(const render::ShaderLibrary& library,
                                                   const ShadingBenchmarkOptions& options) {
    ShadingBenchmarkResult result;
    if (Status shadows = measureShadows(library, options, result.metrics); !shadows) {
        return shadows.error();
    }
    return result;
}

}  // namespace sylva::bench
