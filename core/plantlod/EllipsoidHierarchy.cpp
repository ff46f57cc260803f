#include "sylva/core/plantlod/EllipsoidHierarchy.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <random>
#include <tuple>

#include "TexelColour.h"
#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/plantlod/EllipsoidFit.h"
#include "sylva/core/plantlod/ImageErrorMetric.h"

namespace sylva {

namespace {

int findRoot(std::vector<int>& parent, int i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

LodEllipsoid toEllipsoid(const PrincipalAxes& axes) {
    LodEllipsoid e;
    e.center = glm::vec3(axes.center);
    for (int i = 0; i < 3; ++i) {
        e.axes[i] = glm::vec3(glm::normalize(axes.axes[i]));
        e.radii[i] = static_cast<float>(axes.radii[i]);
    }
    return e;
}

// Minimises error(scale) over log(scale) in [lo, hi] by golden-section search; returns
// (scale, error). The error of calibration is unimodal in practice: too small leaves
// holes, too large covers background.
template <typename Evaluate>
std::pair<float, double> calibrateScale(Evaluate evaluate, float lo, float hi, int iterations) {
    const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
    double a = std::log(lo), b = std::log(hi);
    double c = b - phi * (b - a), d = a + phi * (b - a);
    double fc = evaluate(static_cast<float>(std::exp(c)));
    double fd = evaluate(static_cast<float>(std::exp(d)));
    for (int i = 0; i < iterations; ++i) {
        if (fc <= fd) {
            b = d;
            d = c;
            fd = fc;
            c = b - phi * (b - a);
            fc = evaluate(static_cast<float>(std::exp(c)));
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + phi * (b - a);
            fd = evaluate(static_cast<float>(std::exp(d)));
        }
    }
    return fc <= fd ? std::pair{static_cast<float>(std::exp(c)), fc}
                    : std::pair{static_cast<float>(std::exp(d)), fd};
}

}  // namespace

namespace {

// How a leaf mesh looks: its material's colour, its texture when it has a usable one
// (RGBA8 of the stated size, one uv per vertex) and the alpha cutoff.
struct LeafSurface {
    const PlantTexture* texture = nullptr;
    glm::vec4 base{0.5f, 0.5f, 0.5f, 1.0f};
    float cutoff = 0.5f;
};

LeafSurface leafSurface(const PlantModel& model, const PlantMesh& mesh) {
    const PlantMaterial* material =
        mesh.material >= 0 && mesh.material < static_cast<int>(model.materials.size())
            ? &model.materials[mesh.material]
            : nullptr;
    LeafSurface surface;
    surface.texture = material && material->baseColorTexture.width > 0 &&
                              material->baseColorTexture.rgba.size() ==
                                  static_cast<std::size_t>(material->baseColorTexture.width) *
                                      material->baseColorTexture.height * 4 &&
                              mesh.uvs.size() == mesh.positions.size()
                          ? &material->baseColorTexture
                          : nullptr;
    surface.base = material ? material->baseColor : glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    surface.cutoff = material && material->alphaMasked ? material->alphaCutoff : 0.5f;
    return surface;
}

// Leaves = connected triangles (vertices at equal positions count as shared): the
// triangles of each leaf, ordered by root vertex so the result is deterministic.
std::map<int, std::vector<std::size_t>> leafTriangles(const PlantMesh& mesh) {
    const int vertexCount = static_cast<int>(mesh.positions.size());
    std::vector<int> parent(vertexCount);
    std::iota(parent.begin(), parent.end(), 0);
    std::map<std::tuple<float, float, float>, int> welded;
    for (int v = 0; v < vertexCount; ++v) {
        const glm::vec3& p = mesh.positions[v];
        auto [it, inserted] = welded.emplace(std::tuple{p.x, p.y, p.z}, v);
        if (!inserted) {
            parent[findRoot(parent, v)] = findRoot(parent, it->second);
        }
    }
    const std::size_t triangleCount = mesh.indices.size() / 3;
    for (std::size_t t = 0; t < triangleCount; ++t) {
        const std::uint32_t* tri = &mesh.indices[3 * t];
        if (tri[0] >= static_cast<std::uint32_t>(vertexCount) ||
            tri[1] >= static_cast<std::uint32_t>(vertexCount) ||
            tri[2] >= static_cast<std::uint32_t>(vertexCount)) {
            continue;
        }
        parent[findRoot(parent, tri[1])] = findRoot(parent, tri[0]);
        parent[findRoot(parent, tri[2])] = findRoot(parent, tri[0]);
    }
    std::map<int, std::vector<std::size_t>> leaves;
    for (std::size_t t = 0; t < triangleCount; ++t) {
        const std::uint32_t* tri = &mesh.indices[3 * t];
        if (tri[0] < static_cast<std::uint32_t>(vertexCount)) {
            leaves[findRoot(parent, tri[0])].push_back(t);
        }
    }
    return leaves;
}

// Colour and alpha of the leaf surface at barycentric (w, u, v) of a triangle.
glm::dvec3 surfaceColour(const PlantMesh& mesh, const LeafSurface& surface,
                         const std::uint32_t* tri, double w, double u, double v, double& alpha) {
    glm::dvec3 colour(surface.base);
    alpha = surface.base.a;
    const PlantTexture* texture = surface.texture;
    if (texture) {
        const glm::dvec2 uv = w * glm::dvec2(mesh.uvs[tri[0]]) + u * glm::dvec2(mesh.uvs[tri[1]]) +
                              v * glm::dvec2(mesh.uvs[tri[2]]);
        const int tx = std::min(texture->width - 1,
                                static_cast<int>((uv.x - std::floor(uv.x)) * texture->width));
        const int ty = std::min(texture->height - 1,
                                static_cast<int>((uv.y - std::floor(uv.y)) * texture->height));
        const std::uint8_t* texel =
            &texture->rgba[(static_cast<std::size_t>(ty) * texture->width + tx) * 4];
        colour *=
            glm::dvec3(texelToLinear(texel[0]), texelToLinear(texel[1]), texelToLinear(texel[2]));
        alpha *= texel[3] / 255.0;
    }
    return colour;
}

// One leaf's ellipsoid from `samplesPerLeaf` area-stratified samples that pass the
// alpha cutoff; nothing for a leaf without area or with fewer than three opaque samples.
std::optional<LodEllipsoid> fitLeaf(const PlantMesh& mesh,
                                    const std::vector<std::size_t>& triangles,
                                    const LeafSurface& surface, int samplesPerLeaf,
                                    std::mt19937_64& random,
                                    std::uniform_real_distribution<double>& unit) {
    std::vector<double> cumulative;
    double area = 0.0;
    for (std::size_t t : triangles) {
        const std::uint32_t* tri = &mesh.indices[3 * t];
        const glm::dvec3 a(mesh.positions[tri[0]]), b(mesh.positions[tri[1]]),
            c(mesh.positions[tri[2]]);
        area += 0.5 * glm::length(glm::cross(b - a, c - a));
        cumulative.push_back(area);
    }
    if (!(area > 0.0)) {
        return std::nullopt;
    }
    WeightedMoments moments;
    glm::dvec3 colour(0.0);
    int kept = 0;
    for (int s = 0; s < samplesPerLeaf; ++s) {
        // Stratified over the leaf area, then uniform inside the triangle.
        const double pick = (s + unit(random)) / samplesPerLeaf * area;
        const std::size_t index = std::min<std::size_t>(
            std::lower_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin(),
            triangles.size() - 1);
        const std::uint32_t* tri = &mesh.indices[3 * triangles[index]];
        double u = unit(random), v = unit(random);
        if (u + v > 1.0) {
            u = 1.0 - u;
            v = 1.0 - v;
        }
        const double w = 1.0 - u - v;
        const glm::dvec3 point = w * glm::dvec3(mesh.positions[tri[0]]) +
                                 u * glm::dvec3(mesh.positions[tri[1]]) +
                                 v * glm::dvec3(mesh.positions[tri[2]]);
        double alpha = 1.0;
        const glm::dvec3 sampleColour = surfaceColour(mesh, surface, tri, w, u, v, alpha);
        if (alpha < surface.cutoff) {
            continue;
        }
        moments.addPoint(point, 1.0);
        colour += sampleColour;
        ++kept;
    }
    if (kept < 3) {
        return std::nullopt;  // (almost) fully transparent: nothing to draw
    }
    LodEllipsoid leaf = toEllipsoid(principalAxes(moments));
    leaf.color = glm::vec3(colour / static_cast<double>(kept));
    leaf.weight = static_cast<float>(area * kept / samplesPerLeaf);
    leaf.noiseLevel = 0.5f;  // l = 0.5 (1 + log2 1)
    return leaf;
}

}  // namespace

std::vector<LodEllipsoid> importLeafEllipsoids(const PlantModel& model, std::uint32_t seed,
                                               int samplesPerLeaf) {
    std::vector<LodEllipsoid> leaves;
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const PlantMesh& mesh : model.meshes) {
        if (mesh.part != PlantPart::Leaf || mesh.positions.empty()) {
            continue;
        }
        const LeafSurface surface = leafSurface(model, mesh);
        for (const auto& [root, triangles] : leafTriangles(mesh)) {
            if (std::optional<LodEllipsoid> leaf =
                    fitLeaf(mesh, triangles, surface, samplesPerLeaf, random, unit)) {
                leaves.push_back(*leaf);
            }
        }
    }
    return leaves;
}

std::vector<LodEllipsoid> ellipsoidsFromAssignments(std::span<const LodEllipsoid> leaves,
                                                    const GaussianMixtureFit& fit,
                                                    bool hardAssignment) {
    const std::size_t k = fit.components.size();
    std::vector<WeightedMoments> moments(k);
    std::vector<double> membership(k, 0.0);
    std::vector<glm::dvec3> colour(k, glm::dvec3(0.0));
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        const LodEllipsoid& leaf = leaves[i];
        const glm::dmat3 covariance = ellipsoidCovariance(leaf.axes, leaf.radii);
        std::uint32_t begin = fit.offsets[i], end = fit.offsets[i + 1];
        if (hardAssignment && begin < end) {
            std::uint32_t best = begin;
            for (std::uint32_t e = begin; e < end; ++e) {
                if (fit.responsibility[e] > fit.responsibility[best]) {
                    best = e;
                }
            }
            begin = best;
            end = best + 1;
        }
        for (std::uint32_t e = begin; e < end; ++e) {
            const int j = fit.cluster[e];
            const double r = hardAssignment ? 1.0 : fit.responsibility[e];
            const double w = r * leaf.weight;
            moments[j].addDistribution(glm::dvec3(leaf.center), covariance, w);
            membership[j] += r;
            colour[j] += w * glm::dvec3(leaf.color);
        }
    }
    std::vector<LodEllipsoid> result;
    for (std::size_t j = 0; j < k; ++j) {
        if (!(moments[j].weight() > 0.0)) {
            continue;
        }
        LodEllipsoid e = toEllipsoid(principalAxes(moments[j]));
        e.color = glm::vec3(colour[j] / moments[j].weight());
        e.weight = static_cast<float>(moments[j].weight());
        e.noiseLevel = static_cast<float>(0.5 * (1.0 + std::log2(std::max(membership[j], 1e-6))));
        result.push_back(e);
    }
    return result;
}

double ellipsoidImageError(const PrimitiveRasterizer& rasterizer,
                           std::span<const LodEllipsoid> ellipsoids,
                           const std::vector<std::vector<float>>& reference,
                           const EllipsoidStyle& style, WorkerPool& pool) {
    const int views = rasterizer.viewCount();
    std::vector<std::vector<double>> perView(views);
    pool.run(views, [&](int view) {
        thread_local RasterFrame frame;
        rasterizer.clearFrame(frame);
        rasterizer.drawEllipsoids(ellipsoids, view, frame, style);
        perView[view] = multiScaleSquaredErrors(rasterizer.resolve(frame), reference[view],
                                                rasterizer.resolution());
    });
    return multiScaleRmse(meanOverViews(perView));
}

namespace {

void discardSmall(std::vector<LodEllipsoid>& ellipsoids, double fraction) {
    double largest = 0.0;
    for (const LodEllipsoid& e : ellipsoids) {
        largest = std::max(largest, ellipsoidSurfaceArea(glm::dvec3(e.radii)));
    }
    std::erase_if(ellipsoids, [&](const LodEllipsoid& e) {
        return ellipsoidSurfaceArea(glm::dvec3(e.radii)) < fraction * largest;
    });
}

void bake(std::vector<LodEllipsoid>& ellipsoids, float scale, float threshold,
          std::uint32_t level) {
    for (LodEllipsoid& e : ellipsoids) {
        e.radii *= scale;
        // Flat leaves have a third radius near 0; the stored radii carry the same floor
        // the rasterizer applies, so a shader needs no rule of its own.
        e.radii = glm::max(e.radii, glm::vec3(1e-3f * std::max({e.radii.x, e.radii.y, e.radii.z})));
        e.alphaThreshold = threshold;
        e.level = level;
    }
}

// Cluster counts of the coarser levels: a quarter of the finer level's each, down to 1.
std::vector<int> levelTargets(std::size_t leafCount) {
    std::vector<int> targets;
    for (int k = static_cast<int>(leafCount) / 4;; k /= 4) {
        targets.push_back(std::max(k, 1));
        if (targets.back() == 1) {
            return targets;
        }
    }
}

// Progress of the "ellipsoids" stage: level by level, restart by restart.
class HierarchyProgress {
public:
    HierarchyProgress(const PlantLodProgressCallback& progress, int levelCount, int restarts,
                      double start, double end)
        : progress_(progress),
          levelCount_(levelCount),
          restarts_(restarts),
          start_(start),
          end_(end) {}

    void level(int level) {
        if (!progress_) {
            return;
        }
        std::lock_guard lock(mutex_);
        const double done = static_cast<double>(level) / levelCount_;
        emit(level, 0, start_ + (end_ - start_) * std::min(done, 1.0));
    }

    // One more restart of `level` finished (restarts run on several threads).
    void restartFinished(int level) {
        std::lock_guard lock(mutex_);
        ++finished_;
        if (progress_) {
            emit(level, finished_,
                 start_ + (end_ - start_) * (level + 0.8 * finished_ / restarts_) / levelCount_);
        }
    }
    void startLevel() { finished_ = 0; }

private:
    void emit(int level, int restart, double fraction) {
        PlantLodProgress p;
        p.stage = "ellipsoids";
        p.level = level;
        p.levelCount = levelCount_;
        p.restart = restart;
        p.restartCount = restarts_;
        p.fraction = fraction;
        progress_(p);
    }

    const PlantLodProgressCallback& progress_;
    int levelCount_, restarts_;
    double start_, end_;
    std::mutex mutex_;
    int finished_ = 0;
};

// Level 0: the imported leaves, scale calibrated (§3.3.3).
EllipsoidLevel leafLevel(std::span<const LodEllipsoid> leaves,
                         const PrimitiveRasterizer& rasterizer,
                         const std::vector<std::vector<float>>& reference, WorkerPool& pool) {
    EllipsoidLevel level;
    level.ellipsoids.assign(leaves.begin(), leaves.end());
    const auto [scale, error] = calibrateScale(
        [&](float s) {
            return ellipsoidImageError(rasterizer, leaves, reference, {s, 0.0f}, pool);
        },
        0.5f, 6.0f, 12);
    level.primitiveScale = scale;
    level.imageError = error;
    bake(level.ellipsoids, scale, 0.0f, 0);
    return level;
}

// The best of `restarts` mixture fits with k clusters (§3.4.1: random initial means),
// each measured with the finer level's style. Lowest error wins; ties go to the lower
// restart index (thread-count independent).
std::vector<LodEllipsoid> bestClustering(std::span<const LodEllipsoid> leaves, int k,
                                         int levelIndex, const EllipsoidStyle& style,
                                         const PrimitiveRasterizer& rasterizer,
                                         const std::vector<std::vector<float>>& reference,
                                         const EllipsoidHierarchyOptions& options, WorkerPool& pool,
                                         HierarchyProgress& progress) {
    std::vector<glm::dvec3> centers(leaves.size());
    std::vector<double> weights(leaves.size());
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        centers[i] = glm::dvec3(leaves[i].center);
        weights[i] = std::max(static_cast<double>(leaves[i].weight), 1e-12);
    }
    struct Run {
        std::vector<LodEllipsoid> ellipsoids;
        double error = 0.0;
    };
    std::vector<Run> runs(options.restarts);
    pool.run(options.restarts, [&](int restart) {
        std::mt19937_64 random(options.seed * 0x9E3779B97F4A7C15ull + levelIndex * 1000003ull +
                               restart);
        std::vector<int> order(leaves.size());
        std::iota(order.begin(), order.end(), 0);
        std::vector<glm::dvec3> initial(k);
        for (int j = 0; j < k; ++j) {  // partial Fisher–Yates: k distinct leaves
            const std::size_t pick = j + random() % (order.size() - j);
            std::swap(order[j], order[pick]);
            initial[j] = centers[order[j]];
        }
        const GaussianMixtureFit fit =
            fitGaussianMixture(centers, weights, initial, options.mixture);
        Run run;
        run.ellipsoids = ellipsoidsFromAssignments(leaves, fit);
        discardSmall(run.ellipsoids, options.discardAreaFraction);
        run.error = ellipsoidImageError(rasterizer, run.ellipsoids, reference, style, pool);
        runs[restart] = std::move(run);
        progress.restartFinished(levelIndex);
    });
    std::size_t best = 0;
    for (std::size_t r = 1; r < runs.size(); ++r) {
        if (runs[r].error < runs[best].error) {
            best = r;
        }
    }
    return std::move(runs[best].ellipsoids);
}

// The shared alpha threshold and the scale that compensates the area it removes
// (§3.4.1): a coarse grid of thresholds (up to 0.9: sparse crowns are mostly holes at
// coarse levels), then the neighbours of the best one.
void calibrateThreshold(EllipsoidLevel& level, float previousScale,
                        const PrimitiveRasterizer& rasterizer,
                        const std::vector<std::vector<float>>& reference, WorkerPool& pool) {
    level.imageError = std::numeric_limits<double>::infinity();
    const auto tryThreshold = [&](float threshold) {
        const auto [scale, error] = calibrateScale(
            [&](float s) {
                return ellipsoidImageError(rasterizer, level.ellipsoids, reference, {s, threshold},
                                           pool);
            },
            0.5f * previousScale, 3.0f * previousScale, 5);
        if (error < level.imageError) {
            level.imageError = error;
            level.primitiveScale = scale;
            level.alphaThreshold = threshold;
        }
    };
    for (float threshold : {0.0f, 0.5f, 0.75f, 0.9f}) {
        tryThreshold(threshold);
    }
    const float bestThreshold = level.alphaThreshold;
    for (float threshold : {bestThreshold - 0.1f, bestThreshold + 0.05f}) {
        if (threshold > 0.0f && threshold < 0.97f) {
            tryThreshold(threshold);
        }
    }
}

}  // namespace

std::vector<EllipsoidLevel> buildEllipsoidHierarchy(
    std::span<const LodEllipsoid> leaves, const PrimitiveRasterizer& rasterizer,
    const std::vector<std::vector<float>>& reference, const EllipsoidHierarchyOptions& options,
    const PlantLodProgressCallback& progress, double progressStart, double progressEnd) {
    std::vector<EllipsoidLevel> levels;
    if (leaves.empty()) {
        return levels;
    }
    const std::vector<int> targets = levelTargets(leaves.size());
    const int levelCount = static_cast<int>(targets.size()) + 1;
    HierarchyProgress report(progress, levelCount, options.restarts, progressStart, progressEnd);
    WorkerPool& pool = options.pool != nullptr ? *options.pool : WorkerPool::shared();

    report.level(0);
    levels.push_back(leafLevel(leaves, rasterizer, reference, pool));
    for (std::size_t li = 0; li < targets.size(); ++li) {
        const int levelIndex = static_cast<int>(li) + 1;
        const EllipsoidStyle previous{levels.back().primitiveScale, levels.back().alphaThreshold};
        report.startLevel();
        report.level(levelIndex);
        EllipsoidLevel level;
        level.ellipsoids = bestClustering(leaves, targets[li], levelIndex, previous, rasterizer,
                                          reference, options, pool, report);
        level.clusterTarget = targets[li];
        calibrateThreshold(level, previous.scale, rasterizer, reference, pool);
        bake(level.ellipsoids, level.primitiveScale, level.alphaThreshold,
             static_cast<std::uint32_t>(levelIndex));
        levels.push_back(std::move(level));
    }
    report.level(levelCount);
    return levels;
}

}  // namespace sylva
