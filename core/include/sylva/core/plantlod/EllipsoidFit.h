// EllipsoidFit: principal component analysis of weighted 3-D points and of weighted
// mixtures of ellipsoids (seed 001 §3.3.1, Fig. 3.2 and §3.4.1, Fig. 3.7). The axes are
// the covariance eigenvectors and the radii the square roots of the eigenvalues (the
// thesis's convention; the calibrated primitive scale later maps them to visible size).
// Metres; doubles inside, because leaf-sized covariances of trees tens of metres from
// the origin lose digits in float.
#pragma once

#include <glm/glm.hpp>

namespace sylva {

// Eigen-decomposition of a symmetric 3×3 matrix by cyclic Jacobi rotations; values
// descending, vectors orthonormal and right-handed.
struct SymmetricEigen {
    glm::dvec3 values{0.0};
    glm::dvec3 vectors[3];
};
SymmetricEigen symmetricEigen(const glm::dmat3& matrix);

// Accumulates weighted points or weighted ellipsoids (a mixture's first two moments).
class WeightedMoments {
public:
    void addPoint(const glm::dvec3& point, double weight);
    // An ellipsoid given as centre and covariance (axes · radii² · axesᵀ).
    void addDistribution(const glm::dvec3& mean, const glm::dmat3& covariance, double weight);

    double weight() const { return weight_; }
    glm::dvec3 mean() const;
    glm::dmat3 covariance() const;

private:
    double weight_ = 0.0;
    glm::dvec3 sum_{0.0};
    glm::dmat3 outer_{0.0};  // Σ w (x xᵀ + C)
};

struct PrincipalAxes {
    glm::dvec3 center{0.0};
    glm::dvec3 axes[3];
    glm::dvec3 radii{0.0};  // sqrt(eigenvalue), descending
};
PrincipalAxes principalAxes(const WeightedMoments& moments);

// Covariance of an ellipsoid with the given orthonormal axes and radii.
glm::dmat3 ellipsoidCovariance(const glm::vec3 axes[3], const glm::vec3& radii);

// Surface area (Knud Thomsen's approximation, relative error < 1.1 %), m².
double ellipsoidSurfaceArea(const glm::dvec3& radii);

}  // namespace sylva
