#include "sylva/bench/BenchmarkMetrics.h"

#include <algorithm>
#include <cstdio>

namespace sylva::bench {

double median(std::vector<double> values) {
    if (values.empty()) {
        return 0.0;
    }
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::string metricsJsonMembers(const MetricList& metrics, NumberFormat format) {
    std::string out;
    for (std::size_t i = 0; i < metrics.size(); ++i) {
        char value[64];
        if (format.notation == NumberFormat::Notation::Fixed) {
            std::snprintf(value, sizeof value, "%.*f", format.digits, metrics[i].second);
        } else {
            std::snprintf(value, sizeof value, "%.*g", format.digits, metrics[i].second);
        }
        if (i != 0) {
            out += ',';
        }
        out += '"';
        out += metrics[i].first;
        out += "\":";
        out += value;
    }
    return out;
}

std::string metricsJson(std::string_view suite, const MetricList& metrics, NumberFormat format) {
    std::string out = "{\"suite\":\"";
    out += suite;
    out += "\",\"metrics\":{";
    out += metricsJsonMembers(metrics, format);
    out += "}}";
    return out;
}

std::string metricsJson(std::string_view suite, const std::map<std::string, double>& metrics,
                        NumberFormat format) {
    return metricsJson(suite, MetricList(metrics.begin(), metrics.end()), format);
}

}  // namespace sylva::bench
