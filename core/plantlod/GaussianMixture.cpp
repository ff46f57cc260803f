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

// The state of one EM run: the fit being improved and the E-step's scratch.
class MixtureFitter {
public:
    MixtureFitter(std::span<const glm::dvec3> points, std::span<const double> weights, int k,
                  const GaussianMixtureOptions& options)
        : points_(points),
          weights_(weights),
          options_(options),
          n_(static_cast<int>(points.size())),
          k_(k),
          truncated_(options.neighbourCount > 0 && options.neighbourCount < k),
          neighbours_(truncated_ ? options.neighbourCount : k),
          densities_(k),
          means_(k),
          candidates_(truncated_ ? static_cast<std::size_t>(n_) * neighbours_ : 0, -1) {
        fit_.components.resize(k);
        fit_.offsets.assign(n_ + 1, 0);
    }

    // Means as given, isotropic covariances of radius (bounding diagonal / 2) / ∛k,
    // equal mixing weights.
    void initialize(std::span<const glm::dvec3> initialMeans) {
        glm::dvec3 minimum(std::numeric_limits<double>::max()),
            maximum(-std::numeric_limits<double>::max());
        for (int i = 0; i < n_; ++i) {
            SYLVA_CHECK(weights_[i] > 0.0);
            minimum = glm::min(minimum, points_[i]);
            maximum = glm::max(maximum, points_[i]);
            totalWeight_ += weights_[i];
        }
        const double initialRadius = std::max(
            glm::length(maximum - minimum) / (2.0 * std::cbrt(static_cast<double>(k_))), 1e-6);
        for (int j = 0; j < k_; ++j) {
            fit_.components[j].mean = initialMeans[j];
            fit_.components[j].covariance = glm::dmat3(initialRadius * initialRadius);
            fit_.components[j].mixingWeight = 1.0 / k_;
        }
    }

    GaussianMixtureFit run() {
        double previousLikelihood = -std::numeric_limits<double>::infinity();
        for (int iteration = 0; iteration < options_.maximumIterations; ++iteration) {
            const double likelihood = expectation(iteration);
            fit_.iterations = iteration + 1;
            fit_.logLikelihood = likelihood;
            const bool converged = std::abs(likelihood - previousLikelihood) <=
                                   options_.tolerance * std::abs(likelihood);
            previousLikelihood = likelihood;
            if (converged) {
                break;
            }
            maximization();
        }
        return std::move(fit_);
    }

private:
    // The live components (positive weight, a positive finite determinant) with their
    // densities; a component that degenerated gets weight 0.
    std::vector<int> prepareDensities() {
        const double logTwoPi = std::log(2.0 * std::numbers::pi);
        std::vector<int> alive;
        for (int j = 0; j < k_; ++j) {
            GaussianComponent& c = fit_.components[j];
            means_[j] = c.mean;
            if (c.mixingWeight <= 0.0) {
                continue;
            }
            const double determinant = glm::determinant(c.covariance);
            if (!(determinant > 0.0) || !std::isfinite(determinant)) {
                c.mixingWeight = 0.0;
                continue;
            }
            densities_[j].inverse = glm::inverse(c.covariance);
            densities_[j].logNormalizer =
                std::log(c.mixingWeight) - 0.5 * std::log(determinant) - 1.5 * logTwoPi;
            alive.push_back(j);
        }
        SYLVA_CHECK(!alive.empty());
        return alive;
    }

    // The clusters point i is evaluated against, into nearest_: its stored nearest
    // candidates that are still alive (searched anew when `refresh`), or every live one.
    void candidatesOf(int i, bool refresh, const std::vector<int>& alive) {
        if (truncated_) {
            int* own = &candidates_[static_cast<std::size_t>(i) * neighbours_];
            if (refresh) {
                tree_.nearest(points_[i], neighbours_, nearest_);
                std::sort(nearest_.begin(), nearest_.end(),
                          [](const auto& a, const auto& b) { return a.second < b.second; });
                for (int m = 0; m < neighbours_; ++m) {
                    own[m] = m < static_cast<int>(nearest_.size()) ? nearest_[m].second : -1;
                }
            }
            nearest_.clear();
            for (int m = 0; m < neighbours_; ++m) {
                if (own[m] >= 0 && fit_.components[own[m]].mixingWeight > 0.0) {
                    nearest_.emplace_back(0.0, own[m]);
                }
            }
            if (!nearest_.empty()) {
                return;
            }
            // every candidate died since the last search: fall through to all live ones
        }
        nearest_.clear();
        for (int j : alive) {
            nearest_.emplace_back(0.0, j);
        }
    }

    // Point i's responsibilities (those above 1e-7) appended to the fit; returns its
    // weighted log-likelihood.
    double responsibilities(int i) {
        const glm::dvec3& x = points_[i];
        logDensity_.resize(nearest_.size());
        double best = -std::numeric_limits<double>::infinity();
        for (std::size_t m = 0; m < nearest_.size(); ++m) {
            const int j = nearest_[m].second;
            const glm::dvec3 d = x - fit_.components[j].mean;
            logDensity_[m] =
                densities_[j].logNormalizer - 0.5 * glm::dot(d, densities_[j].inverse * d);
            best = std::max(best, logDensity_[m]);
        }
        double sum = 0.0;
        for (double& l : logDensity_) {
            l = std::exp(l - best);
            sum += l;
        }
        for (std::size_t m = 0; m < nearest_.size(); ++m) {
            const float r = static_cast<float>(logDensity_[m] / sum);
            if (r > 1e-7f) {
                fit_.cluster.push_back(nearest_[m].second);
                fit_.responsibility.push_back(r);
            }
        }
        fit_.offsets[i + 1] = static_cast<std::uint32_t>(fit_.cluster.size());
        return weights_[i] * (best + std::log(sum));
    }

    // E-step; returns the log-likelihood. The candidate clusters of each point are
    // re-searched every kNeighbourRefresh iterations: means move little between
    // iterations, and the search dominates the cost otherwise.
    double expectation(int iteration) {
        constexpr int kNeighbourRefresh = 4;
        const std::vector<int> alive = prepareDensities();
        const bool refresh = truncated_ && iteration % kNeighbourRefresh == 0;
        if (refresh) {
            tree_.build(means_, alive);
        }
        fit_.cluster.clear();
        fit_.responsibility.clear();
        double likelihood = 0.0;
        for (int i = 0; i < n_; ++i) {
            candidatesOf(i, refresh, alive);
            likelihood += responsibilities(i);
        }
        return likelihood;
    }

    // M-step: means, then covariances about the new means (+ the variance floor) and
    // mixing weights; a component without mass dies.
    void maximization() {
        std::vector<double> mass(k_, 0.0);
        std::vector<glm::dvec3> sum(k_, glm::dvec3(0.0));
        for (int i = 0; i < n_; ++i) {
            for (std::uint32_t e = fit_.offsets[i]; e < fit_.offsets[i + 1]; ++e) {
                const double w = weights_[i] * fit_.responsibility[e];
                mass[fit_.cluster[e]] += w;
                sum[fit_.cluster[e]] += w * points_[i];
            }
        }
        for (int j = 0; j < k_; ++j) {
            if (mass[j] > 1e-12 * totalWeight_) {
                fit_.components[j].mean = sum[j] / mass[j];
            }
        }
        std::vector<glm::dmat3> scatter(k_, glm::dmat3(0.0));
        for (int i = 0; i < n_; ++i) {
            for (std::uint32_t e = fit_.offsets[i]; e < fit_.offsets[i + 1]; ++e) {
                const int j = fit_.cluster[e];
                const glm::dvec3 d = points_[i] - fit_.components[j].mean;
                scatter[j] += (weights_[i] * fit_.responsibility[e]) * glm::outerProduct(d, d);
            }
        }
        for (int j = 0; j < k_; ++j) {
            GaussianComponent& c = fit_.components[j];
            if (mass[j] <= 1e-12 * totalWeight_) {
                c.mixingWeight = 0.0;
                continue;
            }
            c.covariance = scatter[j] / mass[j] + glm::dmat3(options_.varianceFloor);
            c.mixingWeight = mass[j] / totalWeight_;
        }
    }

    std::span<const glm::dvec3> points_;
    std::span<const double> weights_;
    const GaussianMixtureOptions& options_;
    const int n_;
    const int k_;
    const bool truncated_;
    const int neighbours_;
    double totalWeight_ = 0.0;
    GaussianMixtureFit fit_;
    std::vector<Density> densities_;
    std::vector<glm::dvec3> means_;
    MeanTree tree_;
    std::vector<int> candidates_;  // per point, its neighbours_ nearest clusters (−1: none)
    std::vector<std::pair<double, int>> nearest_;
    std::vector<double> logDensity_;
};

}  // namespace

GaussianMixtureFit fitGaussianMixture(std::span<const glm::dvec3> points,
                                      std::span<const double> weights,
                                      std::span<const glm::dvec3> initialMeans,
                                      const GaussianMixtureOptions& options) {
    SYLVA_CHECK(points.size() == weights.size());
    SYLVA_CHECK(!initialMeans.empty());
    const int k = static_cast<int>(initialMeans.size());
    if (points.empty()) {
        GaussianMixtureFit fit;
        fit.components.resize(k);
        fit.offsets.assign(1, 0);
        return fit;
    }
    MixtureFitter fitter(points, weights, k, options);
    fitter.initialize(initialMeans);
    return fitter.run();
}

}  // namespace sylva
