#include "sylva/core/plantlod/EllipsoidFit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace sylva {

SymmetricEigen symmetricEigen(const glm::dmat3& matrix) {
    // glm is column-major: a[c][r]; the matrix is symmetric so the layout does not matter.
    double a[3][3];
    double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
            a[r][c] = 0.5 * (matrix[c][r] + matrix[r][c]);
        }
    }
    for (int sweep = 0; sweep < 50; ++sweep) {
        const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        const double scale = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if (off <= 1e-30 * std::max(scale, 1e-300) || off == 0.0) {
            break;
        }
        for (int p = 0; p < 2; ++p) {
            for (int q = p + 1; q < 3; ++q) {
                if (a[p][q] == 0.0) {
                    continue;
                }
                const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                const double t =
                    (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0);
                const double s = t * c;
                for (int k = 0; k < 3; ++k) {  // A ← A J
                    const double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; ++k) {  // A ← Jᵀ A
                    const double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; ++k) {  // V ← V J (columns are eigenvectors)
                    const double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
        }
    }
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int i, int j) { return a[i][i] > a[j][j]; });
    SymmetricEigen result;
    for (int i = 0; i < 3; ++i) {
        result.values[i] = a[order[i]][order[i]];
        result.vectors[i] = glm::dvec3(v[0][order[i]], v[1][order[i]], v[2][order[i]]);
    }
    if (glm::dot(glm::cross(result.vectors[0], result.vectors[1]), result.vectors[2]) < 0.0) {
        result.vectors[2] = -result.vectors[2];
    }
    return result;
}

void WeightedMoments::addPoint(const glm::dvec3& point, double weight) {
    weight_ += weight;
    sum_ += weight * point;
    outer_ += weight * glm::outerProduct(point, point);
}

void WeightedMoments::addDistribution(const glm::dvec3& mean, const glm::dmat3& covariance,
                                      double weight) {
    weight_ += weight;
    sum_ += weight * mean;
    outer_ += weight * (glm::outerProduct(mean, mean) + covariance);
}

glm::dvec3 WeightedMoments::mean() const {
    return weight_ > 0.0 ? sum_ / weight_ : glm::dvec3(0.0);
}

glm::dmat3 WeightedMoments::covariance() const {
    if (weight_ <= 0.0) {
        return glm::dmat3(0.0);
    }
    const glm::dvec3 m = mean();
    return outer_ / weight_ - glm::outerProduct(m, m);
}

PrincipalAxes principalAxes(const WeightedMoments& moments) {
    PrincipalAxes result;
    result.center = moments.mean();
    const SymmetricEigen eigen = symmetricEigen(moments.covariance());
    for (int i = 0; i < 3; ++i) {
        result.axes[i] = eigen.vectors[i];
        result.radii[i] = std::sqrt(std::max(eigen.values[i], 0.0));
    }
    return result;
}

glm::dmat3 ellipsoidCovariance(const glm::vec3 axes[3], const glm::vec3& radii) {
    glm::dmat3 c(0.0);
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3 a(axes[i]);
        c += double(radii[i]) * double(radii[i]) * glm::outerProduct(a, a);
    }
    return c;
}

double ellipsoidSurfaceArea(const glm::dvec3& radii) {
    const double p = 1.6075;
    const double a = std::pow(radii.x, p), b = std::pow(radii.y, p), c = std::pow(radii.z, p);
    return 4.0 * std::numbers::pi * std::pow((a * b + a * c + b * c) / 3.0, 1.0 / p);
}

}  // namespace sylva
