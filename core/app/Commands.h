// The sylva sub-commands. Each takes the arguments after its name and returns the
// process exit code: 0 success, 1 an error in the project, data or environment
// (reported on stderr with its location), 2 a usage error.
#pragma once

#include <string>
#include <vector>

namespace sylva::app {

int runRender(const std::vector<std::string>& arguments);
int runCheck(const std::vector<std::string>& arguments);
int runBench(const std::vector<std::string>& arguments);
int runTerrainBench(const std::vector<std::string>& arguments);

}  // namespace sylva::app
