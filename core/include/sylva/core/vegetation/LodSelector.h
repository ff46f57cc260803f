// LodSelector: per-instance level-of-detail selection for the vegetation renderer
// (seed 001 §6.3), on the CPU, once per instance and never per primitive.
//
// The error an instance tolerates is the size of one pixel at its distance, in metres
// (e = distance × pixel angle / quality), the unit of the PlantLod error intervals. The
// thesis interpolates a per-model table from the projected bounding box; since the
// intervals are already in metres per pixel, the table collapses to this product.
//
// Instead of one draw per instance (what a sequential primitive tree would issue), the
// error axis is cut into geometric buckets (ratio kBucketRatio). Every instance of one
// species and bucket draws the same prefix of the primitive arrays — the prefix for the
// bucket's smallest error, widened by half the screen-door transition band — so a frame
// is a few instanced draws per species. Primitives of the prefix outside an instance's
// own interval are dropped by the vertex shader, which also fades primitives within the
// band around their interval ends by a dither pattern (screen-door transparency, Mulder
// et al. 1998): the finer and the coarser set are drawn on complementary pixels, so no
// LoD step pops. The same fade hands over from the source mesh (close-ups) to the finest
// LoD, and between billboard-cloud levels.
//
// Cost: one pass over the instances (transform to view space, sphere/frustum test, error,
// bucket), a counting sort, and a pass writing the selected instances' view transforms;
// both passes run in chunks on a WorkerPool. The output does not depend on the thread
// count: chunks are contiguous ranges of instances, merged in order. Frames: instances are stored
// relative to a double- precision ECEF origin per batch; everything the GPU sees is in
// camera-relative view space (metres, float).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/plantlod/BillboardCloudBuilder.h"
#include "sylva/core/plantlod/PlantAsset.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/vegetation/DepthPyramid.h"

namespace sylva {

// Instances near one ECEF origin (a tile, or a hand-made group in tests and benchmarks),
// stored as they are consumed every frame.
struct InstanceBatch {
    glm::dvec3 origin{0.0};  // ECEF, metres
    struct Instance {
        glm::vec3 base{0.0f};    // stem base relative to origin, ECEF metres
        glm::vec3 axes[3];       // model x, y, z in ECEF (rotation and scale applied)
        glm::vec3 center{0.0f};  // bounding-sphere centre relative to origin, ECEF metres
        float radius = 0.0f;     // bounding-sphere radius, metres
        glm::vec3 tint{1.0f};    // linear RGB factor
        std::uint32_t species = 0;
        std::uint32_t hash = 0;  // decorrelates the dither patterns of neighbours
    };
    std::vector<Instance> instances;
    // Per instance (same order): bounding-sphere centre relative to origin (xyz, ECEF
    // metres) and radius (w) — all the culling pass reads, packed so that it streams
    // 16 bytes per instance instead of the whole Instance.
    std::vector<glm::vec4> spheres;
    // Bounding sphere of all instances' spheres, relative to origin (per-tile culling).
    glm::vec3 boundsCenter{0.0f};
    float boundsRadius = 0.0f;
    float largestInstanceRadius = 0.0f;
    // A hash of origin and instances, set by makeBatch (batches are not changed after
    // it): what the shadow cache (VegetationRenderer::shadowCacheKey) knows a batch by.
    std::uint64_t contentHash = 0;
};

// One instance placed on the globe: `up` is the ellipsoid normal at its base, heading
// is clockwise from north (radians), scale multiplies the model.
struct InstancePlacement {
    glm::dvec3 baseEcef{0.0};
    double latitude = 0.0, longitude = 0.0;  // radians (to build the local frame)
    float heading = 0.0f;
    float scale = 1.0f;
    // The up axis is scaled by scale × heightScale (growth: a young tree's height and
    // crown grow at different rates, GrowthCurve).
    float heightScale = 1.0f;
    glm::vec3 tint{1.0f};
    std::uint32_t species = 0;
};

// Per species: the bounding sphere of the model and the primitive prefix per bucket.
struct SpeciesLod {
    glm::vec3 sphereCenter{0.0f};  // model frame, metres
    float sphereRadius = 0.0f;     // metres
    float height = 0.0f;           // top of the model above the stem base, metres
    float meshError = 0.0f;        // below this error the source mesh is drawn (0: never)
    std::uint32_t ellipsoidCount = 0;
    std::uint32_t lineCount = 0;
    // Per bucket: primitives of the prefix (arrays sorted by errorMaximum descending).
    std::vector<std::uint32_t> ellipsoidPrefix;
    std::vector<std::uint32_t> linePrefix;
    // Per bucket: the largest radius (metres, model frame) of an ellipsoid an instance of
    // the bucket may draw — what the renderer needs to bound the sprite sizes of a run.
    std::vector<float> ellipsoidRadius;
    // Billboard-cloud levels: level i is drawn in [billboardError[i], billboardError[i+1]).
    // At most LodSelector::kMaxBillboardLevels.
    std::vector<float> billboardError;
    // Radius (metres, model frame) around sphereCenter that holds everything drawn for the
    // species (DrawnExtent; may exceed sphereRadius): the sphere occlusion culling tests.
    float drawnRadius = 0.0f;
};

enum class VegetationMethod : std::uint8_t {
    Lod,        // ellipsoids and lines (the source mesh for close-ups when enabled)
    Billboard,  // billboard clouds (comparison, seed 003)
    Mesh,       // the source mesh everywhere (reference)
    // Point-sampled plants with approximate visible sets (seed 000 ch. 3), selected like
    // Lod without the mesh handover (the bucket sets the prefix).
    Points,
    // Displacement-mapped billboard clouds (seed 000 ch. 5): the billboard levels,
    // selected like Billboard, ray-marched as boxes.
    DisplacedBillboard,
    Impostors,  // view-direction and group impostors (seeds 004, 000 ch. 7): one transform
                // per visible instance, in the species' mesh run, for ImpostorRenderer
};

struct LodSelectionSettings {
    double pixelAngle = 1e-3;      // radians per pixel (vertical field of view / height)
    double quality = 1.0;          // > 1 draws finer levels
    double minimumPixels = 1.5;    // instances smaller than this on screen are skipped
    double maximumDistance = 0.0;  // metres; 0 = no limit besides minimumPixels
    double transitionBand = 0.35;  // width of the screen-door fades in ln(error)
    bool closeUpMesh = true;       // Lod method: hand over to the source mesh up close
    VegetationMethod method = VegetationMethod::Lod;
    // View frustum: the four side planes in view space (inward unit normals through the
    // origin) and the near distance in metres.
    glm::vec3 sidePlanes[4];
    double near = 0.1;
    // Orthographic views (the sun's shadow maps): `sideOffsets` move the side planes off the
    // origin (a plane keeps points with dot(normal, p) + offset >= 0, metres), and a
    // positive `fixedDistance` (metres) replaces each instance's distance in the error
    // (e = fixedDistance × pixelAngle: one shadow texel) and in the size culling. Set
    // `near` very negative to keep instances on either side of the origin.
    float sideOffsets[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    double fixedDistance = 0.0;
    // Occlusion culling (issue 21): instances and batches whose drawn sphere (the
    // instance sphere scaled to SpeciesLod::drawnRadius) is hidden behind the pyramid's
    // depths are skipped and counted in LodSelection::occludedInstances. Null: off. Not
    // owned; it must match this selection's camera and projection.
    const DepthPyramid* occlusion = nullptr;
    // Instances whose sphere centre is at most this far (metres) are skipped: with
    // maximumDistance it splits one frame into a near selection (the occluders, drawn
    // first) and a far one culled against the depth the near one left.
    double minimumDistance = 0.0;
};

// What the GPU receives per drawn instance: the model → view transform (three axis
// columns and the origin, view space, metres) and the tint, the tolerated error and the
// dither hash. 80 bytes, std430/vertex-attribute friendly.
struct DrawInstance {
    glm::vec4 axisX;   // xyz, w: tolerated error (metres per pixel)
    glm::vec4 axisY;   // xyz, w: dither offset in [0, 1) from the instance hash
    glm::vec4 axisZ;   // xyz, w: unused
    glm::vec4 origin;  // xyz, w: 1
    glm::vec4 tint;    // rgb, a: 1
};

// A run of instances drawing the same thing: `kind` Primitives uses the species'
// prefix of bucket `bucket`; Mesh draws the source mesh; Billboard draws level `level`.
struct DrawRun {
    enum class Kind : std::uint8_t { Primitives, Mesh, Billboard } kind = Kind::Primitives;
    std::uint32_t species = 0;
    std::uint32_t bucket = 0;  // Primitives: bucket; Billboard: level
    std::uint32_t ellipsoids = 0, lines = 0;
    std::uint32_t firstInstance = 0;
    std::uint32_t instanceCount = 0;
};

struct LodSelection {
    std::vector<DrawInstance> instances;
    std::vector<DrawRun> runs;
    std::size_t consideredInstances = 0;
    std::size_t visibleInstances = 0;
    std::size_t drawnEllipsoids = 0;  // upper bound: prefixes times instances
    std::size_t drawnLines = 0;
    // Instances that passed every other test but were hidden (LodSelectionSettings::
    // occlusion), and the instances of batches hidden as a whole.
    std::size_t occludedInstances = 0;
};

// The selector of one renderer (or benchmark): an object so that it owns the per-chunk
// scratch of its passes, which keeps its capacity from frame to frame (fresh buffers
// would be paged in again every frame). Not thread-safe: one select() at a time per
// object; the passes themselves run on the WorkerPool given at construction.
class LodSelector {
public:
    static constexpr int kBucketCount = 64;
    static constexpr double kBucketRatio = 1.25;
    static constexpr double kSmallestError = 1e-4;  // metres per pixel of bucket 0
    // Billboard-cloud levels per species the run keys have room for.
    static constexpr int kMaxBillboardLevels = int(sylva::kMaxBillboardLevels);
    // Run-key slots per species: the primitive buckets, the mesh, the billboard levels.
    static constexpr int kSlotsPerSpecies = kBucketCount + 1 + kMaxBillboardLevels;
    // Run keys are 16 bits and 0xFFFF means "none": species × slots must stay below it.
    static constexpr int kMaxSpecies = (0xFFFF - 1) / kSlotsPerSpecies;

    // `pool` runs the per-instance passes; null: WorkerPool::shared(). Not owned: it must
    // outlive the selector.
    explicit LodSelector(WorkerPool* pool = nullptr);

    // The tables of one species; meshError is the finest ellipsoid level's own error
    // (below it a leaf covers more than ~5 pixels and the source mesh is drawn).
    // billboardError is left empty: the renderer fills it when it has billboard levels.
    static SpeciesLod describe(const PlantAsset& asset, double transitionBand);

    // Whether a species with `billboardLevels` billboard-cloud levels can be added as
    // species number `index` (0-based) without overflowing the run keys. The error names
    // `name` and the limit that is exceeded; callers attaching plant LoDs check this.
    static Status checkSpecies(std::size_t index, std::size_t billboardLevels,
                               const std::string& name);

    // Builds a batch from placements (local frame: east, north, up at each base; model
    // +Y to the heading). `species` gives each species' bounding sphere.
    static InstanceBatch makeBatch(const glm::dvec3& origin,
                                   const std::vector<InstancePlacement>& placements,
                                   const std::vector<SpeciesLod>& species);

    static int bucketOf(double error);
    static double bucketLowerError(int bucket);

    // Selects and fills `out` (reused between frames to keep its capacity). `species`
    // must pass checkSpecies (SYLVA_CHECK: at most kMaxSpecies species, at most
    // kMaxBillboardLevels billboard levels each).
    void select(const std::vector<const InstanceBatch*>& batches,
                const std::vector<SpeciesLod>& species, const Camera& camera,
                const LodSelectionSettings& settings, LodSelection& out);

    // The frustum side planes of a symmetric perspective camera, view space.
    static void setFrustum(LodSelectionSettings& settings, double verticalFov, double aspect);

private:
    // The per-instance decision of one frame.
    struct Decision {
        std::uint32_t batch = 0, index = 0;
        float error = 0.0f;
        glm::vec3 originView{0.0f};
        std::uint16_t key = 0;   // run key: species × slots + slot
        std::uint16_t key2 = 0;  // second run during a handover (0xFFFF: none)
    };
    struct Frame;  // what every pass of one select() reads

    std::size_t cullBatches(const std::vector<const InstanceBatch*>& batches, const Frame& frame);
    void decideChunk(int chunk, const Frame& frame);
    void sortRuns(const Frame& frame, LodSelection& out);
    void writeInstances(const Frame& frame, LodSelection& out);

    WorkerPool* pool_;
    // Scratch of select(), kept between frames.
    std::vector<const InstanceBatch*> batches_;      // the batches that pass the culling
    std::vector<std::size_t> batchStart_;            // first instance of each, then the total
    std::vector<std::vector<Decision>> decided_;     // pass 1: per chunk
    std::vector<std::uint32_t> start_;               // first instance per run key, then the total
    std::vector<std::vector<std::uint32_t>> slots_;  // pass 2: per chunk, two per decision
    std::vector<std::size_t> occluded_;              // pass 1: per chunk, hidden instances
    std::size_t occludedBatchInstances_ = 0;         // instances of batches hidden as a whole
};

}  // namespace sylva
