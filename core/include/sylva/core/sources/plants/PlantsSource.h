// PlantsSource (`source x : plants`): plant instances (position on the terrain,
// species, scale, rotation, tint) from point features and/or scattered over a
// density mask or polygons.
//
// Access path. produce() gives the instances of a tile encoded in an ImageTile
// (InstanceTileCodec), so instance tiles go through the same TileProvider (Scheduler,
// caches, budget) as raster tiles. Consumers (rasterize, the vegetation renderer) cast
// their input with PlantsSource::from() and call instances(key, provider), which gets
// that tile from the provider and decodes it. Every produce() is a pure function of
// the key, the inputs and the parameters: the same project gives the same instances
// whatever the worker count or request order.
//
// Scattering (a stratified "jittered grid" with a guard margin, the blue-noise
// approximation of Cook 1986 "Stochastic sampling in computer graphics", made
// global and exact in expectation):
//  - a fixed global grid of cells: latitude rows of equal height Δφ, each row split
//    into n_j equal longitude cells about `cell` metres wide at the row's poleward
//    edge, where cell = 0.99 * 100 m / sqrt(per_hectare) (one cell per instance at
//    full density);
//  - each cell has one candidate at a position drawn uniformly from the cell shrunk
//    by spacing / 2 on every side, with a generator seeded from (seed, row, cell):
//    two candidates of different cells are therefore at least `spacing` apart
//    (the Poisson-disk minimum distance, held exactly), and nothing depends on the
//    tile that asks;
//  - the candidate is kept with probability p = density x per_hectare / 10^4 x the
//    cell's ellipsoidal area, where density is the mask (bilinear) at the candidate,
//    times 1 inside / 0 outside the polygons; so the expected count over any area
//    is exactly the requested one (p is capped at 1, which only bites within a few
//    cells of the poles; cells touching a pole hold no candidate);
//  - the instance belongs to the tile of the requested level that contains it
//    (half-open bounds); its density and elevation are sampled (bilinearly) from the
//    tiles of sampleLevel() (texels of at most two cells, longitude reduction 0),
//    whatever level is requested, so a tile's instances are exactly those of its four
//    children, and the inputs are never evaluated finer than the instances need.
//    A sample tile's elevation is read only when an instance is kept in it, so where
//    the density is zero the elevation chain is never produced.
// This trades the irregularity of true dart-throwing Poisson-disk sampling for
// exact density control and tile independence; the seed's distributions (001 ch. 3)
// are statistical placements of the same kind.
//
// Species: by percentage (`species = { oak = 60%, pine = 40% }`) for scattered
// instances; from an attribute for points (`species_attribute`, through
// `species_map` when given). A value that is not a species is an error naming it.
//
// Models: `models = [@oak, @palm]` names the plant_model sources that draw the species
// (species name = model source name); models() gives them per species. The models are
// not inputs: instances do not depend on them, so their hashes stay out of this one.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sylva/core/seasons/PlantSeasons.h"
#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"
#include "sylva/core/sources/plants/InstanceTile.h"
#include "sylva/core/sources/vector/FeatureSource.h"

namespace sylva {

class PlantModelSource;

struct PlantsParameters {
    double perHectare = 100.0;  // instances per hectare where density = 1
    double spacing = 0.0;       // minimum distance between scattered instances, metres
    std::vector<std::pair<std::string, double>> species;  // name, share (any positive scale)
    std::string speciesAttribute;                         // points: attribute naming the species
    std::vector<std::pair<std::string, std::string>> speciesMap;  // attribute value -> species
    double scaleMinimum = 0.8, scaleMaximum = 1.2;
    std::string scaleAttribute;     // points: attribute with the scale
    std::string rotationAttribute;  // points: attribute with the rotation, degrees from north
    double tintVariation = 0.1;     // tint brightness uniform in [1 - v, 1 + v]
    std::uint64_t seed = 1;
};

class PlantsSource final : public Source {
public:
    // Fails when spacing exceeds the cell size per_hectare allows, or no species is given
    // for scattering.
    static Result<std::unique_ptr<PlantsSource>> make(std::string name, const Source* elevation,
                                                      const Source* density,
                                                      const FeatureSource* features,
                                                      PlantsParameters parameters);
    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    // The instances of `key`, encoded (InstanceTileCodec). Fails like instances().
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

    // The instances that belong to `key`. Fails when an input fails, a point's species
    // is unknown, or the tile is coarser than minimumLevel() (too many cells).
    Result<std::shared_ptr<const InstanceTile>> instances(const TileKey& key,
                                                          TileProvider& provider) const;

    // The instances of the tiles of key's level that lie within `marginMetres` of
    // the key's bounds (for drawing things that reach across tile borders), in plan:
    // their heights are 0 and the elevation input is not read. Why: its one caller
    // (rasterize markers into a colour layer) ignores heights, and a colour tile of
    // level 11 (~10 km) made a worker produce the elevation chain (fractal noise and
    // blends) of 30-60 sample tiles for them: 15-30 s a tile (issue 20's stall).
    Result<std::vector<PlantInstance>> instancesNear(const TileKey& key, double marginMetres,
                                                     TileProvider& provider) const;

    // The coarsest level whose tiles hold at most a few million cells.
    int minimumLevel() const;
    // The level (longitude reduction 0) whose tiles the density and elevation are
    // sampled from: the coarsest with texels of at most two cells.
    int sampleLevel() const { return sampleLevel_; }
    double cellSize() const { return cellSize_; }  // metres
    // The density mask the scattering reads (nullptr when none) and the block's parameters:
    // what the far-field canopy (CanopyProfile) derives its heights and cover from.
    const Source* density() const { return density_; }
    const PlantsParameters& parameters() const { return parameters_; }
    const std::vector<std::string>& speciesNames() const { return speciesNames_; }
    // The plant model of each species, indexed like speciesNames(); nullptr for every
    // species when the block has no `models` (markers only). With `models`, graph build
    // fails for a species without a model, so no entry is nullptr.
    const std::vector<const PlantModelSource*>& models() const { return models_; }

    // Seasons and growth (issue 21 item 3): `planted`, `growth` and the `phenology`
    // overrides of the block. They change how instances are drawn, not which exist, so
    // they stay out of the content hash (like `models`).
    const PlantSeasons& seasons() const { return seasons_; }
    // The phenology table of each species, indexed like speciesNames(): the block's
    // override over the habit of the species' model (evergreen without `models`).
    const std::vector<Phenology>& phenology() const { return phenology_; }
    // Sets the seasons (create() reads them from the block) and the per-species tables.
    void setSeasons(PlantSeasons seasons);

    // Keeps no instance inside the polygons of `footprints` (buildings, paved areas of a
    // proposal): every instance, scattered or from points, whose position lies inside one
    // is dropped. Call once, before the source produces anything; adds `footprints` to
    // the inputs and the content hash.
    void excludeInside(const FeatureSource* footprints);

    // `source` as a PlantsSource when it gives instances, else nullptr.
    static const PlantsSource* from(const Source* source);

private:
    PlantsSource(std::string name, const Source* elevation, const Source* density,
                 const FeatureSource* features, PlantsParameters parameters);
    struct Window;       // the bounds asked for, and the tile that owns the result
    class InputTiles;    // elevation and density tiles at the sample level, fetched once
    struct PointFields;  // the attribute columns of point features
    struct RowCells;     // one row of the global scattering grid
    Result<std::vector<PlantInstance>> generate(const TileKey& key, const Window& window,
                                                TileProvider& provider) const;
    Status dropExcluded(const Window& window, std::vector<PlantInstance>& out) const;
    // Point features: one instance per point the window keeps.
    Status placePoints(const std::vector<FeatureHit>& hits, const FeatureCollection& features,
                       const TileKey& key, const Window& window, InputTiles& inputs,
                       std::vector<PlantInstance>& out) const;
    Result<PointFields> pointFields(const FeatureCollection& features) const;
    Result<PlantInstance> pointInstance(const Feature& feature, std::size_t index,
                                        const PointFields& fields, const std::string& where) const;
    Result<std::uint32_t> pointSpecies(const Feature& feature, std::size_t field,
                                       const std::string& where) const;
    Result<double> pointNumber(const Feature& feature, std::size_t field,
                               const std::string& attribute, const std::string& where) const;
    // Grid scattering over the density mask and/or the polygons.
    Status scatter(const std::vector<FeatureHit>& polygons, const TileKey& key,
                   const Window& window, InputTiles& inputs, std::vector<PlantInstance>& out) const;
    Status scatterRow(int row, const std::vector<FeatureHit>& polygons, const TileKey& key,
                      const Window& window, InputTiles& inputs,
                      std::vector<PlantInstance>& out) const;
    std::vector<std::pair<double, double>> rowIntervals(const std::vector<FeatureHit>& polygons,
                                                        const Window& window, double south,
                                                        double north) const;
    Status scatterCell(const RowCells& cells, std::int64_t cell,
                       const std::vector<FeatureHit>& polygons, const TileKey& key,
                       const Window& window, InputTiles& inputs,
                       std::vector<PlantInstance>& out) const;
    // The plant model of each species from the block's `models`.
    Status attachModels(const SourceBuildContext& context);

    const Source* elevation_;
    const Source* density_;
    const FeatureSource* features_;
    const FeatureSource* exclude_ = nullptr;
    std::uint64_t parameterHash_ = 0;
    PlantsParameters parameters_;
    std::vector<std::string> speciesNames_;
    std::vector<const PlantModelSource*> models_;        // per species
    std::vector<const PlantModelSource*> modelSources_;  // `models` as listed
    PlantSeasons seasons_;
    std::vector<Phenology> phenology_;       // per species
    std::vector<double> speciesCumulative_;  // over the `species` entries, ends at 1
    double cellSize_ = 10.0;
    double rowHeight_ = 0.0;  // radians of latitude
    int rows_ = 0;
    int sampleLevel_ = 0;
};

}  // namespace sylva
