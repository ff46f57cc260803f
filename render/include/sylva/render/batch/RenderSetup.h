// RenderSetup: what a project's `render` block says about every image of a batch — the
// SceneRenderer's settings (resolution, sun, atmosphere, ocean, exposure, vegetation),
// the terrain renderer's settings (finest level) and the tile cache budget. Jobs then
// set their own sun and output kind (JobView, BatchRenderer).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {

struct RenderSetup {
    RenderSettings settings;
    TerrainSettings terrain;
    glm::dvec3 defaultSun{0.0, 0.0, 1.0};  // ECEF unit vector to the render block's sun
    std::size_t cacheMegabytes = 1024;     // tile cache budget in MiB (render block cache_mb)
    // The render block's disk_cache folder (relative ones resolved against the project
    // file's folder), and the disk cache budget in MiB (disk_cache_mb).
    std::optional<std::filesystem::path> diskCacheFolder;
    std::uint64_t diskCacheMegabytes = 16384;

    // From `model`'s render block; width and height > 0 replace its resolution (--size).
    // Errors are located at the render block's attribute.
    static Result<RenderSetup> fromModel(const ProjectModel& model, int overrideWidth = 0,
                                         int overrideHeight = 0);
};

}  // namespace sylva::render
