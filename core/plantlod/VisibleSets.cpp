// Seed 000 ch. 3.2 (preprocessing: view directions, ID rendering, contribution counts)
// and ch. 3.3 (runtime: the sets of the three nearest view directions combined).
#include "sylva/core/plantlod/VisibleSets.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <utility>

namespace sylva {

namespace {

// Any unit vector perpendicular to `d`, and the third of the right-handed frame.
void basisOf(glm::vec3 d, glm::vec3& u, glm::vec3& v) {
    const glm::vec3 helper = std::abs(d.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    u = glm::normalize(glm::cross(helper, d));
    v = glm::cross(d, u);
}

// The ID image of one direction: per pixel the nearest sample (−1: background) and its
// height along `d` (larger is nearer the viewer). Each sample is its disc, projected
// orthographically (an ellipse), the pixel holding its centre always included (samples
// below a pixel still have one, §3.2.5).
struct IdImage {
    int resolution = 0;
    std::vector<int> id;
    std::vector<float> height;

    IdImage(int r)
        : resolution(r),
          id(std::size_t(r) * r, -1),
          height(std::size_t(r) * r, -std::numeric_limits<float>::infinity()) {}

    void write(int x, int y, float h, int sample) {
        if (x < 0 || y < 0 || x >= resolution || y >= resolution) {
            return;
        }
        const std::size_t i = std::size_t(y) * resolution + x;
        if (h > height[i]) {
            height[i] = h;
            id[i] = sample;
        }
    }
};

void renderIds(const PointCloud& cloud, glm::vec3 center, float sphereRadius, glm::vec3 d,
               const VisibleSetOptions& options, IdImage& image) {
    glm::vec3 u, v;
    basisOf(d, u, v);
    const float pixel = 2.0f * sphereRadius / float(options.resolution);
    const float minimumRadius = 0.5f * options.minimumPixels * pixel;
    for (std::size_t s = 0; s < cloud.points.size(); ++s) {
        const PlantPoint& p = cloud.points[s];
        const glm::vec3 offset = p.position - center;
        const float px = (glm::dot(offset, u) + sphereRadius) / pixel;
        const float py = (glm::dot(offset, v) + sphereRadius) / pixel;
        const float h = glm::dot(offset, d);
        image.write(int(std::floor(px)), int(std::floor(py)), h, int(s));
        // Occluders shrunk (VisibleSetOptions::occluderScale): a sample wins more pixels,
        // so the set errs on the side of keeping samples.
        const float radius = std::max(p.radius * options.occluderScale, minimumRadius);
        const float nu = glm::dot(p.normal, u), nv = glm::dot(p.normal, v);
        const float nd = glm::dot(p.normal, d);
        if (std::abs(nd) < 1e-3f) {
            continue;  // edge-on: only its centre pixel
        }
        const int extent = int(std::ceil(radius / pixel));
        const int cx = int(std::floor(px)), cy = int(std::floor(py));
        for (int y = cy - extent; y <= cy + extent; ++y) {
            for (int x = cx - extent; x <= cx + extent; ++x) {
                // The pixel centre's offset in the image plane, then along d onto the disc.
                const float a = (float(x) + 0.5f - px) * pixel, b = (float(y) + 0.5f - py) * pixel;
                const float t = -(a * nu + b * nv) / nd;
                if (a * a + b * b + t * t <= radius * radius) {
                    image.write(x, y, h + t, int(s));
                }
            }
        }
    }
}

}  // namespace

void VisibleSets::geodesicSphere(int subdivisions, std::vector<glm::vec3>& directions,
                                 std::vector<std::array<std::uint32_t, 3>>& cells) {
    const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;
    directions = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                  {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    for (glm::vec3& d : directions) {
        d = glm::normalize(d);
    }
    cells = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < subdivisions; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
        const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            auto [it, inserted] = midpoints.try_emplace(key, std::uint32_t(directions.size()));
            if (inserted) {
                directions.push_back(glm::normalize(directions[a] + directions[b]));
            }
            return it->second;
        };
        std::vector<std::array<std::uint32_t, 3>> finer;
        finer.reserve(cells.size() * 4);
        for (const auto& [a, b, c] : cells) {
            const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            finer.push_back({a, ab, ca});
            finer.push_back({b, bc, ab});
            finer.push_back({c, ca, bc});
            finer.push_back({ab, bc, ca});
        }
        cells = std::move(finer);
    }
}

VisibleSets VisibleSets::build(const PointCloud& cloud, const VisibleSetOptions& options) {
    VisibleSets sets;
    geodesicSphere(options.subdivisions, sets.directions_, sets.cells_);
    const glm::vec3 center = 0.5f * (cloud.boundsMinimum + cloud.boundsMaximum);
    float sphereRadius = 1e-6f;
    for (const PlantPoint& p : cloud.points) {
        sphereRadius = std::max(sphereRadius, glm::length(p.position - center) + p.radius);
    }
    const std::size_t n = cloud.points.size();
    sets.contributions_.assign(n, 0);
    // Per direction: the pixel count of every sample (kept for the cells' order).
    std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> counted(
        sets.directions_.size());
    std::vector<std::uint32_t> pixels(n, 0);
    for (std::size_t k = 0; k < sets.directions_.size(); ++k) {
        IdImage image(options.resolution);
        renderIds(cloud, center, sphereRadius, sets.directions_[k], options, image);
        std::fill(pixels.begin(), pixels.end(), 0u);
        for (int id : image.id) {
            if (id >= 0) {
                ++pixels[std::size_t(id)];
            }
        }
        for (std::size_t s = 0; s < n; ++s) {
            if (pixels[s] > 0) {
                counted[k].push_back({std::uint32_t(s), pixels[s]});
                sets.contributions_[s] += pixels[s];
            }
        }
        std::stable_sort(counted[k].begin(), counted[k].end(),
                         [](const auto& a, const auto& b) { return a.second > b.second; });
        sets.sets_.emplace_back();
        for (const auto& [sample, count] : counted[k]) {
            sets.sets_.back().push_back(sample);
        }
    }
    // Cells: the union of the corners' sets, ordered by the pixels summed over the corners.
    sets.cellOffsets_.push_back(0);
    std::vector<std::uint32_t> cellPixels(n, 0);
    std::vector<std::uint32_t> members;
    for (const auto& corners : sets.cells_) {
        members.clear();
        for (std::uint32_t corner : corners) {
            for (const auto& [sample, count] : counted[corner]) {
                if (cellPixels[sample] == 0) {
                    members.push_back(sample);
                }
                cellPixels[sample] += count;
            }
        }
        std::sort(members.begin(), members.end(), [&](std::uint32_t a, std::uint32_t b) {
            return cellPixels[a] != cellPixels[b] ? cellPixels[a] > cellPixels[b] : a < b;
        });
        sets.cellPoints_.insert(sets.cellPoints_.end(), members.begin(), members.end());
        sets.cellOffsets_.push_back(std::uint32_t(sets.cellPoints_.size()));
        for (std::uint32_t sample : members) {
            cellPixels[sample] = 0;
        }
    }
    return sets;
}

std::uint32_t VisibleSets::cellOf(glm::vec3 direction) const {
    const glm::vec3 d = glm::normalize(direction);
    constexpr float kTolerance = -1e-6f;
    float bestScore = -std::numeric_limits<float>::infinity();
    std::uint32_t best = 0;
    for (std::size_t c = 0; c < cells_.size(); ++c) {
        const glm::vec3 a = directions_[cells_[c][0]], b = directions_[cells_[c][1]],
                        e = directions_[cells_[c][2]];
        if (glm::dot(glm::cross(a, b), d) >= kTolerance &&
            glm::dot(glm::cross(b, e), d) >= kTolerance &&
            glm::dot(glm::cross(e, a), d) >= kTolerance) {
            return std::uint32_t(c);
        }
        const float score = glm::dot(a + b + e, d);
        if (score > bestScore) {
            bestScore = score;
            best = std::uint32_t(c);
        }
    }
    return best;
}

}  // namespace sylva
