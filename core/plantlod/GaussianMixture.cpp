#include "sylva/core/plantlod/GaussianMixture.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "sylva/core/base/Check.h"

namespace sylva {

namespace {

// A static k-d tree over cluster means for k-nearest queries (implicit: the median of
// every range is its node).
class MeanTree {
public:
    void build(const std::vector<glm::dvec3>& points, std::vector<int> ids) {
        points_ = &points;
        order_ = std::move(ids);
        axis_.assign(order_.size(), 0);
        buildRange(0, static_cast<int>(order_.size()));
    }

    // The k nearest (unsorted) into `out`.
    void nearest(const glm::dvec3& x, int k, std::vector<std::pair<double, int>>& out) const {
        out.clear();
        search(x, k, 0, static_cast<int>(order_.size()), out);
    }

private:
    void buildRange(int lo, int hi) {
        if (hi - lo <= 1) {
            return;
        }
        glm::dvec3 minimum(std::numeric_limits<double>::max()),
            maximum(-std::numeric_limits<double>::max());
        for (int i = lo; i < hi; ++i) {
            minimum = glm::min(minimum, (*points_)[order_[i]]);
            maximum = glm::max(maximum, (*points_)[order_[i]]);
        }
        const glm::dvec3 extent = maximum - minimum;
        const int axis =
            extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const int mid = (lo + hi) / 2;
        std::nth_element(order_.begin() + lo, order_.begin() + mid, order_.begin() + hi,
                         [&](int a, int b) {
                             const double pa = (*points_)[a][axis], pb = (*points_)[b][axis];
                             return pa < pb || (pa == pb && a < b);
                         });
        axis_[mid] = axis;
        buildRange(lo, mid);
        buildRange(mid + 1, hi);
    }

    void search(const glm::dvec3& x, int k, int lo, int hi,
                std::vector<std::pair<double, int>>& heap) const {
        if (lo >= hi) {
            return;
        }
        const int mid = (lo + hi) / 2;
        const int id = order_[mid];
        const glm::dvec3 d = x - (*points_)[id];
        const double distance2 = glm::dot(d, d);
        if (static_cast<int>(heap.size()) < k) {
            heap.emplace_back(distance2, id);
            std::push_heap(heap.begin(), heap.end());
        } else if (distance2 < heap.front().first) {
            std::pop_heap(heap.begin(), heap.end());
            heap.back() = {distance2, id};
            std::push_heap(heap.begin(), heap.end());
        }
        const double delta = d[axis_[mid]];
        const bool left = delta < 0.0;
        search(x, k, left ? lo : mid + 1, left ? mid : hi, heap);
        if (static_cast<int>(heap.size()) < k || delta * delta < heap.front().first) {
            search(x, k, left ? mid + 1 : lo, left ? hi : mid, heap);
        }
    }

    const std::vector<glm::dvec3>* points_ = nullptr;
    std::vector<int> order_;
    std::vector<int> axis_;
};

struct Density {
    glm::dmat3 inverse{1.0};
    double logNormalizer = 0.0;  // log π − ½ log det Σ − 3/2 log 2π
};

}  // namespace

GaussianMixtureFit fitGaussianMixture(std::span<const glm::dvec3> points,
                                      std::span<const double> weights,
                                      std::span<const glm::dvec3> initialMeans,
                                      const GaussianMixtureOptions& options) {
    SYLVA_CHECK(points.size() == weights.size());
    SYLVA_CHECK(!initialMeans.empty());
    const int n = static_cast<int>(points.size());
    const int k = static_cast<int>(initialMeans.size());
    GaussianMixtureFit fit;
    fit.components.resize(k);
    if (n == 0) {
        fit.offsets.assign(1, 0);
        return fit;
    }
    glm::dvec3 minimum(std::numeric_limits<double>::max()),
        maximum(-std::numeric_limits<double>::max());
    double totalWeight = 0.0;
    for (int i = 0; i < n; ++i) {
        SYLVA_CHECK(weights[i] > 0.0);
        minimum = glm::min(minimum, points[i]);
        maximum = glm::max(maximum, points[i]);
        totalWeight += weights[i];
    }
    const double initialRadius =
        std::max(glm::length(maximum - minimum) / (2.0 * std::cbrt(static_cast<double>(k))), 1e-6);
    for (int j = 0; j < k; ++j) {
        fit.components[j].mean = initialMeans[j];
        fit.components[j].covariance = glm::dmat3(initialRadius * initialRadius);
        fit.components[j].mixingWeight = 1.0 / k;
    }
    const bool truncated = options.neighbourCount > 0 && options.neighbourCount < k;
    const int neighbours = truncated ? options.neighbourCount : k;
    const double logTwoPi = std::log(2.0 * std::numbers::pi);

    std::vector<Density> densities(k);
    std::vector<glm::dvec3> means(k);
    MeanTree tree;
    constexpr int kNeighbourRefresh = 4;
    std::vector<int> candidates(truncated ? static_cast<std::size_t>(n) * neighbours : 0, -1);
    std::vector<std::pair<double, int>> nearest;
    std::vector<double> logDensity;
    fit.offsets.assign(n + 1, 0);
    double previousLikelihood = -std::numeric_limits<double>::infinity();

    for (int iteration = 0; iteration < options.maximumIterations; ++iteration) {
        // E-step.
        std::vector<int> alive;
        for (int j = 0; j < k; ++j) {
            GaussianComponent& c = fit.components[j];
            means[j] = c.mean;
            if (c.mixingWeight <= 0.0) {
                continue;
            }
            const double determinant = glm::determinant(c.covariance);
            if (!(determinant > 0.0) || !std::isfinite(determinant)) {
                c.mixingWeight = 0.0;
                continue;
            }
            densities[j].inverse = glm::inverse(c.covariance);
            densities[j].logNormalizer =
                std::log(c.mixingWeight) - 0.5 * std::log(determinant) - 1.5 * logTwoPi;
            alive.push_back(j);
        }
        SYLVA_CHECK(!alive.empty());
        // The candidate clusters of each point are re-searched every
        // kNeighbourRefresh iterations: means move little between iterations, and the
        // search dominates the cost otherwise.
        const bool refresh = truncated && iteration % kNeighbourRefresh == 0;
        if (refresh) {
            tree.build(means, alive);
        }
        fit.cluster.clear();
        fit.responsibility.clear();
        double likelihood = 0.0;
        for (int i = 0; i < n; ++i) {
            const glm::dvec3& x = points[i];
            if (truncated) {
                int* own = &candidates[static_cast<std::size_t>(i) * neighbours];
                if (refresh) {
                    tree.nearest(x, neighbours, nearest);
                    std::sort(nearest.begin(), nearest.end(),
                              [](const auto& a, const auto& b) { return a.second < b.second; });
                    for (int m = 0; m < neighbours; ++m) {
                        own[m] = m < static_cast<int>(nearest.size()) ? nearest[m].second : -1;
                    }
                }
                nearest.clear();
                for (int m = 0; m < neighbours; ++m) {
                    if (own[m] >= 0 && fit.components[own[m]].mixingWeight > 0.0) {
                        nearest.emplace_back(0.0, own[m]);
                    }
                }
                if (nearest.empty()) {  // every candidate died since the last search
                    for (int j : alive) {
                        nearest.emplace_back(0.0, j);
                    }
                }
            } else {
                nearest.clear();
                for (int j : alive) {
                    nearest.emplace_back(0.0, j);
                }
            }
            logDensity.resize(nearest.size());
            double best = -std::numeric_limits<double>::infinity();
            for (std::size_t m = 0; m < nearest.size(); ++m) {
                const int j = nearest[m].second;
                const glm::dvec3 d = x - fit.components[j].mean;
                logDensity[m] =
                    densities[j].logNormalizer - 0.5 * glm::dot(d, densities[j].inverse * d);
                best = std::max(best, logDensity[m]);
            }
            double sum = 0.0;
            for (double& l : logDensity) {
                l = std::exp(l - best);
                sum += l;
            }
            likelihood += weights[i] * (best + std::log(sum));
            for (std::size_t m = 0; m < nearest.size(); ++m) {
                const float r = static_cast<float>(logDensity[m] / sum);
                if (r > 1e-7f) {
                    fit.cluster.push_back(nearest[m].second);
                    fit.responsibility.push_back(r);
                }
            }
            fit.offsets[i + 1] = static_cast<std::uint32_t>(fit.cluster.size());
        }
        fit.iterations = iteration + 1;
        fit.logLikelihood = likelihood;
        const bool converged =
            std::abs(likelihood - previousLikelihood) <= options.tolerance * std::abs(likelihood);
        previousLikelihood = likelihood;
        if (converged) {
            break;
        }
        // M-step.
        std::vector<double> mass(k, 0.0);
        std::vector<glm::dvec3> sum(k, glm::dvec3(0.0));
        for (int i = 0; i < n; ++i) {
            for (std::uint32_t e = fit.offsets[i]; e < fit.offsets[i + 1]; ++e) {
                const double w = weights[i] * fit.responsibility[e];
                mass[fit.cluster[e]] += w;
                sum[fit.cluster[e]] += w * points[i];
            }
        }
        for (int j = 0; j < k; ++j) {
            if (mass[j] > 1e-12 * totalWeight) {
                fit.components[j].mean = sum[j] / mass[j];
            }
        }
        std::vector<glm::dmat3> scatter(k, glm::dmat3(0.0));
        for (int i = 0; i < n; ++i) {
            for (std::uint32_t e = fit.offsets[i]; e < fit.offsets[i + 1]; ++e) {
                const int j = fit.cluster[e];
                const glm::dvec3 d = points[i] - fit.components[j].mean;
                scatter[j] += (weights[i] * fit.responsibility[e]) * glm::outerProduct(d, d);
            }
        }
        for (int j = 0; j < k; ++j) {
            GaussianComponent& c = fit.components[j];
            if (mass[j] <= 1e-12 * totalWeight) {
                c.mixingWeight = 0.0;
                continue;
            }
            c.covariance = scatter[j] / mass[j] + glm::dmat3(options.varianceFloor);
            c.mixingWeight = mass[j] / totalWeight;
        }
    }
    return fit;
}

}  // namespace sylva
