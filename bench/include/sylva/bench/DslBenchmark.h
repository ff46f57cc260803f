// DslBenchmark: `sylva bench dsl`. Parses, resolves and checks a generated project of
// 5,000 lines (500 sources in noise → normal_map → hypsometric chains, 20 scenarios
// each extending the previous one with an override, 50 cameras, one views block)
// through the whole loader, in memory; the median of `runs` loads.
#pragma once

#include <cstddef>
#include <string>

#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/base/Result.h"

namespace sylva::bench {

struct DslBenchmarkOptions {
    int runs = 7;  // loads timed; the median is reported
};

struct DslBenchmarkResult {
    MetricList metrics;        // check_ms_5k_lines (median, ms), lines
    std::string json() const;  // {"suite":"dsl","metrics":{...}}, values with 3 decimals
};

// Fails with the loader's rendered diagnostics if the generated project does not check
// (a bug of the generator, never of the user's input).
Result<DslBenchmarkResult> runDslBenchmark(const DslBenchmarkOptions& options);

// The generated project text, padded with comment lines to `targetLines` lines.
std::string generateDslProject(std::size_t targetLines);

}  // namespace sylva::bench
