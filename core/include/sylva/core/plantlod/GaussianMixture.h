// GaussianMixture: Expectation-Maximization for a mixture of full-covariance 3-D normal
// distributions over weighted points (Dempster et al. 1977; seed 001 §3.4.1, Fig. 3.6).
// The result keeps the fuzzy assignments w_ij (responsibilities) that the ellipsoid
// hierarchy turns into weighted-PCA ellipsoids.
//
// Speed (the thesis spent 83 % of 396 minutes here for 27k leaves): with K clusters and
// N points an exact E-step costs N·K density evaluations. When K exceeds
// `neighbourCount`, each point is evaluated only against its `neighbourCount` nearest
// cluster means (a k-d tree rebuilt every iteration); the responsibilities of farther
// clusters are below e^-20 of the nearest ones for the cluster spacings a hierarchy
// level produces, so the truncation changes the result negligibly while one iteration
// drops from O(N·K) to O(N log K). The neighbour lists are re-searched every fourth
// iteration only (means move little between iterations). Exact EM remains available
// (neighbourCount = 0).
//
// Deterministic: the same inputs give the same outputs (no threads inside).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace sylva {

struct GaussianMixtureOptions {
    int maximumIterations = 60;
    double tolerance = 1e-5;  // relative change of the log-likelihood that ends EM
    int neighbourCount = 8;   // 0: every point against every cluster
    // Added to every covariance diagonal, m² (keeps clusters of one or two coplanar
    // points invertible).
    double varianceFloor = 1e-8;
};

struct GaussianComponent {
    glm::dvec3 mean{0.0};
    glm::dmat3 covariance{1.0};
    double mixingWeight = 0.0;  // 0: the cluster died (no responsibility left)
};

struct GaussianMixtureFit {
    std::vector<GaussianComponent> components;
    // Sparse responsibilities: point i owns entries [offsets[i], offsets[i + 1]).
    std::vector<std::uint32_t> offsets;
    std::vector<std::int32_t> cluster;
    std::vector<float> responsibility;  // sums to 1 per point
    int iterations = 0;
    double logLikelihood = 0.0;
};

// `initialMeans` sets K; initial covariances are isotropic with a radius of the point
// bounds' diagonal / (2 K^(1/3)). Weights must be positive (SYLVA_CHECK).
GaussianMixtureFit fitGaussianMixture(std::span<const glm::dvec3> points,
                                      std::span<const double> weights,
                                      std::span<const glm::dvec3> initialMeans,
                                      const GaussianMixtureOptions& options = {});

}  // namespace sylva
