// `sylva bench SUITE [options]`: benchmarks as their own command (never timed unit
// tests). Each suite prints {"suite":..., "metrics":{...}} with --json.
#include <cstdio>
#include <string_view>

#include "Commands.h"
#include "ProjectSession.h"

namespace sylva::app {

int runBench(const std::vector<std::string>& arguments) {
    struct Suite {
        std::string_view name;
        int (*run)(const std::vector<std::string>&);
    };
    static constexpr Suite kSuites[] = {
        {"terrain", &runTerrainBench},
    };
    if (arguments.empty()) {
        reportError("bench needs a suite: terrain");
        return 2;
    }
    const std::vector<std::string> rest(arguments.begin() + 1, arguments.end());
    for (const Suite& suite : kSuites) {
        if (suite.name == arguments[0]) {
            return suite.run(rest);
        }
    }
    reportError("unknown benchmark suite '" + arguments[0] + "' (known: terrain)");
    return 2;
}

}  // namespace sylva::app
