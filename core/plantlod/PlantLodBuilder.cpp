#include "sylva/core/plantlod/PlantLodBuilder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>

#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/plantlod/AmbientOcclusion.h"
#include "sylva/core/plantlod/EllipsoidHierarchy.h"
#include "sylva/core/plantlod/ImageErrorMetric.h"
#include "sylva/core/plantlod/PrimitiveRasterizer.h"

namespace sylva {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// The pool of PlantLodOptions::threads: the shared pool for <= 0, else a pool of that
// size, its threads started once for the whole call.
class BuildPool {
public:
    explicit BuildPool(int threads) {
        if (threads > 0) {
            own_.emplace(threads);
        }
    }
    WorkerPool& get() { return own_ ? *own_ : WorkerPool::shared(); }

private:
    std::optional<WorkerPool> own_;
};

struct Bounds {
    glm::vec3 minimum{std::numeric_limits<float>::max()};
    glm::vec3 maximum{std::numeric_limits<float>::lowest()};
    void add(const glm::vec3& p, float r = 0.0f) {
        minimum = glm::min(minimum, p - glm::vec3(r));
        maximum = glm::max(maximum, p + glm::vec3(r));
    }
    bool valid() const { return minimum.x <= maximum.x; }
};

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::vector<std::vector<float>> renderReference(const PrimitiveRasterizer& rasterizer,
                                                const PlantModel& model, PlantPart part, bool all,
                                                WorkerPool& pool) {
    std::vector<std::vector<float>> images(rasterizer.viewCount());
    pool.run(rasterizer.viewCount(), [&](int view) {
        RasterFrame frame = rasterizer.blankFrame();
        rasterizer.drawMesh(model, part, all, view, frame);
        images[view] = rasterizer.resolve(frame);
    });
    return images;
}

double imageError(const PrimitiveRasterizer& rasterizer, std::span<const LodEllipsoid> ellipsoids,
                  std::span<const LodLine> lines, float lineScale,
                  const std::vector<std::vector<float>>& reference, WorkerPool& pool) {
    const int views = rasterizer.viewCount();
    std::vector<std::vector<double>> perView(views);
    pool.run(views, [&](int view) {
        thread_local RasterFrame frame;
        rasterizer.clearFrame(frame);
        rasterizer.drawEllipsoids(ellipsoids, view, frame);
        rasterizer.drawLines(lines, view, frame, lineScale);
        perView[view] = multiScaleSquaredErrors(rasterizer.resolve(frame), reference[view],
                                                rasterizer.resolution());
    });
    return multiScaleRmse(meanOverViews(perView));
}

glm::vec3 branchColor(const PlantModel& model) {
    for (const PlantMesh& mesh : model.meshes) {
        if (mesh.part == PlantPart::Branch && mesh.material >= 0 &&
            mesh.material < static_cast<int>(model.materials.size())) {
            return glm::vec3(model.materials[mesh.material].baseColor);
        }
    }
    return glm::vec3(0.3f, 0.22f, 0.15f);
}

std::vector<LodEllipsoid> ellipsoidsAt(const PlantLod& lod, float error) {
    std::vector<LodEllipsoid> drawn;
    for (const LodEllipsoid& e : lod.ellipsoids) {
        if (e.errorMinimum <= error && error < e.errorMaximum) {
            drawn.push_back(e);
        }
    }
    return drawn;
}

std::vector<LodLine> linesAt(const PlantLod& lod, float error) {
    std::vector<LodLine> drawn;
    for (const LodLine& l : lod.lines) {
        if (l.errorMinimum <= error && error < l.errorMaximum) {
            drawn.push_back(l);
        }
    }
    return drawn;
}

Bounds modelBounds(const PlantModel& model) {
    Bounds bounds;
    for (const PlantMesh& mesh : model.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            bounds.add(p);
        }
    }
    for (const SkeletonSegment& s : model.skeleton) {
        bounds.add(s.start, s.startRadius);
        bounds.add(s.end, s.endRadius);
    }
    return bounds;
}

// Finite geometry, something to build from, a power-of-two error image.
Status checkInput(const PlantModel& model, const PlantLodOptions& options,
                  const std::string& label) {
    for (const PlantMesh& mesh : model.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            if (!finite(p)) {
                return Error{label + ": mesh '" + mesh.name + "' has a non-finite vertex position"};
            }
        }
    }
    for (std::size_t i = 0; i < model.skeleton.size(); ++i) {
        const SkeletonSegment& s = model.skeleton[i];
        if (!finite(s.start) || !finite(s.end) || !std::isfinite(s.startRadius) ||
            !std::isfinite(s.endRadius)) {
            return Error{label + ": skeleton segment " + std::to_string(i) +
                         " has a non-finite coordinate"};
        }
    }
    if (model.triangleCount(PlantPart::Leaf) == 0 && model.skeleton.empty()) {
        return Error{label +
                     " has neither leaves nor a branch skeleton: nothing to build a LoD from"};
    }
    if (options.resolution <= 0 || (options.resolution & (options.resolution - 1)) != 0) {
        return Error{label + ": the error image resolution " + std::to_string(options.resolution) +
                     " is not a power of two"};
    }
    return Status::success();
}

// §3.3.3: the line width scale that best matches the branch mesh, by ternary search on
// log(scale) in [0.5, 2.5].
float calibrateLineWidth(const PlantModel& model, const glm::vec3& barkColor,
                         const PrimitiveRasterizer& rasterizer,
                         const std::vector<std::vector<float>>& branchReference, WorkerPool& pool) {
    const LineSkeleton original(model.skeleton, barkColor);
    std::vector<LodLine> lines;
    for (const LineNode& node : original.nodes()) {
        lines.push_back(node.line);
    }
    float lo = std::log(0.5f), hi = std::log(2.5f);
    for (int i = 0; i < 10; ++i) {
        const float a = lo + (hi - lo) / 3.0f, b = hi - (hi - lo) / 3.0f;
        const double ea = imageError(rasterizer, {}, lines, std::exp(a), branchReference, pool);
        const double eb = imageError(rasterizer, {}, lines, std::exp(b), branchReference, pool);
        (ea <= eb ? hi : lo) = ea <= eb ? b : a;
    }
    return std::exp(0.5f * (lo + hi));
}

// Ellipsoid level switches: the mean diameter (weighted by area) of a level over
// ellipsoidPixels, strictly increasing; level 0 starts at 0.
std::vector<float> ellipsoidLevelErrors(const std::vector<EllipsoidLevel>& levels,
                                        const PlantLodOptions& options) {
    std::vector<float> levelError(levels.size(), 0.0f);
    for (std::size_t k = 1; k < levels.size(); ++k) {
        double weighted = 0.0, weight = 0.0;
        for (const LodEllipsoid& e : levels[k].ellipsoids) {
            weighted += static_cast<double>(e.weight) * (e.radii.x + e.radii.y);
            weight += e.weight;
        }
        const float size =
            weight > 0.0 ? static_cast<float>(weighted / weight) / options.ellipsoidPixels : 0.0f;
        levelError[k] = std::max(size, std::nextafter(levelError[k - 1], kInfinity));
    }
    return levelError;
}

// Line intervals as a sequential point tree: a node's error is the largest width in its
// merge subtree divided by linePixels; original lines start at 0.
void addLines(const LineHierarchyResult& lineHierarchy, const PlantLodOptions& options,
              PlantLod& lod) {
    const std::vector<LineNode>& nodes = lineHierarchy.nodes;
    std::vector<float> nodeError(nodes.size(), 0.0f);
    std::vector<int> mergedInto(nodes.size(), -1);
    for (const LineMergeRecord& merge : lineHierarchy.merges) {
        mergedInto[merge.first] = merge.result;
        mergedInto[merge.second] = merge.result;
    }
    const float widthScale = lineHierarchy.widthScale;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const LodLine& l = nodes[i].line;
        nodeError[i] =
            2.0f * std::max(l.startRadius, l.endRadius) * widthScale / options.linePixels;
    }
    for (const LineMergeRecord& merge : lineHierarchy.merges) {  // in creation order
        nodeError[merge.result] =
            std::max({nodeError[merge.result], nodeError[merge.first], nodeError[merge.second]});
    }
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        LodLine l = nodes[i].line;
        l.startRadius *= widthScale;
        l.endRadius *= widthScale;
        l.errorMinimum = nodes[i].birthStep == 0 ? 0.0f : nodeError[i];
        l.errorMaximum = mergedInto[i] >= 0 ? nodeError[mergedInto[i]] : kInfinity;
        if (l.errorMinimum < l.errorMaximum) {
            lod.lines.push_back(l);
        }
    }
}

// The discrete levels with the lines drawn at their error and their measured image
// error against the full mesh; a plant of branches only gets one level.
void addLevels(const std::vector<EllipsoidLevel>& levels, const std::vector<float>& levelError,
               const PrimitiveRasterizer& rasterizer,
               const std::vector<std::vector<float>>& fullReference, WorkerPool& pool,
               PlantLod& lod) {
    for (std::size_t k = 0; k < levels.size(); ++k) {
        PlantLodLevel level;
        level.errorMinimum = levelError[k];
        level.errorMaximum = k + 1 < levels.size() ? levelError[k + 1] : kInfinity;
        level.ellipsoidCount = static_cast<std::uint32_t>(levels[k].ellipsoids.size());
        level.alphaThreshold = levels[k].alphaThreshold;
        level.primitiveScale = levels[k].primitiveScale;
        const std::vector<LodLine> lines = linesAt(lod, level.errorMinimum);
        level.lineCount = static_cast<std::uint32_t>(lines.size());
        level.imageError = static_cast<float>(
            imageError(rasterizer, levels[k].ellipsoids, lines, 1.0f, fullReference, pool));
        lod.levels.push_back(level);
    }
    if (levels.empty()) {  // branches only: one level per distinct line error would do; keep one
        PlantLodLevel level;
        const std::vector<LodLine> lines = linesAt(lod, 0.0f);
        level.lineCount = static_cast<std::uint32_t>(lines.size());
        level.imageError =
            static_cast<float>(imageError(rasterizer, {}, lines, 1.0f, fullReference, pool));
        lod.levels.push_back(level);
    }
}

}  // namespace

Result<PlantLod> buildPlantLod(const PlantModel& model, const PlantLodOptions& options,
                               const PlantLodProgressCallback& progress) {
    if (Status valid = checkInput(model, options, "plant '" + model.name + "'"); !valid) {
        return valid.error();
    }
    const Bounds bounds = modelBounds(model);
    BuildPool buildPool(options.threads);
    WorkerPool& pool = buildPool.get();
    std::mutex progressMutex;
    const PlantLodProgressCallback report = [&](const PlantLodProgress& p) {
        if (progress) {
            std::lock_guard lock(progressMutex);
            progress(p);
        }
    };
    const auto stage = [&](const char* name, double fraction) {
        PlantLodProgress p;
        p.stage = name;
        p.fraction = fraction;
        report(p);
    };

    stage("import", 0.0);
    const PrimitiveRasterizer rasterizer(bounds.minimum, bounds.maximum, options.resolution,
                                         options.views, options.supersampling);
    const auto leafReference = renderReference(rasterizer, model, PlantPart::Leaf, false, pool);
    const auto branchReference = renderReference(rasterizer, model, PlantPart::Branch, false, pool);
    const auto fullReference = renderReference(rasterizer, model, PlantPart::Leaf, true, pool);
    const std::vector<LodEllipsoid> leaves = importLeafEllipsoids(model, options.seed);

    EllipsoidHierarchyOptions hierarchyOptions;
    hierarchyOptions.restarts = std::max(options.restarts, 1);
    hierarchyOptions.pool = &pool;
    hierarchyOptions.seed = options.seed;
    std::vector<EllipsoidLevel> levels = buildEllipsoidHierarchy(
        leaves, rasterizer, leafReference, hierarchyOptions, report, 0.02, 0.7);

    // Lines: calibrate the width scale against the branch mesh (§3.3.3), then merge.
    const glm::vec3 barkColor = branchColor(model);
    LineHierarchyOptions lineOptions = options.lines;
    lineOptions.seed = options.seed;
    lineOptions.widthScale = 1.0f;
    lineOptions.pool = &pool;
    if (!model.skeleton.empty() && model.triangleCount(PlantPart::Branch) > 0) {
        stage("line calibration", 0.7);
        lineOptions.widthScale =
            calibrateLineWidth(model, barkColor, rasterizer, branchReference, pool);
    }
    LineHierarchyResult lineHierarchy;
    if (!model.skeleton.empty()) {
        // The merge order is chosen on images without supersampling: a quarter of the
        // pixels, and lines thinner than a pixel are still drawn by coverage, so the
        // ranking of merges hardly changes; the level errors below use the full images.
        const PrimitiveRasterizer mergeRasterizer(bounds.minimum, bounds.maximum,
                                                  options.resolution, options.views, 1);
        lineHierarchy = buildLineHierarchy(model.skeleton, barkColor, mergeRasterizer, lineOptions,
                                           report, 0.72, 0.85);
    }

    stage("levels", 0.85);
    PlantLod lod;
    lod.name = model.name;
    lod.boundsMinimum = bounds.minimum;
    lod.boundsMaximum = bounds.maximum;
    const std::vector<float> levelError = ellipsoidLevelErrors(levels, options);
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const float high = k + 1 < levels.size() ? levelError[k + 1] : kInfinity;
        for (LodEllipsoid e : levels[k].ellipsoids) {
            e.errorMinimum = levelError[k];
            e.errorMaximum = high;
            lod.ellipsoids.push_back(e);
        }
    }
    addLines(lineHierarchy, options, lod);
    // Coarse → fine: errorMaximum descending (stable keeps level/creation order).
    std::stable_sort(lod.ellipsoids.begin(), lod.ellipsoids.end(),
                     [](const LodEllipsoid& a, const LodEllipsoid& b) {
                         return a.errorMaximum > b.errorMaximum;
                     });
    std::stable_sort(lod.lines.begin(), lod.lines.end(), [](const LodLine& a, const LodLine& b) {
        return a.errorMaximum > b.errorMaximum;
    });

    stage("level errors", 0.86);
    addLevels(levels, levelError, rasterizer, fullReference, pool, lod);
    if (options.ambientOcclusionSamples > 0) {
        stage("ambient occlusion", 0.9);
        AmbientOcclusionOptions ao;
        ao.samples = options.ambientOcclusionSamples;
        ao.seed = options.seed;
        ao.pool = &pool;
        computeAmbientOcclusion(model, lod, ao);
    }

    stage("done", 1.0);
    return lod;
}

double plantLodImageError(const PlantModel& model, const PlantLod& lod, float error,
                          const PlantLodOptions& options) {
    const Bounds bounds = modelBounds(model);
    const PrimitiveRasterizer rasterizer(bounds.minimum, bounds.maximum, options.resolution,
                                         options.views, options.supersampling);
    BuildPool buildPool(options.threads);
    WorkerPool& pool = buildPool.get();
    const auto reference = renderReference(rasterizer, model, PlantPart::Leaf, true, pool);
    return imageError(rasterizer, ellipsoidsAt(lod, error), linesAt(lod, error), 1.0f, reference,
                      pool);
}

double plantMeshImageError(const PlantModel& source, const PlantModel& candidate,
                           const PlantLodOptions& options) {
    const Bounds bounds = modelBounds(source);
    const PrimitiveRasterizer rasterizer(bounds.minimum, bounds.maximum, options.resolution,
                                         options.views, options.supersampling);
    BuildPool buildPool(options.threads);
    WorkerPool& pool = buildPool.get();
    const auto reference = renderReference(rasterizer, source, PlantPart::Leaf, true, pool);
    const auto drawn = renderReference(rasterizer, candidate, PlantPart::Leaf, true, pool);
    std::vector<std::vector<double>> perView;
    for (int view = 0; view < rasterizer.viewCount(); ++view) {
        perView.push_back(
            multiScaleSquaredErrors(drawn[view], reference[view], rasterizer.resolution()));
    }
    return multiScaleRmse(meanOverViews(perView));
}

Status addBillboardClouds(const PlantModel& model, PlantLod& lod, const PlantLodOptions& options,
                          const BillboardCloudOptions& billboardOptions) {
    Result<BillboardCloud> cloud = BillboardCloudBuilder::build(model, billboardOptions);
    if (!cloud) {
        return Error{"plant '" + model.name + "': billboard clouds: " + cloud.error().message};
    }
    for (BillboardLevel& level : cloud->levels) {
        const PlantModel levelModel = BillboardCloudBuilder::levelModel(level, model.name);
        level.imageError = static_cast<float>(plantMeshImageError(model, levelModel, options));
    }
    lod.billboards = std::move(cloud.value());
    return Status::success();
}

}  // namespace sylva
