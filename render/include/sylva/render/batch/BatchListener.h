// BatchListener: how a batch run tells its caller what happens, so the CLI (or a test,
// or a viewer) decides how to print it. Every message the run produces comes through
// here; the library itself writes nothing to stdout or stderr.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "sylva/core/scene/ViewSeries.h"
#include "sylva/core/terrain/LevelVisibility.h"

namespace sylva::render {

// One job that is done: written, or skipped because its manifest record is current.
struct JobReport {
    const RenderJob* job = nullptr;  // the plan's job; valid during the call
    bool skipped = false;
    double seconds = 0;  // wall time to make it (0 when skipped)
    // Images and comparisons: the size written. Images: the terrain levels drawn, the
    // triangles and the tiles produced for this image (not found in the cache).
    int width = 0;
    int height = 0;
    LevelRange levels;
    std::uint64_t triangles = 0;
    std::size_t tiles = 0;
    // Comparisons: the scenarios of the two images compared.
    std::string firstScenario;
    std::string secondScenario;
    // Progress over the run: jobs done so far (this one included), of `total`, and the
    // estimated seconds left (elapsed / done × remaining).
    std::size_t done = 0;
    std::size_t total = 0;
    double etaSeconds = 0;
};

class BatchListener {
public:
    virtual ~BatchListener() = default;
    // A job is done (see JobReport).
    virtual void jobDone(const JobReport& report) = 0;
    // A user or data error that does not stop the run: a job that failed (its message
    // names the camera or file and the reason), an image drawn with coarser terrain, a
    // manifest that could not be saved.
    virtual void error(const std::string& message) = 0;
    // A contact sheet of `images` thumbnails was written to `file`.
    virtual void contactSheetWritten(const std::filesystem::path& file, std::size_t images) {
        (void)file;
        (void)images;
    }
};

}  // namespace sylva::render
