// RenderManifest: the record of a batch render (manifest.json in the output folder):
// per image its camera, scenario, time, the content hash of everything that decides
// its pixels, timings and tiles generated. `sylva render --resume` skips an image
// whose entry has the current hash and whose file exists; every finished image
// rewrites the manifest atomically (temporary file + rename), so an interrupted run
// leaves a manifest that lists exactly the images that are complete.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "sylva/core/base/Result.h"

namespace sylva {

struct ManifestEntry {
    std::string output;  // path as written, relative to the manifest's folder when inside it
    std::string view, camera, path, scenario, time, kind;
    int frame = -1;
    std::uint64_t hash = 0;  // content hash of the job (project content, camera, time, settings)
    double seconds = 0;      // wall time to make the image
    std::uint64_t tilesGenerated = 0;
};

class RenderManifest {
public:
    explicit RenderManifest(std::filesystem::path file) : file_(std::move(file)) {}

    // Reads the manifest if it exists (a missing file is an empty manifest); a corrupt
    // one is an error naming the file and the reason.
    Status load();
    // Writes atomically. Errors name the file.
    Status save() const;

    void record(const ManifestEntry& entry) { entries_[entry.output] = entry; }
    // Whether `output` is recorded with `hash` and the image file exists.
    bool isCurrent(const std::string& output, std::uint64_t hash) const;
    const std::map<std::string, ManifestEntry>& entries() const { return entries_; }
    const std::filesystem::path& file() const { return file_; }

private:
    std::filesystem::path file_;
    std::map<std::string, ManifestEntry> entries_;
};

}  // namespace sylva
