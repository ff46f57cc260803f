// PlantModelSource (`source oak : plant_model { ... }`): one plant species for the
// vegetation renderer — its source mesh and its ellipsoid/line LoD (seed 001 ch. 3),
// optionally with billboard clouds for comparison.
//
// Where the model comes from (exactly one of `preset` and `file`):
//  - `preset = "oak"` (+ `leaves`, `seed`): PlantGenerator's Weber–Penn tree;
//  - `file = "trees/oak.glb"` (.gltf, .glb, .obj): imported by PlantImporter;
//  - `file = "oak.plod"`: a prebuilt LoD only. A .plod stores no mesh, so such an asset
//    has an empty `model` (no close-up mesh: the renderer draws the LoD at every
//    distance). To have both, give the mesh as `file` or `preset` and the prebuilt LoD as
//    `lod = "oak.plod"`; the LoD is then read instead of built.
//
// Building once. asset() builds on first use (std::call_once: thread-safe, once per
// source object) and caches the built LoD on disk as
// `<cache>/plants/<content hash, 16 hex digits>.plod`, where <cache> is $SYLVA_CACHE_DIR,
// else $XDG_CACHE_HOME/sylva, else ~/.cache/sylva. The hash covers the parameters, the
// model file's bytes (and its `.plant.json` sidecar), and the builder version, so a
// second process (the next render) reads the cache instead of rebuilding. The cache file
// is written atomically; a cache file that fails to read (corrupt, truncated, other
// version) is rebuilt with a warning on stderr. Failing to write the cache is a warning
// too: the asset is still returned.
//
// Not an image source: produce() fails. The plants source references plant models in
// `models = [@oak, @palm]` (species name = model source name).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "sylva/core/plantlod/PlantAsset.h"
#include "sylva/core/seasons/Phenology.h"
#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"

namespace sylva {

struct PlantModelParameters {
    std::string preset;          // generator preset; empty when `file` is given
    std::optional<int> leaves;   // generator leaf target (the preset's own when absent)
    std::uint64_t seed = 1;      // generator seed (also seeds the LoD builder)
    std::filesystem::path file;  // model (.gltf/.glb/.obj) or LoD-only (.plod)
    std::filesystem::path lod;   // optional prebuilt .plod for the model
    bool billboards = false;     // also build billboard clouds
    // `phenology`: the species' leaf habit; none: Phenology::habitOfPlantPreset(preset).
    // Not part of the asset (or its hash): it only changes how the asset is drawn.
    std::optional<LeafHabit> leafHabit;
};

class PlantModelSource final : public Source {
public:
    // Fails (message naming the source, and the file when there is one) when neither or
    // both of preset and file are given, the preset is unknown, a file is missing or of
    // an unsupported type. `where` prefixes errors found later by asset() (the block's
    // file:line:col).
    static Result<std::unique_ptr<PlantModelSource>> make(std::string name,
                                                          PlantModelParameters parameters,
                                                          std::string where = {});
    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    // Always an error: a plant model has no raster tiles.
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;
    std::vector<std::filesystem::path> files() const override;

    // The built (or cached) asset. Thread-safe; the first call builds (seconds to a
    // minute, depending on the leaf count), later calls return the same pointer or the
    // same error. Errors: an unreadable or corrupt model or .plod (naming the file and
    // the reason), a failed LoD build.
    Result<std::shared_ptr<const PlantAsset>> asset() const;

    const PlantModelParameters& parameters() const { return parameters_; }
    // The species' leaf habit (`phenology`, else the preset's default).
    LeafHabit leafHabit() const;
    // Where asset() keeps the built LoD for this source's content hash.
    std::filesystem::path cacheFile() const;
    // $SYLVA_CACHE_DIR, else $XDG_CACHE_HOME/sylva, else $HOME/.cache/sylva (else the
    // system temporary folder's sylva-cache).
    static std::filesystem::path cacheDirectory();

    // `source` as a PlantModelSource when it is one, else nullptr.
    static const PlantModelSource* from(const Source* source);

private:
    PlantModelSource(std::string name, PlantModelParameters parameters, std::string where);
    Result<std::shared_ptr<const PlantAsset>> build() const;

    PlantModelParameters parameters_;
    std::string where_;
    mutable std::once_flag once_;
    mutable std::optional<Result<std::shared_ptr<const PlantAsset>>> asset_;
};

}  // namespace sylva
