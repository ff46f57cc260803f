// SourceGraph: the typed dependency graph of sources built from a ProjectModel
// (seed 001 §4.4, Fig. 4.2b). Owns every Source; sources reference their inputs by
// pointer, so the graph must outlive every TileProvider that evaluates it.
//
// Building fails with a located message (file:line:col of the offending attribute)
// for an unknown kind, a missing or mistyped input or a dependency cycle; the DSL
// normally reports these first, the graph re-checks so hand-built models are safe.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/sources/Source.h"

namespace sylva {

class PlantsSource;
class MeshSource;

// The sources that feed the terrain clipmaps of one scenario.
struct TerrainLayers {
    const Source* elevation = nullptr;        // required
    const Source* color = nullptr;            // may be null: a neutral grey is drawn
    const Source* normals = nullptr;          // never null: derived from elevation if not given
    std::vector<const PlantsSource*> plants;  // drawn by the vegetation renderer (may be empty)
    std::vector<const MeshSource*> meshes;    // buildings and objects (the mesh renderer)
};

class SourceGraph {
public:
    static Result<SourceGraph> build(const ProjectModel& model);

    SourceGraph(SourceGraph&&) noexcept;
    SourceGraph& operator=(SourceGraph&&) noexcept;
    ~SourceGraph();

    const Source* find(std::string_view name) const;
    std::size_t size() const { return sources_.size(); }

    // The content hashes of every source of the graph and their inputs (for
    // Scheduler::retainOnly after a reload) and every file they read (for FileWatch).
    std::unordered_set<std::uint64_t> contentHashes() const;
    std::vector<std::filesystem::path> files() const;

    // The layers of a scenario (its `layers` list, one source per port type), or of
    // the first scenario when `scenario` is empty. Adds a derived normal_map source
    // when the scenario has none.
    Result<TerrainLayers> terrainLayers(const ProjectModel& model, std::string_view scenario);

private:
    SourceGraph() = default;
    std::vector<std::unique_ptr<Source>> sources_;
};

}  // namespace sylva
