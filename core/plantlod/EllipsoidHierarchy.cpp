#include "sylva/core/plantlod/EllipsoidHierarchy.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <random>
#include <tuple>

#include "sylva/core/plantlod/EllipsoidFit.h"
#include "sylva/core/plantlod/ImageErrorMetric.h"
#include "sylva/core/plantlod/PlantThreads.h"

namespace sylva {

namespace {

float srgbToLinear(std::uint8_t value) {
    const float c = value / 255.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

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

std::vector<LodEllipsoid> importLeafEllipsoids(const PlantModel& model, std::uint32_t seed,
                                               int samplesPerLeaf) {
    std::vector<LodEllipsoid> leaves;
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const PlantMesh& mesh : model.meshes) {
        if (mesh.part != PlantPart::Leaf || mesh.positions.empty()) {
            continue;
        }
        const PlantMaterial* material =
            mesh.material >= 0 && mesh.material < static_cast<int>(model.materials.size())
                ? &model.materials[mesh.material]
                : nullptr;
        const PlantTexture* texture =
            material && material->baseColorTexture.width > 0 &&
                    material->baseColorTexture.rgba.size() ==
                        static_cast<std::size_t>(material->baseColorTexture.width) *
                            material->baseColorTexture.height * 4 &&
                    mesh.uvs.size() == mesh.positions.size()
                ? &material->baseColorTexture
                : nullptr;
        const glm::vec4 base = material ? material->baseColor : glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
        const float cutoff = material && material->alphaMasked ? material->alphaCutoff : 0.5f;
        // Leaves = connected triangles; vertices at equal positions count as shared.
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
        std::map<int, std::vector<std::size_t>> leafTriangles;  // ordered: deterministic
        for (std::size_t t = 0; t < triangleCount; ++t) {
            const std::uint32_t* tri = &mesh.indices[3 * t];
            if (tri[0] < static_cast<std::uint32_t>(vertexCount)) {
                leafTriangles[findRoot(parent, tri[0])].push_back(t);
            }
        }
        for (const auto& [root, triangles] : leafTriangles) {
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
                continue;
            }
            WeightedMoments moments;
            glm::dvec3 colour(0.0);
            int kept = 0;
            for (int s = 0; s < samplesPerLeaf; ++s) {
                // Stratified over the leaf area, then uniform inside the triangle.
                const double pick = (s + unit(random)) / samplesPerLeaf * area;
                const std::size_t index = std::min<std::size_t>(
                    std::lower_bound(cumulative.begin(), cumulative.end(), pick) -
                        cumulative.begin(),
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
                glm::dvec3 sampleColour(base);
                double alpha = base.a;
                if (texture) {
                    const glm::dvec2 uv = w * glm::dvec2(mesh.uvs[tri[0]]) +
                                          u * glm::dvec2(mesh.uvs[tri[1]]) +
                                          v * glm::dvec2(mesh.uvs[tri[2]]);
                    const int tx =
                        std::min(texture->width - 1,
                                 static_cast<int>((uv.x - std::floor(uv.x)) * texture->width));
                    const int ty =
                        std::min(texture->height - 1,
                                 static_cast<int>((uv.y - std::floor(uv.y)) * texture->height));
                    const std::uint8_t* texel =
                        &texture->rgba[(static_cast<std::size_t>(ty) * texture->width + tx) * 4];
                    sampleColour *= glm::dvec3(srgbToLinear(texel[0]), srgbToLinear(texel[1]),
                                               srgbToLinear(texel[2]));
                    alpha *= texel[3] / 255.0;
                }
                if (alpha < cutoff) {
                    continue;
                }
                moments.addPoint(point, 1.0);
                colour += sampleColour;
                ++kept;
            }
            if (kept < 3) {
                continue;  // (almost) fully transparent: nothing to draw
            }
            LodEllipsoid leaf = toEllipsoid(principalAxes(moments));
            leaf.color = glm::vec3(colour / static_cast<double>(kept));
            leaf.weight = static_cast<float>(area * kept / samplesPerLeaf);
            leaf.noiseLevel = 0.5f;  // l = 0.5 (1 + log2 1)
            leaves.push_back(leaf);
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
                           const EllipsoidStyle& style, int threads) {
    const int views = rasterizer.viewCount();
    std::vector<std::vector<double>> perView(views);
    runOnThreads(views, threads, [&](int view) {
        thread_local RasterFrame frame;
        rasterizer.clearFrame(frame);
        rasterizer.drawEllipsoids(ellipsoids, view, frame, style);
        perView[view] = multiScaleSquaredErrors(rasterizer.resolve(frame), reference[view],
                                                rasterizer.resolution());
    });
    std::vector<double> mean(perView[0].size(), 0.0);
    for (const auto& levels : perView) {
        for (std::size_t k = 0; k < levels.size(); ++k) {
            mean[k] += levels[k] / views;
        }
    }
    return multiScaleRmse(mean);
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

}  // namespace

std::vector<EllipsoidLevel> buildEllipsoidHierarchy(
    std::span<const LodEllipsoid> leaves, const PrimitiveRasterizer& rasterizer,
    const std::vector<std::vector<float>>& reference, const EllipsoidHierarchyOptions& options,
    const PlantLodProgressCallback& progress, double progressStart, double progressEnd) {
    std::vector<EllipsoidLevel> levels;
    if (leaves.empty()) {
        return levels;
    }
    std::vector<int> targets;
    for (int k = static_cast<int>(leaves.size()) / 4;; k /= 4) {
        targets.push_back(std::max(k, 1));
        if (targets.back() == 1) {
            break;
        }
    }
    const int levelCount = static_cast<int>(targets.size()) + 1;
    std::mutex progressMutex;
    const auto report = [&](int level, int restart) {
        if (!progress) {
            return;
        }
        std::lock_guard lock(progressMutex);
        PlantLodProgress p;
        p.stage = "ellipsoids";
        p.level = level;
        p.levelCount = levelCount;
        p.restart = restart;
        p.restartCount = options.restarts;
        const double done =
            (level + static_cast<double>(restart) / std::max(options.restarts, 1)) / levelCount;
        p.fraction = progressStart + (progressEnd - progressStart) * std::min(done, 1.0);
        progress(p);
    };
    const int threads = resolveThreadCount(options.threads);

    // Level 0: the imported leaves, scale calibrated (§3.3.3).
    report(0, 0);
    {
        EllipsoidLevel level;
        level.ellipsoids.assign(leaves.begin(), leaves.end());
        const auto [scale, error] = calibrateScale(
            [&](float s) {
                return ellipsoidImageError(rasterizer, leaves, reference, {s, 0.0f}, threads);
            },
            0.5f, 6.0f, 12);
        level.primitiveScale = scale;
        level.imageError = error;
        bake(level.ellipsoids, scale, 0.0f, 0);
        levels.push_back(std::move(level));
    }

    std::vector<glm::dvec3> centers(leaves.size());
    std::vector<double> weights(leaves.size());
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        centers[i] = glm::dvec3(leaves[i].center);
        weights[i] = std::max(static_cast<double>(leaves[i].weight), 1e-12);
    }
    for (std::size_t li = 0; li < targets.size(); ++li) {
        const int levelIndex = static_cast<int>(li) + 1;
        const int k = targets[li];
        const float previousScale = levels.back().primitiveScale;
        const float previousThreshold = levels.back().alphaThreshold;
        struct Run {
            std::vector<LodEllipsoid> ellipsoids;
            double error = 0.0;
        };
        std::vector<Run> runs(options.restarts);
        int finished = 0;
        report(levelIndex, 0);
        runOnThreads(options.restarts, threads, [&](int restart) {
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
            run.error = ellipsoidImageError(rasterizer, run.ellipsoids, reference,
                                            {previousScale, previousThreshold}, 1);
            runs[restart] = std::move(run);
            std::lock_guard lock(progressMutex);
            ++finished;
            if (progress) {
                PlantLodProgress p;
                p.stage = "ellipsoids";
                p.level = levelIndex;
                p.levelCount = levelCount;
                p.restart = finished;
                p.restartCount = options.restarts;
                p.fraction = progressStart + (progressEnd - progressStart) *
                                                 (levelIndex + 0.8 * finished / options.restarts) /
                                                 levelCount;
                progress(p);
            }
        });
        // Lowest error wins; ties go to the lower restart index (thread-count independent).
        std::size_t best = 0;
        for (std::size_t r = 1; r < runs.size(); ++r) {
            if (runs[r].error < runs[best].error) {
                best = r;
            }
        }
        EllipsoidLevel level;
        level.ellipsoids = std::move(runs[best].ellipsoids);
        level.clusterTarget = k;
        // Calibrate the shared alpha threshold and the scale that compensates the area it
        // removes (§3.4.1).
        level.imageError = std::numeric_limits<double>::infinity();
        const auto tryThreshold = [&](float threshold) {
            const auto [scale, error] = calibrateScale(
                [&](float s) {
                    return ellipsoidImageError(rasterizer, level.ellipsoids, reference,
                                               {s, threshold}, threads);
                },
                0.5f * previousScale, 3.0f * previousScale, 5);
            if (error < level.imageError) {
                level.imageError = error;
                level.primitiveScale = scale;
                level.alphaThreshold = threshold;
            }
        };
        // A coarse grid of thresholds (up to 0.9: sparse crowns are mostly holes at
        // coarse levels), then the neighbours of the best one.
        for (float threshold : {0.0f, 0.5f, 0.75f, 0.9f}) {
            tryThreshold(threshold);
        }
        const float bestThreshold = level.alphaThreshold;
        for (float threshold : {bestThreshold - 0.1f, bestThreshold + 0.05f}) {
            if (threshold > 0.0f && threshold < 0.97f) {
                tryThreshold(threshold);
            }
        }
        bake(level.ellipsoids, level.primitiveScale, level.alphaThreshold,
             static_cast<std::uint32_t>(levelIndex));
        levels.push_back(std::move(level));
    }
    report(levelCount, 0);
    return levels;
}

}  // namespace sylva
