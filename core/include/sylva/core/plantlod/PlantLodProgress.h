// PlantLodProgress: what the LoD builder reports while it runs (stage, hierarchy level,
// EM restart, overall fraction), for the CLI's progress bar. The callback may be called
// from worker threads, but never concurrently (the builder serialises the calls).
#pragma once

#include <functional>
#include <string>

namespace sylva {

struct PlantLodProgress {
    std::string stage;  // "import", "ellipsoids", "lines", "levels", "ambient occlusion"
    int level = 0;      // current level (ellipsoids) or merge step (lines); 0 when none
    int levelCount = 0;
    int restart = 0;  // finished EM restarts of the current level
    int restartCount = 0;
    double fraction = 0.0;  // of the whole build, [0, 1]
};

using PlantLodProgressCallback = std::function<void(const PlantLodProgress&)>;

}  // namespace sylva
