// The sylva sub-commands. Each takes the arguments after its name and returns the
// process exit code: 0 success, 1 an error in the project, data or environment
// (reported on stderr with its location), 2 a usage error.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace sylva::app {

int runRender(const std::vector<std::string>& arguments);
int runCache(const std::vector<std::string>& arguments);
int runJobs(const std::vector<std::string>& arguments);
int runAssemble(const std::vector<std::string>& arguments);
int runWatch(const std::vector<std::string>& arguments);
int runView(const std::vector<std::string>& arguments);
int runCheck(const std::vector<std::string>& arguments);
int runAnalyse(const std::vector<std::string>& arguments);
int runMontage(const std::vector<std::string>& arguments);
int runFmt(const std::vector<std::string>& arguments);
int runDump(const std::vector<std::string>& arguments);
int runDoc(const std::vector<std::string>& arguments);
int runBench(const std::vector<std::string>& arguments);
int runTerrainBench(const std::vector<std::string>& arguments);
int runShadingBench(const std::vector<std::string>& arguments);
int runObjectsBench(const std::vector<std::string>& arguments);
int runTilesBench(const std::vector<std::string>& arguments);
int runVegetationBench(const std::vector<std::string>& arguments);
int runShadingBench(const std::vector<std::string>& arguments);
int runPlant(const std::vector<std::string>& arguments);
int runPlantBuild(const std::vector<std::string>& arguments);
int runPlantInfo(const std::vector<std::string>& arguments);
int runPlantLodBench(const std::vector<std::string>& arguments);
int runTurnaroundBench(const std::vector<std::string>& arguments);
int runViewerBench(const std::vector<std::string>& arguments);

// Removes every `--set block.attribute=value` (or `--set=...`) from `arguments` and
// returns them as (path, value) pairs; the option may repeat, which CommandLine does not
// allow. A malformed one sets `error`.
std::vector<std::pair<std::string, std::string>> extractSets(std::vector<std::string>& arguments,
                                                             std::string& error);

}  // namespace sylva::app
