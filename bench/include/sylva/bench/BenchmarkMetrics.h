// BenchmarkMetrics: the named figures a `sylva bench SUITE` run reports, and the one JSON
// shape every suite prints with --json: {"suite":"NAME","metrics":{"key":value,...}}.
// Suites differ only in the order of their keys (insertion order, or sorted where a
// suite keeps a std::map) and in how many digits a value gets, so both stay theirs.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sylva::bench {

// Metrics in the order they are printed.
using MetricList = std::vector<std::pair<std::string, double>>;

// How a value is written: printf's %.Nf (Fixed) or %.Ng (General), N = digits.
struct NumberFormat {
    enum class Notation { Fixed, General };
    Notation notation = Notation::General;
    int digits = 6;
};

// The median of frame or run times (the mean of the two middle values for an even count);
// 0 for none.
double median(std::vector<double> values);

// `"key":value` pairs joined by commas, in the order given.
std::string metricsJsonMembers(const MetricList& metrics, NumberFormat format);
// {"suite":"SUITE","metrics":{MEMBERS}}
std::string metricsJson(std::string_view suite, const MetricList& metrics, NumberFormat format);
// The same for a map, whose keys print sorted.
std::string metricsJson(std::string_view suite, const std::map<std::string, double>& metrics,
                        NumberFormat format);

}  // namespace sylva::bench
