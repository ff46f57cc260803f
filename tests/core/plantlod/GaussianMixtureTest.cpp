#include "sylva/core/plantlod/GaussianMixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "sylva/core/plantlod/EllipsoidFit.h"
#include "sylva/core/plantlod/EllipsoidHierarchy.h"

namespace sylva {
namespace {

// Three well-separated anisotropic clusters with known means and covariances.
struct KnownCluster {
    glm::dvec3 mean;
    glm::dvec3 sigma;  // per axis, axis-aligned
    int count;
};

std::vector<glm::dvec3> sample(const std::vector<KnownCluster>& clusters, std::mt19937& random) {
    std::vector<glm::dvec3> points;
    std::normal_distribution<double> normal(0.0, 1.0);
    for (const KnownCluster& c : clusters) {
        for (int i = 0; i < c.count; ++i) {
            points.push_back(c.mean +
                             c.sigma * glm::dvec3(normal(random), normal(random), normal(random)));
        }
    }
    return points;
}

TEST(GaussianMixture, RecoversKnownClusters) {
    const std::vector<KnownCluster> clusters = {{{0, 0, 0}, {0.5, 0.2, 0.1}, 3000},
                                                {{6, 1, 0}, {0.2, 0.6, 0.3}, 2000},
                                                {{2, 7, 3}, {0.4, 0.4, 0.8}, 1000}};
    std::mt19937 random(5);
    const std::vector<glm::dvec3> points = sample(clusters, random);
    const std::vector<double> weights(points.size(), 1.0);
    // Start from one point of each cluster, slightly off.
    const std::vector<glm::dvec3> initial = {points[10] + 0.3, points[3010] - 0.3,
                                             points[5010] + 0.2};
    for (int neighbours : {0, 2}) {
        GaussianMixtureOptions options;
        options.neighbourCount = neighbours;
        const GaussianMixtureFit fit = fitGaussianMixture(points, weights, initial, options);
        ASSERT_EQ(fit.components.size(), 3u);
        for (std::size_t j = 0; j < 3; ++j) {
            const GaussianComponent& c = fit.components[j];
            const KnownCluster& k = clusters[j];
            // Standard error of the mean is sigma/sqrt(n) ≤ 0.03: allow 5 of them.
            EXPECT_NEAR(c.mean.x, k.mean.x, 0.05) << j;
            EXPECT_NEAR(c.mean.y, k.mean.y, 0.05) << j;
            EXPECT_NEAR(c.mean.z, k.mean.z, 0.05) << j;
            for (int a = 0; a < 3; ++a) {
                EXPECT_NEAR(std::sqrt(c.covariance[a][a]), k.sigma[a], 0.06 * k.sigma[a])
                    << j << " axis " << a;
            }
            EXPECT_NEAR(c.mixingWeight, k.count / 6000.0, 0.01);
        }
        // Responsibilities sum to one per point.
        for (std::size_t i = 0; i < points.size(); i += 97) {
            float sum = 0.0f;
            for (std::uint32_t e = fit.offsets[i]; e < fit.offsets[i + 1]; ++e) {
                sum += fit.responsibility[e];
            }
            EXPECT_NEAR(sum, 1.0f, 1e-4f);
        }
    }
}

TEST(EllipsoidFit, JacobiEigenDecomposition) {
    // A = R diag(9, 4, 1) Rᵀ for a known rotation.
    const glm::dvec3 a = glm::normalize(glm::dvec3(1, 2, 2));
    const glm::dvec3 b = glm::normalize(glm::cross(a, glm::dvec3(0, 0, 1)));
    const glm::dvec3 c = glm::cross(a, b);
    const glm::dmat3 m =
        9.0 * glm::outerProduct(a, a) + 4.0 * glm::outerProduct(b, b) + glm::outerProduct(c, c);
    const SymmetricEigen eigen = symmetricEigen(m);
    EXPECT_NEAR(eigen.values[0], 9.0, 1e-12);
    EXPECT_NEAR(eigen.values[1], 4.0, 1e-12);
    EXPECT_NEAR(eigen.values[2], 1.0, 1e-12);
    EXPECT_NEAR(std::abs(glm::dot(eigen.vectors[0], a)), 1.0, 1e-12);
    EXPECT_NEAR(std::abs(glm::dot(eigen.vectors[1], b)), 1.0, 1e-12);
    EXPECT_NEAR(std::abs(glm::dot(eigen.vectors[2], c)), 1.0, 1e-12);
}

TEST(EllipsoidFit, PcaRadiiOfASampledEllipsoid) {
    // Points uniform in a solid ellipsoid with semi-axes (3, 2, 0.5), rotated: the
    // variance along a semi-axis R of a uniform solid ellipsoid is R²/5 (analytic).
    const glm::dvec3 semi(3.0, 2.0, 0.5);
    const double angle = 0.7;
    const glm::dvec3 u(std::cos(angle), std::sin(angle), 0.0),
        v(-std::sin(angle), std::cos(angle), 0.0), w(0, 0, 1);
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    WeightedMoments moments;
    int count = 0;
    while (count < 200000) {
        const glm::dvec3 q(unit(random), unit(random), unit(random));
        if (glm::dot(q, q) > 1.0) {
            continue;
        }
        moments.addPoint(
            glm::dvec3(5, -2, 1) + q.x * semi.x * u + q.y * semi.y * v + q.z * semi.z * w, 1.0);
        ++count;
    }
    const PrincipalAxes axes = principalAxes(moments);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(axes.radii[i], semi[i] / std::sqrt(5.0), 0.01 * semi[i]) << i;
    }
    EXPECT_NEAR(std::abs(glm::dot(axes.axes[0], u)), 1.0, 1e-3);
    EXPECT_NEAR(std::abs(glm::dot(axes.axes[2], w)), 1.0, 1e-3);
    EXPECT_NEAR(axes.center.x, 5.0, 0.01);
}

TEST(EllipsoidHierarchy, FuzzyAssignmentKeepsTheSmallCluster) {
    // Seed 001 Fig. 3.8: five leaves lie between a large cluster A and a small cluster
    // B; each gives B a quarter of its weight, never the majority. B accumulates 1.25 —
    // hard assignment rounds it away, fuzzy assignment keeps it.
    std::vector<LodEllipsoid> leaves;
    GaussianMixtureFit fit;
    fit.components.resize(2);
    fit.offsets.push_back(0);
    for (int i = 0; i < 25; ++i) {
        LodEllipsoid leaf;
        leaf.center = glm::vec3(float(i % 5) * 0.1f, float(i / 5) * 0.1f, 0.0f);
        leaf.radii = glm::vec3(0.05f, 0.03f, 0.001f);
        leaf.weight = 0.01f;
        leaf.color = glm::vec3(0.1f, 0.5f, 0.1f);
        leaves.push_back(leaf);
        const bool shared = i >= 20;
        fit.cluster.push_back(0);
        fit.responsibility.push_back(shared ? 0.75f : 1.0f);
        if (shared) {
            fit.cluster.push_back(1);
            fit.responsibility.push_back(0.25f);
        }
        fit.offsets.push_back(static_cast<std::uint32_t>(fit.cluster.size()));
    }
    const auto fuzzy = ellipsoidsFromAssignments(leaves, fit, false);
    const auto hard = ellipsoidsFromAssignments(leaves, fit, true);
    EXPECT_EQ(fuzzy.size(), 2u);
    EXPECT_EQ(hard.size(), 1u);
    // Noise level of the small cluster: l = 0.5 (1 + log2 1.25).
    const float expected = 0.5f * (1.0f + std::log2(1.25f));
    const bool found = std::any_of(fuzzy.begin(), fuzzy.end(), [&](const LodEllipsoid& e) {
        return std::abs(e.noiseLevel - expected) < 1e-5f;
    });
    EXPECT_TRUE(found);
}

}  // namespace
}  // namespace sylva
