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

constexpr double kUnreached = std::numeric_limits<double>::infinity();

// The branch triangles welded: vertices with bit-identical positions are one (tube
// seams, shared rings), `canonical` maps every vertex to its first copy.
struct WeldedBranches {
    std::vector<Vector> positions;
    std::vector<std::uint32_t> canonical;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;  // three per triangle
};

WeldedBranches weldBranches(const std::vector<PlantMesh>& meshes) {
    WeldedBranches welded;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> byPosition;
    for (const PlantMesh& mesh : meshes) {
        if (mesh.part != PlantPart::Branch) {
            continue;
        }
        const std::uint32_t base = std::uint32_t(welded.positions.size());
        for (const glm::vec3& p : mesh.positions) {
            std::uint32_t bits[3];
            std::memcpy(bits, &p, sizeof bits);
            const std::uint64_t key = (std::uint64_t(bits[0]) * 0x9E3779B97F4A7C15ull) ^
                                      (std::uint64_t(bits[1]) * 0xC2B2AE3D27D4EB4Full) ^
                                      std::uint64_t(bits[2]);
            std::uint32_t id = std::uint32_t(welded.positions.size());
            for (std::uint32_t other : byPosition[key]) {
                if (glm::vec3(welded.positions[other]) == p) {
                    id = other;
                    break;
                }
            }
            if (id == welded.positions.size()) {
                byPosition[key].push_back(id);
            }
            welded.canonical.push_back(id);
            welded.positions.emplace_back(p);
        }
        for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            for (int k = 0; k < 3; ++k) {
                welded.edges.emplace_back(base + mesh.indices[i + std::size_t(k)],
                                          base + mesh.indices[i + std::size_t((k + 1) % 3)]);
            }
        }
    }
    return welded;
}

// The canonical vertices of each connected component (unique positions only: duplicates
// would weight seams), in vertex order.
std::vector<std::vector<std::uint32_t>> connectedComponents(const WeldedBranches& welded) {
    UnionFind sets(welded.positions.size());
    for (std::uint32_t i = 0; i < welded.positions.size(); ++i) {
        sets.unite(i, welded.canonical[i]);
    }
    for (const auto& [a, b] : welded.edges) {
        sets.unite(a, b);
    }
    std::unordered_map<std::uint32_t, std::size_t> componentOf;
    std::vector<std::vector<std::uint32_t>> componentVertices;
    for (std::uint32_t i = 0; i < welded.positions.size(); ++i) {
        if (welded.canonical[i] != i) {
            continue;
        }
        const std::uint32_t root = sets.find(i);
        auto [it, inserted] = componentOf.emplace(root, componentVertices.size());
        if (inserted) {
            componentVertices.emplace_back();
        }
        componentVertices[it->second].push_back(i);
    }
    return componentVertices;
}

// The welded vertex graph: edge lengths, and the boundary edges (used by one triangle
// only), which are the open ends of tubes.
struct SurfaceGraph {
    std::vector<std::vector<std::pair<std::uint32_t, double>>> adjacency;
    std::vector<std::vector<std::uint32_t>> boundary;
};

SurfaceGraph surfaceGraph(const WeldedBranches& welded) {
    SurfaceGraph graph;
    graph.adjacency.resize(welded.positions.size());
    for (const auto& [a, b] : welded.edges) {
        const std::uint32_t ca = welded.canonical[a];
        const std::uint32_t cb = welded.canonical[b];
        if (ca != cb) {
            const double length = glm::length(welded.positions[ca] - welded.positions[cb]);
            graph.adjacency[ca].emplace_back(cb, length);
            graph.adjacency[cb].emplace_back(ca, length);
        }
    }
    std::unordered_map<std::uint64_t, int> edgeUse;
    for (const auto& [a, b] : welded.edges) {
        const std::uint32_t ca = std::min(welded.canonical[a], welded.canonical[b]);
        const std::uint32_t cb = std::max(welded.canonical[a], welded.canonical[b]);
        if (ca != cb) {
            ++edgeUse[(std::uint64_t(ca) << 32) | cb];
        }
    }
    graph.boundary.resize(welded.positions.size());
    for (const auto& [key, uses] : edgeUse) {
        if (uses == 1) {
            graph.boundary[std::uint32_t(key >> 32)].push_back(std::uint32_t(key & 0xFFFFFFFFu));
            graph.boundary[std::uint32_t(key & 0xFFFFFFFFu)].push_back(std::uint32_t(key >> 32));
        }
    }
    return graph;
}

// Each vertex's distance along the stem from its open end. Double sweep: the vertex
// farthest (along the surface) from an end of the principal axis is one end of the
// stem; distances from the whole open end there (the boundary loop through it, when it
// lies on one) give every ring of a tube one distance, even a fat one. `geodesic` holds
// kUnreached for every vertex on entry and on return.
std::vector<double> distancesAlongStem(const std::vector<std::uint32_t>& vertices,
                                       const std::vector<Vector>& points,
                                       const WeldedBranches& welded, const SurfaceGraph& graph,
                                       std::vector<double>& geodesic) {
    const Vector centroid = centroidOf(points);
    std::array<double, 3> values{};
    std::array<Vector, 3> vectors{};
    covarianceEigen(points, centroid, values, vectors);
    const Vector axis =
        vectors[std::size_t(std::max_element(values.begin(), values.end()) - values.begin())];
    std::uint32_t start = vertices.front();
    for (std::uint32_t v : vertices) {
        if (glm::dot(welded.positions[v], axis) < glm::dot(welded.positions[start], axis)) {
            start = v;
        }
    }
    geodesicDistances({start}, graph.adjacency, geodesic);
    std::uint32_t end = start;
    for (std::uint32_t v : vertices) {
        if (geodesic[v] != kUnreached && geodesic[v] > geodesic[end]) {
            end = v;
        }
    }
    for (std::uint32_t v : vertices) {
        geodesic[v] = kUnreached;
    }
    std::vector<std::uint32_t> sources = {end};
    for (std::size_t i = 0; i < sources.size(); ++i) {
        for (std::uint32_t next : graph.boundary[sources[i]]) {
            if (std::find(sources.begin(), sources.end(), next) == sources.end()) {
                sources.push_back(next);
            }
        }
    }
    geodesicDistances(sources, graph.adjacency, geodesic);
    std::vector<double> along;
    for (std::uint32_t v : vertices) {
        along.push_back(geodesic[v]);
        geodesic[v] = kUnreached;
    }
    return along;
}

// Components of at least four vertices as chains of pieces.
std::vector<Component> fitComponents(const WeldedBranches& welded) {
    const SurfaceGraph graph = surfaceGraph(welded);
    std::vector<double> geodesic(welded.positions.size(), kUnreached);
    std::vector<Component> components;
    for (const std::vector<std::uint32_t>& vertices : connectedComponents(welded)) {
        if (vertices.size() < 4) {
            continue;
        }
        std::vector<Vector> points;
        for (std::uint32_t v : vertices) {
            points.push_back(welded.positions[v]);
        }
        const std::vector<double> along =
            distancesAlongStem(vertices, points, welded, graph, geodesic);
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
    return components;
}

// Root: among the components that reach down to the lowest point, the one thickest at
// its lower end (a trunk base, not a drooping branch tip; whole-chain maxima are fooled
// by a badly fitted piece).
std::size_t rootComponent(const std::vector<Component>& components,
                          const std::vector<Vector>& positions) {
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
    return root;
}

// Prim-style linking: the components join the growing skeleton one at a time, always
// the unattached one whose nearer end lies closest to a segment already there.
class SkeletonLinker {
public:
    explicit SkeletonLinker(const std::vector<Component>& components)
        : components_(components), attached_(components.size(), false), best_(components.size()) {}

    std::vector<SkeletonSegment> link(std::size_t root) {
        const Component& trunk = components_[root];
        append(root, trunk.pieces.front().start.z > trunk.pieces.back().end.z, -1, nullptr);
        for (std::size_t round = 1; round < components_.size(); ++round) {
            std::size_t next = components_.size();
            for (std::size_t i = 0; i < components_.size(); ++i) {
                if (!attached_[i] &&
                    (next == components_.size() || best_[i].distance < best_[next].distance)) {
                    next = i;
                }
            }
            const Attachment attachment = best_[next];
            append(next, attachment.fromEnd, attachment.segment, &attachment.point);
        }
        return std::move(skeleton_);
    }

private:
    // Appends a component's chain (reversed when it attaches by its last end), its first
    // segment starting at `startPoint` on segment `parent`.
    void append(std::size_t index, bool reversed, int parent, const Vector* startPoint) {
        std::vector<Piece> pieces = components_[index].pieces;
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
        const int first = int(skeleton_.size());
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            SkeletonSegment segment;
            segment.start = glm::vec3(pieces[k].start);
            segment.end = glm::vec3(pieces[k].end);
            segment.startRadius = float(pieces[k].startRadius);
            segment.endRadius = float(pieces[k].endRadius);
            segment.parent = k == 0 ? parent : first + int(k) - 1;
            skeleton_.push_back(segment);
        }
        attached_[index] = true;
        updateAttachments(std::size_t(first));
    }

    // Every unattached component's best attachment against the segments from `first` on.
    void updateAttachments(std::size_t first) {
        for (std::size_t other = 0; other < components_.size(); ++other) {
            if (attached_[other]) {
                continue;
            }
            const std::array<Vector, 2> ends = {components_[other].pieces.front().start,
                                                components_[other].pieces.back().end};
            for (std::size_t s = first; s < skeleton_.size(); ++s) {
                for (std::size_t e = 0; e < 2; ++e) {
                    Vector closest;
                    const double distance = distanceToSegment(ends[e], Vector(skeleton_[s].start),
                                                              Vector(skeleton_[s].end), closest);
                    if (distance < best_[other].distance) {
                        best_[other] = {distance, e == 1, int(s), closest};
                    }
                }
            }
        }
    }

    const std::vector<Component>& components_;
    std::vector<SkeletonSegment> skeleton_;
    std::vector<bool> attached_;
    std::vector<Attachment> best_;
};

}  // namespace

std::vector<SkeletonSegment> SkeletonReconstructor::reconstruct(
    const std::vector<PlantMesh>& meshes) {
    const WeldedBranches welded = weldBranches(meshes);
    if (welded.positions.empty()) {
        return {};
    }
    const std::vector<Component> components = fitComponents(welded);
    if (components.empty()) {
        return {};
    }
    return SkeletonLinker(components).link(rootComponent(components, welded.positions));
}

}  // namespace sylva
