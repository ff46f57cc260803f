// Skeleton reconstruction from branch triangles (seed 001 §3.3.2, "can be
// reconstructed from the source model"; the thesis gives no method, this one is ours):
// connected components → PCA cylinders → Prim-style linking into one tree.
#include "sylva/core/plantlod/SkeletonReconstructor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <queue>
#include <unordered_map>

namespace sylva {

namespace {

using Vector = glm::dvec3;

struct UnionFind {
    std::vector<std::uint32_t> parent;
    explicit UnionFind(std::size_t size) : parent(size) {
        std::iota(parent.begin(), parent.end(), 0u);
    }
    std::uint32_t find(std::uint32_t x) {
        while (parent[x] != x) {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        return x;
    }
    void unite(std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) {
            parent[std::max(a, b)] = std::min(a, b);
        }
    }
};

// Eigen-decomposition of a symmetric 3×3 matrix by cyclic Jacobi rotations.
void symmetricEigen(std::array<std::array<double, 3>, 3> a, std::array<double, 3>& values,
                    std::array<Vector, 3>& vectors) {
    std::array<std::array<double, 3>, 3> v{};
    for (int i = 0; i < 3; ++i) {
        v[std::size_t(i)][std::size_t(i)] = 1.0;
    }
    for (int sweep = 0; sweep < 32; ++sweep) {
        const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        if (off < 1e-30) {
            break;
        }
        for (std::size_t p = 0; p < 2; ++p) {
            for (std::size_t q = p + 1; q < 3; ++q) {
                if (std::abs(a[p][q]) < 1e-300) {
                    continue;
                }
                const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                const double t =
                    (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0);
                const double s = t * c;
                for (std::size_t k = 0; k < 3; ++k) {
                    const double akp = a[k][p];
                    const double akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (std::size_t k = 0; k < 3; ++k) {
                    const double apk = a[p][k];
                    const double aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (std::size_t k = 0; k < 3; ++k) {
                    const double vkp = v[k][p];
                    const double vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
        }
    }
    for (std::size_t i = 0; i < 3; ++i) {
        values[i] = a[i][i];
        vectors[i] = glm::normalize(Vector(v[0][i], v[1][i], v[2][i]));
    }
}

Vector centroidOf(const std::vector<Vector>& points) {
    Vector sum(0.0);
    for (const Vector& p : points) {
        sum += p;
    }
    return sum / double(points.size());
}

void covarianceEigen(const std::vector<Vector>& points, const Vector& centroid,
                     std::array<double, 3>& values, std::array<Vector, 3>& vectors) {
    std::array<std::array<double, 3>, 3> covariance{};
    for (const Vector& p : points) {
        const Vector d = p - centroid;
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                covariance[std::size_t(i)][std::size_t(j)] += d[i] * d[j];
            }
        }
    }
    symmetricEigen(covariance, values, vectors);
}

// A truncated cone along a straight axis.
struct Piece {
    Vector start;
    Vector end;
    double startRadius = 0.0;
    double endRadius = 0.0;
    double spread = 0.0;  // standard deviation of the radial residual
};

// Fits a cone to points: the axis direction is the candidate (principal axes, the
// component's axis) whose distances to the axis vary least — for a tube that is its
// true axis, even for short pieces where the principal axis lies across the tube.
Piece fitPiece(const std::vector<Vector>& points, const Vector& preferred) {
    const Vector centroid = centroidOf(points);
    std::array<double, 3> values{};
    std::array<Vector, 3> vectors{};
    covarianceEigen(points, centroid, values, vectors);
    const std::array<Vector, 4> candidates = {preferred, vectors[0], vectors[1], vectors[2]};
    Piece best;
    double bestScore = std::numeric_limits<double>::max();
    for (Vector direction : candidates) {
        if (glm::dot(direction, preferred) < 0.0) {
            direction = -direction;
        }
        // Least squares r(s) = alpha + beta s over the position s along the axis.
        double sumS = 0, sumR = 0, sumSS = 0, sumSR = 0;
        double minimum = std::numeric_limits<double>::max();
        double maximum = std::numeric_limits<double>::lowest();
        std::vector<std::pair<double, double>> samples;
        samples.reserve(points.size());
        for (const Vector& p : points) {
            const Vector d = p - centroid;
            const double s = glm::dot(d, direction);
            const double r = glm::length(d - direction * s);
            samples.emplace_back(s, r);
            sumS += s;
            sumR += r;
            sumSS += s * s;
            sumSR += s * r;
            minimum = std::min(minimum, s);
            maximum = std::max(maximum, s);
        }
        const double n = double(points.size());
        const double denominator = n * sumSS - sumS * sumS;
        const double beta = denominator > 1e-18 ? (n * sumSR - sumS * sumR) / denominator : 0.0;
        const double alpha = (sumR - beta * sumS) / n;
        double residual = 0.0;
        for (const auto& [s, r] : samples) {
            const double e = r - (alpha + beta * s);
            residual += e * e;
        }
        const double spread = std::sqrt(residual / n);
        if (spread < bestScore - 1e-12) {
            bestScore = spread;
            best.start = centroid + direction * minimum;
            best.end = centroid + direction * maximum;
            best.startRadius = std::max(0.0, alpha + beta * minimum);
            best.endRadius = std::max(0.0, alpha + beta * maximum);
            best.spread = spread;
        }
    }
    return best;
}

// Fits a cone to `points`; when they are not straight enough (radial spread above
// 12 % of the radius, or a bend off the axis) splits them near the median of `along` (their
// geodesic distance from one end of the stem, see reconstruct) and recurses, so curved stems become
// chains of short straight pieces. Splitting by geodesic distance rather than by projection keeps
// the arms of a U-shaped stem apart. Cuts keep at least four points on each side; depth 6 bounds a
// stem at 64 pieces. Pieces come out ordered by `along`, each oriented from its low to its high
// end.
void splitPiece(const std::vector<Vector>& points, const std::vector<double>& along, int depth,
                std::vector<Piece>& out) {
    std::vector<std::size_t> order(points.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return along[a] < along[b]; });
    const std::size_t half = order.size() / 2;
    Vector low(0.0);
    Vector high(0.0);
    for (std::size_t i = 0; i < order.size(); ++i) {
        (i < half ? low : high) += points[order[i]];
    }
    Vector preferred =
        high / double(order.size() - half) - low / double(std::max<std::size_t>(half, 1));
    preferred = glm::length(preferred) > 0.0 ? glm::normalize(preferred) : Vector(0.0, 0.0, 1.0);
    const Piece piece = fitPiece(points, preferred);
    const double radius = 0.5 * (piece.startRadius + piece.endRadius);
    // Bend: the middle third's centroid (in stem order) off the fitted axis, which the
    // radial spread alone misses on thick tubes (a fitted radius absorbs the bend).
    Vector middle(0.0);
    const std::size_t third = order.size() / 3;
    for (std::size_t i = third; i < order.size() - third; ++i) {
        middle += points[order[i]];
    }
    middle /= double(order.size() - 2 * third);
    const Vector axis = piece.end - piece.start;
    const double axisLength = glm::length(axis);
    const double bend =
        axisLength > 0.0 ? glm::length(glm::cross(middle - piece.start, axis)) / axisLength : 0.0;
    const bool straight =
        piece.spread <= 0.12 * radius + 1e-4 && bend <= 0.1 * radius + 0.005 * axisLength;
    if (straight || points.size() < 8 || depth >= 6) {
        // Ends: the centroids of the first and last sixth of the points in stem order
        // (an end ring's centre), projected on the axis. Extreme projections would
        // overshoot by the radius times the axis tilt, badly at a flared trunk base.
        Piece ends = piece;
        if (axisLength > 0.0 && points.size() >= 6) {
            const glm::dvec3 unit = axis / axisLength;
            const std::size_t sixth = std::max<std::size_t>(order.size() / 6, 1);
            Vector first(0.0);
            Vector last(0.0);
            for (std::size_t i = 0; i < sixth; ++i) {
                first += points[order[i]];
                last += points[order[order.size() - 1 - i]];
            }
            first /= double(sixth);
            last /= double(sixth);
            const double t0 = glm::dot(first - piece.start, unit);
            const double t1 = glm::dot(last - piece.start, unit);
            if (t1 > t0) {
                const double slope = (piece.endRadius - piece.startRadius) / axisLength;
                ends.start = piece.start + unit * t0;
                ends.end = piece.start + unit * t1;
                ends.startRadius = std::max(0.0, piece.startRadius + slope * t0);
                ends.endRadius = std::max(0.0, piece.startRadius + slope * t1);
            }
        }
        out.push_back(ends);
        return;
    }
    // Cut at the widest gap in stem order within the middle half, so whole rings of a
    // tube stay together (a cut through a ring biases both pieces' centroids).
    std::size_t cut = half;
    double widest = -1.0;
    for (std::size_t i = std::max<std::size_t>(order.size() / 4, 4);
         i + 4 <= order.size() && i <= 3 * order.size() / 4; ++i) {
        const double gap = along[order[i]] - along[order[i - 1]];
        if (gap > widest) {
            widest = gap;
            cut = i;
        }
    }
    std::array<std::vector<Vector>, 2> parts;
    std::array<std::vector<double>, 2> partAlong;
    for (std::size_t i = 0; i < order.size(); ++i) {
        parts[i < cut ? 0 : 1].push_back(points[order[i]]);
        partAlong[i < cut ? 0 : 1].push_back(along[order[i]]);
    }
    splitPiece(parts[0], partAlong[0], depth + 1, out);
    splitPiece(parts[1], partAlong[1], depth + 1, out);
}

// A component as a chain of straight pieces along its length.
std::vector<Piece> fitComponent(const std::vector<Vector>& points,
                                const std::vector<double>& along) {
    std::vector<Piece> pieces;
    splitPiece(points, along, 0, pieces);
    // Consecutive pieces meet at the midpoint of their facing ends.
    for (std::size_t i = 1; i < pieces.size(); ++i) {
        const Vector joint = 0.5 * (pieces[i - 1].end + pieces[i].start);
        const double radius = 0.5 * (pieces[i - 1].endRadius + pieces[i].startRadius);
        pieces[i - 1].end = joint;
        pieces[i].start = joint;
        pieces[i - 1].endRadius = radius;
        pieces[i].startRadius = radius;
    }
    return pieces;
}

// Geodesic (edge-path) distances over the welded vertex graph from `source`, by
// Dijkstra; `distance` must hold infinity for the component's vertices.
void geodesicDistances(const std::vector<std::uint32_t>& sources,
                       const std::vector<std::vector<std::pair<std::uint32_t, double>>>& adjacency,
                       std::vector<double>& distance) {
    using Entry = std::pair<double, std::uint32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    for (std::uint32_t source : sources) {
        distance[source] = 0.0;
        queue.emplace(0.0, source);
    }
    while (!queue.empty()) {
        const auto [d, vertex] = queue.top();
        queue.pop();
        if (d > distance[vertex]) {
            continue;
        }
        for (const auto& [next, length] : adjacency[vertex]) {
            if (d + length < distance[next]) {
                distance[next] = d + length;
                queue.emplace(distance[next], next);
            }
        }
    }
}

double distanceToSegment(const Vector& p, const Vector& a, const Vector& b, Vector& closest) {
    const Vector ab = b - a;
    const double lengthSquared = glm::dot(ab, ab);
    const double t =
        lengthSquared > 0.0 ? std::clamp(glm::dot(p - a, ab) / lengthSquared, 0.0, 1.0) : 0.0;
    closest = a + ab * t;
    return glm::length(p - closest);
}

struct Component {
    std::vector<Piece> pieces;
    double lowest = 0.0;
    double baseRadius = 0.0;  // radius at the chain's lower end
};

struct Attachment {
    double distance = std::numeric_limits<double>::max();
    bool fromEnd = false;  // the component's last end attaches (chain reversed)
    int segment = -1;
    Vector point{0.0};
};

}  // namespace

std::vector<SkeletonSegment> SkeletonReconstructor::reconstruct(
    const std::vector<PlantMesh>& meshes) {
    // Weld: vertices with bit-identical positions are one (tube seams, shared rings).
    std::vector<Vector> positions;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> byPosition;
    std::vector<std::uint32_t> canonical;
    for (const PlantMesh& mesh : meshes) {
        if (mesh.part != PlantPart::Branch) {
            continue;
        }
        const std::uint32_t base = std::uint32_t(positions.size());
        for (const glm::vec3& p : mesh.positions) {
            std::uint32_t bits[3];
            std::memcpy(bits, &p, sizeof bits);
            const std::uint64_t key = (std::uint64_t(bits[0]) * 0x9E3779B97F4A7C15ull) ^
                                      (std::uint64_t(bits[1]) * 0xC2B2AE3D27D4EB4Full) ^
                                      std::uint64_t(bits[2]);
            std::uint32_t id = std::uint32_t(positions.size());
            for (std::uint32_t other : byPosition[key]) {
                if (glm::vec3(positions[other]) == p) {
                    id = other;
                    break;
                }
            }
            if (id == positions.size()) {
                byPosition[key].push_back(id);
            }
            canonical.push_back(id);
            positions.emplace_back(p);
        }
        for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            for (int k = 0; k < 3; ++k) {
                edges.emplace_back(base + mesh.indices[i + std::size_t(k)],
                                   base + mesh.indices[i + std::size_t((k + 1) % 3)]);
            }
        }
    }
    if (positions.empty()) {
        return {};
    }
    UnionFind sets(positions.size());
    for (std::uint32_t i = 0; i < positions.size(); ++i) {
        sets.unite(i, canonical[i]);
    }
    for (const auto& [a, b] : edges) {
        sets.unite(a, b);
    }
    // Points of each component, unique positions only (duplicates would weight seams).
    std::unordered_map<std::uint32_t, std::size_t> componentOf;
    std::vector<std::vector<std::uint32_t>> componentVertices;
    for (std::uint32_t i = 0; i < positions.size(); ++i) {
        if (canonical[i] != i) {
            continue;
        }
        const std::uint32_t root = sets.find(i);
        auto [it, inserted] = componentOf.emplace(root, componentVertices.size());
        if (inserted) {
            componentVertices.emplace_back();
        }
        componentVertices[it->second].push_back(i);
    }
    std::vector<std::vector<std::pair<std::uint32_t, double>>> adjacency(positions.size());
    for (const auto& [a, b] : edges) {
        const std::uint32_t ca = canonical[a];
        const std::uint32_t cb = canonical[b];
        if (ca != cb) {
            const double length = glm::length(positions[ca] - positions[cb]);
            adjacency[ca].emplace_back(cb, length);
            adjacency[cb].emplace_back(ca, length);
        }
    }
    std::vector<double> geodesic(positions.size(), std::numeric_limits<double>::infinity());
    // Boundary edges (used by one triangle only): the open ends of tubes.
    std::unordered_map<std::uint64_t, int> edgeUse;
    for (const auto& [a, b] : edges) {
        const std::uint32_t ca = std::min(canonical[a], canonical[b]);
        const std::uint32_t cb = std::max(canonical[a], canonical[b]);
        if (ca != cb) {
            ++edgeUse[(std::uint64_t(ca) << 32) | cb];
        }
    }
    std::vector<std::vector<std::uint32_t>> boundary(positions.size());
    for (const auto& [key, uses] : edgeUse) {
        if (uses == 1) {
            boundary[std::uint32_t(key >> 32)].push_back(std::uint32_t(key & 0xFFFFFFFFu));
            boundary[std::uint32_t(key & 0xFFFFFFFFu)].push_back(std::uint32_t(key >> 32));
        }
    }

    std::vector<Component> components;
    for (const std::vector<std::uint32_t>& vertices : componentVertices) {
        if (vertices.size() < 4) {
            continue;
        }
        std::vector<Vector> points;
        for (std::uint32_t v : vertices) {
            points.push_back(positions[v]);
        }
        // Double sweep: the vertex farthest (along the surface) from an end of the
        // principal axis is one end of the stem; distances from it order the stem.
        const Vector centroid = centroidOf(points);
        std::array<double, 3> values{};
        std::array<Vector, 3> vectors{};
        covarianceEigen(points, centroid, values, vectors);
        const Vector axis =
            vectors[std::size_t(std::max_element(values.begin(), values.end()) - values.begin())];
        std::uint32_t start = vertices.front();
        for (std::uint32_t v : vertices) {
            if (glm::dot(positions[v], axis) < glm::dot(positions[start], axis)) {
                start = v;
            }
        }
        geodesicDistances({start}, adjacency, geodesic);
        std::uint32_t end = start;
        for (std::uint32_t v : vertices) {
            if (geodesic[v] != std::numeric_limits<double>::infinity() &&
                geodesic[v] > geodesic[end]) {
                end = v;
            }
        }
        for (std::uint32_t v : vertices) {
            geodesic[v] = std::numeric_limits<double>::infinity();
        }
        // Distances from the whole open end (the boundary loop through `end`, when it
        // lies on one) so that every ring of a tube gets one distance, even a fat one.
        std::vector<std::uint32_t> sources = {end};
        for (std::size_t i = 0; i < sources.size(); ++i) {
            for (std::uint32_t next : boundary[sources[i]]) {
                if (std::find(sources.begin(), sources.end(), next) == sources.end()) {
                    sources.push_back(next);
                }
            }
        }
        geodesicDistances(sources, adjacency, geodesic);
        std::vector<double> along;
        for (std::uint32_t v : vertices) {
            along.push_back(geodesic[v]);
            geodesic[v] = std::numeric_limits<double>::infinity();
        }
        Component component;
        component.pieces = fitComponent(points, along);
        component.lowest = std::numeric_limits<double>::max();
        for (const Vector& p : points) {
            component.lowest = std::min(component.lowest, p.z);
        }
        component.baseRadius = component.pieces.front().start.z <= component.pieces.back().end.z
                                   ? component.pieces.front().startRadius
                                   : component.pieces.back().endRadius;
        components.push_back(std::move(component));
    }
    if (components.empty()) {
        return {};
    }

    // Root: among the components that reach down to the lowest point, the one thickest
    // at its lower end (a trunk base, not a drooping branch tip; whole-chain maxima are
    // fooled by a badly fitted piece).
    double lowest = std::numeric_limits<double>::max();
    double highest = std::numeric_limits<double>::lowest();
    for (const Vector& p : positions) {
        lowest = std::min(lowest, p.z);
        highest = std::max(highest, p.z);
    }
    const double reach = lowest + 0.02 * (highest - lowest) + 1e-6;
    std::size_t root = 0;
    for (std::size_t i = 0; i < components.size(); ++i) {
        if (components[i].lowest <= reach &&
            (components[root].lowest > reach ||
             components[i].baseRadius > components[root].baseRadius)) {
            root = i;
        }
    }

    std::vector<SkeletonSegment> skeleton;
    std::vector<bool> attached(components.size(), false);
    std::vector<Attachment> best(components.size());
    auto append = [&](std::size_t index, bool reversed, int parent, const Vector* startPoint) {
        std::vector<Piece> pieces = components[index].pieces;
        if (reversed) {
            std::reverse(pieces.begin(), pieces.end());
            for (Piece& piece : pieces) {
                std::swap(piece.start, piece.end);
                std::swap(piece.startRadius, piece.endRadius);
            }
        }
        if (startPoint != nullptr) {
            pieces.front().start = *startPoint;
        }
        const int first = int(skeleton.size());
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            SkeletonSegment segment;
            segment.start = glm::vec3(pieces[k].start);
            segment.end = glm::vec3(pieces[k].end);
            segment.startRadius = float(pieces[k].startRadius);
            segment.endRadius = float(pieces[k].endRadius);
            segment.parent = k == 0 ? parent : first + int(k) - 1;
            skeleton.push_back(segment);
        }
        attached[index] = true;
        // Update every unattached component's best attachment against the new segments.
        for (std::size_t other = 0; other < components.size(); ++other) {
            if (attached[other]) {
                continue;
            }
            const std::array<Vector, 2> ends = {components[other].pieces.front().start,
                                                components[other].pieces.back().end};
            for (std::size_t s = std::size_t(first); s < skeleton.size(); ++s) {
                for (std::size_t e = 0; e < 2; ++e) {
                    Vector closest;
                    const double distance = distanceToSegment(ends[e], Vector(skeleton[s].start),
                                                              Vector(skeleton[s].end), closest);
                    if (distance < best[other].distance) {
                        best[other] = {distance, e == 1, int(s), closest};
                    }
                }
            }
        }
    };
    const Component& trunk = components[root];
    append(root, trunk.pieces.front().start.z > trunk.pieces.back().end.z, -1, nullptr);
    for (std::size_t round = 1; round < components.size(); ++round) {
        std::size_t next = components.size();
        for (std::size_t i = 0; i < components.size(); ++i) {
            if (!attached[i] &&
                (next == components.size() || best[i].distance < best[next].distance)) {
                next = i;
            }
        }
        const Attachment attachment = best[next];
        append(next, attachment.fromEnd, attachment.segment, &attachment.point);
    }
    return skeleton;
}

}  // namespace sylva
