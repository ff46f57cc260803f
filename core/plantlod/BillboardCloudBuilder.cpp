// Billboard clouds after Décoret et al. 2003 with the tree extensions of Fuhrmann,
// Umlauf & Mantler 2005 (seed 003 §3.3, seed 000 ch. 4). Section references below are
// to seed 003.
#include "sylva/core/plantlod/BillboardCloudBuilder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <unordered_set>

#include "sylva/core/plantlod/PlantRasterizer.h"

namespace sylva {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Face {
    std::array<std::uint32_t, 3> vertices{};
    std::size_t mesh = 0;
    std::size_t triangle = 0;
    std::size_t source = 0;  // global triangle index
    PlantPart part = PlantPart::Leaf;
    double area = 0.0;
    glm::dvec3 normal{0.0};
    int plane = -1;
};

struct Plane {
    glm::dvec3 normal{0.0, 0.0, 1.0};
    double offset = 0.0;             // normal · x = offset
    std::vector<std::size_t> faces;  // simplified onto it (cardboard: the faces it shows)
    PlantPart part = PlantPart::Leaf;
    bool cardboard = false;
};

glm::dvec3 direction(double azimuth, double elevation) {
    return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
            std::sin(elevation)};
}

// One simplification run of one part at one epsilon, on mutable (welded) positions.
class PartSimplifier {
public:
    PartSimplifier(std::vector<Face>& faces, std::vector<glm::dvec3>& positions,
                   const std::vector<std::size_t>& members,
                   const std::vector<std::vector<std::size_t>>& facesOfVertex, glm::dvec3 centre,
                   double radius, double epsilon, const BillboardCloudOptions& options)
        : faces_(faces),
          positions_(positions),
          members_(members),
          facesOfVertex_(facesOfVertex),
          centre_(centre),
          radius_(radius),
          epsilon_(epsilon),
          options_(options) {
        distanceCells_ = std::clamp(int(std::ceil(2.0 * radius / epsilon)), 8, 96);
        cellSize_ = 2.0 * radius / double(distanceCells_);
        for (int e = 0; e < kElevations; ++e) {
            for (int a = 0; a < kAzimuths; ++a) {
                directions_.push_back(direction((a + 0.5) * 2.0 * kPi / kAzimuths,
                                                (e + 0.5) * 0.5 * kPi / kElevations));
            }
        }
        density_.assign(directions_.size() * std::size_t(distanceCells_), 0.0);
        for (std::size_t face : members_) {
            if (faces_[face].plane < 0) {
                accumulate(face, 1.0);
            }
        }
    }

    // Greedy plane selection until every member face is simplified. Returns false when
    // more than `planeLimit` planes would be needed (epsilon too small for the budget).
    bool run(std::vector<Plane>& planes, int planeLimit) {
        std::size_t remaining = 0;
        for (std::size_t face : members_) {
            remaining += faces_[face].plane < 0 ? 1 : 0;
        }
        while (remaining > 0) {
            if (int(planes.size()) >= planeLimit) {
                return false;
            }
            Plane plane = pickPlane();
            std::vector<std::size_t> simplified = validFaces(plane.normal, plane.offset);
            if (simplified.empty()) {
                // §3.3.2 fail-safe: the discretised validity gave a false positive; take
                // the largest remaining face's own plane.
                std::size_t largest = members_.front();
                double area = -1.0;
                for (std::size_t face : members_) {
                    if (faces_[face].plane < 0 && faces_[face].area > area) {
                        area = faces_[face].area;
                        largest = face;
                    }
                }
                plane.normal = faces_[largest].normal.z < 0.0 ? -faces_[largest].normal
                                                              : faces_[largest].normal;
                plane.offset = glm::dot(plane.normal, positions_[faces_[largest].vertices[0]]);
                simplified = validFaces(plane.normal, plane.offset);
                if (simplified.empty()) {
                    simplified = {largest};
                }
            }
            tweak(plane, simplified);
            const int index = int(planes.size());
            for (std::size_t face : simplified) {
                accumulate(face, -1.0);
                faces_[face].plane = index;
            }
            remaining -= simplified.size();
            weld(plane, simplified);
            plane.faces = simplified;
            plane.part = faces_[simplified.front()].part;
            planes.push_back(plane);
            if (plane.part == PlantPart::Branch) {
                addCardboard(planes, planes.size() - 1);
            }
            if (int(planes.size()) > planeLimit) {
                return false;  // a cardboard plane overshot the budget
            }
        }
        return true;
    }

private:
    static constexpr int kAzimuths = 24;
    static constexpr int kElevations = 6;

    // §3.3.5: D scaled down linearly from the cutoff to the maximum at horizontal planes
    // (normal elevation 90°).
    double horizontalFactor(const glm::dvec3& normal) const {
        const double elevation = std::asin(std::min(1.0, std::abs(normal.z)));
        const double cutoff = options_.horizontalCutoff;
        if (elevation <= cutoff) {
            return 1.0;
        }
        return 1.0 - options_.horizontalPenalty * (elevation - cutoff) / (0.5 * kPi - cutoff);
    }

    // §3.3.1 angular contribution: the unprojected area weighted linearly by the angle
    // between face and plane (1 when parallel, 0 at 90°); two-sided faces.
    double contribution(std::size_t face, const glm::dvec3& normal) const {
        const double cosine = std::min(1.0, std::abs(glm::dot(faces_[face].normal, normal)));
        return faces_[face].area * std::max(0.0, 1.0 - std::acos(cosine) / (0.5 * kPi));
    }

    bool valid(std::size_t face, const glm::dvec3& normal, double offset) const {
        for (std::uint32_t v : faces_[face].vertices) {
            if (std::abs(glm::dot(normal, positions_[v]) - offset) > epsilon_) {
                return false;
            }
        }
        return true;
    }

    // Adds (sign +1) or removes (−1) a face's density in every dual-space cell whose
    // plane is valid for it: per direction, the distance interval where all three
    // vertices lie within epsilon.
    void accumulate(std::size_t face, double sign) {
        const Face& f = faces_[face];
        for (std::size_t d = 0; d < directions_.size(); ++d) {
            const glm::dvec3& n = directions_[d];
            double low = std::numeric_limits<double>::lowest();
            double high = std::numeric_limits<double>::max();
            for (std::uint32_t v : f.vertices) {
                const double rho = glm::dot(n, positions_[v] - centre_);
                low = std::max(low, rho - epsilon_);
                high = std::min(high, rho + epsilon_);
            }
            if (low > high) {
                continue;
            }
            const int first = std::max(0, int(std::ceil((low + radius_) / cellSize_ - 0.5)));
            const int last =
                std::min(distanceCells_ - 1, int(std::floor((high + radius_) / cellSize_ - 0.5)));
            if (first > last) {
                continue;
            }
            const double value = sign * contribution(face, n) * horizontalFactor(n);
            for (int cell = first; cell <= last; ++cell) {
                density_[d * std::size_t(distanceCells_) + std::size_t(cell)] += value;
            }
        }
    }

    // Exact density of a plane over the remaining faces (penalised).
    double exactDensity(const glm::dvec3& normal, double offset) const {
        double sum = 0.0;
        for (std::size_t face : members_) {
            if (faces_[face].plane < 0 && valid(face, normal, offset)) {
                sum += contribution(face, normal);
            }
        }
        return sum * horizontalFactor(normal);
    }

    // The densest cell, refined by a 3×3×3 local search with halving steps (Décoret's
    // recursive cell subdivision, evaluated exactly instead of on a finer grid).
    Plane pickPlane() const {
        const auto best = std::max_element(density_.begin(), density_.end());
        const std::size_t index = std::size_t(best - density_.begin());
        const std::size_t d = index / std::size_t(distanceCells_);
        const int cell = int(index % std::size_t(distanceCells_));
        double azimuth = (double(d % kAzimuths) + 0.5) * 2.0 * kPi / kAzimuths;
        double elevation = (double(d / kAzimuths) + 0.5) * 0.5 * kPi / kElevations;
        double rho = -radius_ + (cell + 0.5) * cellSize_;
        double stepAzimuth = kPi / kAzimuths;
        double stepElevation = 0.25 * kPi / kElevations;
        double stepRho = 0.5 * cellSize_;
        glm::dvec3 normal = direction(azimuth, elevation);
        double score = exactDensity(normal, rho + glm::dot(normal, centre_));
        for (int round = 0; round < 3; ++round) {
            double bestAzimuth = azimuth, bestElevation = elevation, bestRho = rho;
            for (int i = -1; i <= 1; ++i) {
                for (int j = -1; j <= 1; ++j) {
                    for (int k = -1; k <= 1; ++k) {
                        if (i == 0 && j == 0 && k == 0) {
                            continue;
                        }
                        const double a = azimuth + i * stepAzimuth;
                        const double e = std::clamp(elevation + j * stepElevation, 0.0, 0.5 * kPi);
                        const double r = rho + k * stepRho;
                        const glm::dvec3 n = direction(a, e);
                        const double candidate = exactDensity(n, r + glm::dot(n, centre_));
                        if (candidate > score) {
                            score = candidate;
                            bestAzimuth = a;
                            bestElevation = e;
                            bestRho = r;
                        }
                    }
                }
            }
            azimuth = bestAzimuth;
            elevation = bestElevation;
            rho = bestRho;
            stepAzimuth *= 0.5;
            stepElevation *= 0.5;
            stepRho *= 0.5;
        }
        Plane plane;
        plane.normal = direction(azimuth, elevation);
        plane.offset = rho + glm::dot(plane.normal, centre_);
        return plane;
    }

    std::vector<std::size_t> validFaces(const glm::dvec3& normal, double offset) const {
        std::vector<std::size_t> result;
        for (std::size_t face : members_) {
            if (faces_[face].plane < 0 && valid(face, normal, offset)) {
                result.push_back(face);
            }
        }
        return result;
    }

    // §3.3.3 post-plane tweaking: area-weighted normal (faces flipped into the plane's
    // half-space first, so two-sided leaves do not cancel) through the area-weighted
    // centre; kept only if every simplified face stays valid.
    void tweak(Plane& plane, const std::vector<std::size_t>& simplified) const {
        glm::dvec3 normal(0.0);
        glm::dvec3 centre(0.0);
        double area = 0.0;
        for (std::size_t face : simplified) {
            const Face& f = faces_[face];
            normal += (glm::dot(f.normal, plane.normal) < 0.0 ? -f.normal : f.normal) * f.area;
            centre += (positions_[f.vertices[0]] + positions_[f.vertices[1]] +
                       positions_[f.vertices[2]]) *
                      (f.area / 3.0);
            area += f.area;
        }
        if (area <= 0.0 || glm::length(normal) <= 0.0) {
            return;
        }
        const glm::dvec3 tweakedNormal = glm::normalize(normal);
        const double tweakedOffset = glm::dot(tweakedNormal, centre / area);
        for (std::size_t face : simplified) {
            if (!valid(face, tweakedNormal, tweakedOffset)) {
                return;
            }
        }
        plane.normal = tweakedNormal;
        plane.offset = tweakedOffset;
    }

    // §3.3.4 vertex welding: a vertex's first projection moves it for good, so the
    // faces around it meet on later planes (gap 2ε → ε). Their density is updated.
    void weld(const Plane& plane, const std::vector<std::size_t>& simplified) {
        std::vector<std::uint32_t> moved;
        for (std::size_t face : simplified) {
            for (std::uint32_t v : faces_[face].vertices) {
                if (!welded_.count(v)) {
                    welded_.insert(v);
                    moved.push_back(v);
                }
            }
        }
        std::vector<std::size_t> affected;
        for (std::uint32_t v : moved) {
            for (std::size_t face : facesOfVertex_[v]) {
                if (faces_[face].plane < 0 &&
                    faces_[face].part == faces_[simplified.front()].part) {
                    affected.push_back(face);
                }
            }
        }
        std::sort(affected.begin(), affected.end());
        affected.erase(std::unique(affected.begin(), affected.end()), affected.end());
        for (std::size_t face : affected) {
            accumulate(face, -1.0);
        }
        for (std::uint32_t v : moved) {
            positions_[v] -= plane.normal * (glm::dot(plane.normal, positions_[v]) - plane.offset);
        }
        for (std::size_t face : affected) {
            accumulate(face, 1.0);
        }
    }

    // §3.3.6 cardboard: two planes perpendicular to a branch plane through the centroid
    // of its faces, parallel to the edges of their bounding rectangle; the one whose
    // covered area (of the primary's faces valid for it) relative to the primary's is
    // larger is added when above the threshold.
    void addCardboard(std::vector<Plane>& planes, std::size_t primaryIndex) {
        const Plane& primary = planes[primaryIndex];
        glm::dvec3 centroid(0.0);
        double area = 0.0;
        for (std::size_t face : primary.faces) {
            const Face& f = faces_[face];
            centroid += (positions_[f.vertices[0]] + positions_[f.vertices[1]] +
                         positions_[f.vertices[2]]) *
                        (f.area / 3.0);
            area += f.area;
        }
        if (area <= 0.0) {
            return;
        }
        centroid /= area;
        // Rectangle axes: principal direction of the face centres within the plane.
        const glm::dvec3 helper =
            std::abs(primary.normal.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
        glm::dvec3 u = glm::normalize(glm::cross(helper, primary.normal));
        glm::dvec3 v = glm::cross(primary.normal, u);
        double suu = 0, suv = 0, svv = 0;
        for (std::size_t face : primary.faces) {
            const Face& f = faces_[face];
            const glm::dvec3 c = (positions_[f.vertices[0]] + positions_[f.vertices[1]] +
                                  positions_[f.vertices[2]]) /
                                     3.0 -
                                 centroid;
            const double x = glm::dot(c, u), y = glm::dot(c, v);
            suu += f.area * x * x;
            suv += f.area * x * y;
            svv += f.area * y * y;
        }
        const double angle = 0.5 * std::atan2(2.0 * suv, suu - svv);
        const glm::dvec3 major = u * std::cos(angle) + v * std::sin(angle);
        const glm::dvec3 minor = glm::cross(primary.normal, major);
        double primaryCoverage = 0.0;
        for (std::size_t face : primary.faces) {
            primaryCoverage +=
                faces_[face].area * std::abs(glm::dot(faces_[face].normal, primary.normal));
        }
        Plane best;
        double bestCoverage = 0.0;
        for (const glm::dvec3& normal : {minor, major}) {
            Plane candidate;
            candidate.normal = normal;
            candidate.offset = glm::dot(normal, centroid);
            double covered = 0.0;
            for (std::size_t face : primary.faces) {
                if (valid(face, candidate.normal, candidate.offset)) {
                    candidate.faces.push_back(face);
                    covered += faces_[face].area * std::abs(glm::dot(faces_[face].normal, normal));
                }
            }
            const double coverage = primaryCoverage > 0.0 ? covered / primaryCoverage : 0.0;
            if (coverage > bestCoverage && !candidate.faces.empty()) {
                bestCoverage = coverage;
                best = candidate;
            }
        }
        if (bestCoverage >= options_.cardboardCoverage) {
            best.part = PlantPart::Branch;
            best.cardboard = true;
            planes.push_back(best);
        }
    }

    std::vector<Face>& faces_;
    std::vector<glm::dvec3>& positions_;
    const std::vector<std::size_t>& members_;
    const std::vector<std::vector<std::size_t>>& facesOfVertex_;
    glm::dvec3 centre_;
    double radius_;
    double epsilon_;
    const BillboardCloudOptions& options_;
    int distanceCells_ = 0;
    double cellSize_ = 0.0;
    std::vector<glm::dvec3> directions_;
    std::vector<double> density_;
    std::unordered_set<std::uint32_t> welded_;
};

struct Tile {
    int x = 0, y = 0, width = 0, height = 0;
    RasterImage image;
};

// §3.3.7: render at twice the tile size, then each texel's alpha is binary: opaque
// when at least `threshold` of its 2×2 samples are covered (colour: their mean).
RasterImage bakeTile(const PlantModel& model, const OrthographicView& view, int width, int height,
                     const std::vector<std::vector<bool>>& mask, float threshold) {
    const RasterImage fine =
        PlantRasterizer::renderOrthographic(model, view, 2 * width, 2 * height, &mask);
    RasterImage tile;
    tile.width = width;
    tile.height = height;
    tile.rgba.assign(std::size_t(width) * std::size_t(height) * 4, 0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            int covered = 0;
            std::array<int, 3> sum{0, 0, 0};
            for (int sy = 0; sy < 2; ++sy) {
                for (int sx = 0; sx < 2; ++sx) {
                    const std::uint8_t* p =
                        &fine.rgba[(std::size_t(2 * y + sy) * std::size_t(2 * width) +
                                    std::size_t(2 * x + sx)) *
                                   4];
                    if (p[3] != 0) {
                        ++covered;
                        for (int c = 0; c < 3; ++c) {
                            sum[std::size_t(c)] += p[c];
                        }
                    }
                }
            }
            std::uint8_t* out =
                &tile.rgba[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4];
            if (covered > 0) {
                for (int c = 0; c < 3; ++c) {
                    out[c] = std::uint8_t(sum[std::size_t(c)] / covered);
                }
            }
            out[3] = float(covered) / 4.0f >= threshold ? 255 : 0;
        }
    }
    return tile;
}

// Faces and positions over all meshes (vertex indices offset per mesh, so welding acts
// on the vertices the meshes share between their triangles).
struct SourceFaces {
    std::vector<Face> faces;
    std::vector<glm::dvec3> positions;
    std::vector<std::vector<std::size_t>> facesOfVertex;
    std::size_t triangleCount = 0;
};

SourceFaces collectFaces(const PlantModel& model) {
    SourceFaces source;
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        const PlantMesh& mesh = model.meshes[m];
        const std::uint32_t base = std::uint32_t(source.positions.size());
        for (const glm::vec3& p : mesh.positions) {
            source.positions.emplace_back(p);
        }
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            Face face;
            face.vertices = {base + mesh.indices[t], base + mesh.indices[t + 1],
                             base + mesh.indices[t + 2]};
            face.mesh = m;
            face.triangle = t / 3;
            face.source = source.triangleCount++;
            face.part = mesh.part;
            source.faces.push_back(face);
        }
    }
    source.facesOfVertex.resize(source.positions.size());
    for (std::size_t f = 0; f < source.faces.size(); ++f) {
        for (std::uint32_t v : source.faces[f].vertices) {
            source.facesOfVertex[v].push_back(f);
        }
    }
    return source;
}

// The planes of one level (seed 003 §3.3.8: on the finer level's welded geometry).
struct LevelPlanes {
    double epsilon = 0.0;
    std::vector<Plane> planes;
    std::vector<glm::dvec3> positions;  // welded
    std::vector<Face> faces;            // with their planes
};

// One simplification of both parts at `epsilon`; false when more than `limit` planes
// would be needed.
bool simplifyParts(const SourceFaces& source, const glm::dvec3& centre, double radius, int limit,
                   const BillboardCloudOptions& options, LevelPlanes& level) {
    for (PlantPart part : {PlantPart::Leaf, PlantPart::Branch}) {
        std::vector<std::size_t> members;
        for (std::size_t f = 0; f < level.faces.size(); ++f) {
            Face& face = level.faces[f];
            const std::vector<glm::dvec3>& p = level.positions;
            const glm::dvec3 cross = glm::cross(p[face.vertices[1]] - p[face.vertices[0]],
                                                p[face.vertices[2]] - p[face.vertices[0]]);
            face.area = 0.5 * glm::length(cross);
            face.normal = face.area > 0.0 ? cross / (2.0 * face.area) : glm::dvec3(0.0, 0.0, 1.0);
            if (face.part == part && face.area > 1e-14) {
                members.push_back(f);
            }
        }
        if (members.empty()) {
            continue;
        }
        PartSimplifier simplifier(level.faces, level.positions, members, source.facesOfVertex,
                                  centre, radius, level.epsilon, options);
        if (!simplifier.run(level.planes, limit)) {
            return false;
        }
    }
    return true;
}

// Up to 16 attempts at a plane count in [minimumPlanes, limit]: epsilon grows by 1.3 when
// there are too many planes and shrinks by 1.25 when there are too few.
std::optional<LevelPlanes> findLevelPlanes(const SourceFaces& source,
                                           const std::vector<glm::dvec3>& input,
                                           const glm::dvec3& centre, double radius, double epsilon,
                                           int limit, const BillboardCloudOptions& options) {
    LevelPlanes level;
    level.epsilon = epsilon;
    for (int attempt = 0; attempt < 16; ++attempt) {
        level.positions = input;
        level.faces = source.faces;
        level.planes.clear();
        const bool complete = simplifyParts(source, centre, radius, limit, options, level);
        const int count = int(level.planes.size());
        if (!complete) {
            level.epsilon *= 1.3;  // too many planes: coarser bound
        } else if (count < options.minimumPlanes && attempt < 15) {
            level.epsilon /= 1.25;
        } else {
            return level;
        }
    }
    return std::nullopt;
}

// A plane's rectangle: axes along the principal direction of its faces' (original)
// vertices in the plane, and the bounds of those vertices.
struct PlaneRectangle {
    glm::dvec3 origin{0.0}, right{0.0}, up{0.0};
    glm::dvec2 low{std::numeric_limits<double>::max()};
    glm::dvec2 high{std::numeric_limits<double>::lowest()};
};

PlaneRectangle planeRectangle(const Plane& plane, const std::vector<Face>& faces,
                              const std::vector<glm::dvec3>& original) {
    PlaneRectangle r;
    const glm::dvec3 helper =
        std::abs(plane.normal.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    glm::dvec3 u = glm::normalize(glm::cross(helper, plane.normal));
    glm::dvec3 v = glm::cross(plane.normal, u);
    r.origin = plane.normal * plane.offset;
    double suu = 0, suv = 0, svv = 0;
    glm::dvec2 mean(0.0);
    std::size_t count = 0;
    for (std::size_t face : plane.faces) {
        for (std::uint32_t vertex : faces[face].vertices) {
            mean += glm::dvec2(glm::dot(original[vertex] - r.origin, u),
                               glm::dot(original[vertex] - r.origin, v));
            ++count;
        }
    }
    mean /= double(std::max<std::size_t>(count, 1));
    for (std::size_t face : plane.faces) {
        for (std::uint32_t vertex : faces[face].vertices) {
            const double x = glm::dot(original[vertex] - r.origin, u) - mean.x;
            const double y = glm::dot(original[vertex] - r.origin, v) - mean.y;
            suu += x * x;
            suv += x * y;
            svv += y * y;
        }
    }
    const double angle = 0.5 * std::atan2(2.0 * suv, suu - svv);
    r.right = u * std::cos(angle) + v * std::sin(angle);
    r.up = glm::cross(plane.normal, r.right);
    for (std::size_t face : plane.faces) {
        for (std::uint32_t vertex : faces[face].vertices) {
            const glm::dvec2 p(glm::dot(original[vertex] - r.origin, r.right),
                               glm::dot(original[vertex] - r.origin, r.up));
            r.low = glm::min(r.low, p);
            r.high = glm::max(r.high, p);
        }
    }
    return r;
}

// The source triangles a plane's texture shows: its own faces and (§3.3.7, not for
// cardboard) every face of the part valid for the plane that falls inside its rectangle,
// which makes the foliage look more solid.
std::vector<std::vector<bool>> planeMask(const PlantModel& model, const Plane& plane,
                                         const PlaneRectangle& r, const LevelPlanes& level,
                                         const std::vector<glm::dvec3>& original) {
    std::vector<std::vector<bool>> mask(model.meshes.size());
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        mask[m].assign(model.meshes[m].indices.size() / 3, false);
    }
    for (std::size_t face : plane.faces) {
        mask[level.faces[face].mesh][level.faces[face].triangle] = true;
    }
    if (plane.cardboard) {
        return mask;
    }
    for (const Face& face : level.faces) {
        if (face.part != plane.part || face.plane < 0 || mask[face.mesh][face.triangle]) {
            continue;
        }
        bool inside = true;
        for (std::uint32_t vertex : face.vertices) {
            const glm::dvec2 p(glm::dot(original[vertex] - r.origin, r.right),
                               glm::dot(original[vertex] - r.origin, r.up));
            inside = inside &&
                     std::abs(glm::dot(plane.normal, level.positions[vertex]) - plane.offset) <=
                         level.epsilon &&
                     p.x >= r.low.x && p.x <= r.high.x && p.y >= r.low.y && p.y <= r.high.y;
        }
        mask[face.mesh][face.triangle] = inside;
    }
    return mask;
}

// A plane's quad (original geometry, which the texture shows, bounded by its rectangle
// plus one texel of margin all round) and its baked tile.
BillboardQuad planeQuad(const PlantModel& model, const Plane& plane, const LevelPlanes& level,
                        const std::vector<glm::dvec3>& original, double texelsPerMetre,
                        const BillboardCloudOptions& options, Tile& tile) {
    PlaneRectangle r = planeRectangle(plane, level.faces, original);
    const std::vector<std::vector<bool>> mask = planeMask(model, plane, r, level, original);
    const int width = std::clamp(int(std::ceil((r.high.x - r.low.x) * texelsPerMetre)) + 2, 4, 512);
    const int height =
        std::clamp(int(std::ceil((r.high.y - r.low.y) * texelsPerMetre)) + 2, 4, 512);
    const glm::dvec2 pad((r.high.x - r.low.x) / double(width - 2),
                         (r.high.y - r.low.y) / double(height - 2));
    r.low -= pad;
    r.high += pad;
    OrthographicView view;
    view.origin = glm::vec3(r.origin);
    view.right = glm::vec3(r.right);
    view.up = glm::vec3(r.up);
    view.minimum = glm::vec2(r.low);
    view.maximum = glm::vec2(r.high);
    view.lit = false;
    tile.width = width;
    tile.height = height;
    tile.image = bakeTile(model, view, width, height, mask, options.alphaThreshold);
    BillboardQuad quad;
    const std::array<glm::dvec2, 4> corners = {r.low, glm::dvec2(r.high.x, r.low.y), r.high,
                                               glm::dvec2(r.low.x, r.high.y)};
    for (std::size_t c = 0; c < 4; ++c) {
        quad.corners[c] = glm::vec3(r.origin + r.right * corners[c].x + r.up * corners[c].y);
    }
    quad.normal = glm::vec3(plane.normal);
    quad.part = plane.part;
    quad.cardboard = plane.cardboard;
    return quad;
}

// Shelf packing, tallest tiles first, into an atlas about as wide as the square root of
// the tiles' area (so coarse texel densities give small atlases), at most 1024 texels
// unless one tile is wider; the quads get their atlas coordinates.
void packAtlas(std::vector<Tile>& tiles, BillboardLevel& level) {
    std::vector<std::size_t> order(tiles.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return tiles[a].height > tiles[b].height;
    });
    double tileArea = 0.0;
    int widestTile = 4;
    for (const Tile& tile : tiles) {
        tileArea += double(tile.width) * double(tile.height);
        widestTile = std::max(widestTile, tile.width);
    }
    int atlasWidth =
        std::min(1024, (static_cast<int>(std::ceil(1.15 * std::sqrt(tileArea))) + 3) / 4 * 4);
    atlasWidth = std::max(atlasWidth, widestTile);
    int x = 0, y = 0, shelf = 0;
    for (std::size_t i : order) {
        if (x + tiles[i].width > atlasWidth) {
            x = 0;
            y += shelf;
            shelf = 0;
        }
        tiles[i].x = x;
        tiles[i].y = y;
        x += tiles[i].width;
        shelf = std::max(shelf, tiles[i].height);
    }
    const int atlasHeight = std::max(4, (y + shelf + 3) / 4 * 4);
    level.atlas.width = atlasWidth;
    level.atlas.height = atlasHeight;
    level.atlas.rgba.assign(std::size_t(atlasWidth) * std::size_t(atlasHeight) * 4, 0);
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        const Tile& tile = tiles[i];
        for (int row = 0; row < tile.height; ++row) {
            std::copy_n(tile.image.rgba.begin() +
                            std::ptrdiff_t(std::size_t(row) * std::size_t(tile.width) * 4),
                        std::size_t(tile.width) * 4,
                        level.atlas.rgba.begin() +
                            std::ptrdiff_t((std::size_t(tile.y + row) * std::size_t(atlasWidth) +
                                            std::size_t(tile.x)) *
                                           4));
        }
        const float u0 = float(tile.x) / float(atlasWidth);
        const float u1 = float(tile.x + tile.width) / float(atlasWidth);
        const float v0 = float(tile.y) / float(atlasHeight);
        const float v1 = float(tile.y + tile.height) / float(atlasHeight);
        // Corner 0 is the rectangle's low corner: the tile's bottom-left texel.
        level.quads[i].atlasUvs[0] = {u0, v1};
        level.quads[i].atlasUvs[1] = {u1, v1};
        level.quads[i].atlasUvs[2] = {u1, v0};
        level.quads[i].atlasUvs[3] = {u0, v0};
    }
}

Status checkOptions(const PlantModel& model, const BillboardCloudOptions& options) {
    if (options.epsilons.empty() || options.minimumPlanes < 1 ||
        options.maximumPlanes < options.minimumPlanes || options.texelsAcrossModel < 16 ||
        options.texelsAcrossModel > 4096) {
        return Error{"billboard cloud of '" + model.name +
                     "': needs epsilons, 1 <= minimumPlanes <= maximumPlanes and texelsAcrossModel "
                     "in [16, 4096]"};
    }
    if (options.epsilons.size() > kMaxBillboardLevels) {
        return Error{"billboard cloud of '" + model.name +
                     "': " + std::to_string(options.epsilons.size()) + " epsilons, at most " +
                     std::to_string(kMaxBillboardLevels) + " levels are supported"};
    }
    for (float epsilon : options.epsilons) {
        if (!(epsilon > 0.0f && epsilon < 1.0f)) {
            return Error{"billboard cloud of '" + model.name +
                         "': epsilons must lie in (0, 1) of the bounding radius"};
        }
    }
    return Status::success();
}

}  // namespace

Result<BillboardCloud> BillboardCloudBuilder::build(const PlantModel& model,
                                                    const BillboardCloudOptions& options) {
    if (Status valid = checkOptions(model, options); !valid) {
        return valid.error();
    }
    const SourceFaces source = collectFaces(model);
    if (source.faces.empty()) {
        return Error{"billboard cloud of '" + model.name + "': the model has no triangles"};
    }
    const glm::dvec3 minimum(model.boundsMinimum());
    const glm::dvec3 maximum(model.boundsMaximum());
    const glm::dvec3 centre = 0.5 * (minimum + maximum);
    const double radius = std::max(1e-3, 0.5 * glm::length(maximum - minimum));
    const double texelsPerMetre = double(options.texelsAcrossModel) / (2.0 * radius);

    BillboardCloud cloud;
    std::vector<glm::dvec3> input = source.positions;  // level k: level k−1's welded geometry
    int previousPlanes = std::numeric_limits<int>::max();
    for (float fraction : options.epsilons) {
        const int limit = std::min(options.maximumPlanes, previousPlanes - 1);
        if (limit < options.minimumPlanes) {
            break;  // no coarser level fits the budget
        }
        std::optional<LevelPlanes> planes = findLevelPlanes(
            source, input, centre, radius, double(fraction) * radius, limit, options);
        if (!planes) {
            break;
        }
        BillboardLevel level;
        level.epsilon = float(planes->epsilon);
        level.trianglePlane.assign(source.triangleCount, -1);
        for (const Face& face : planes->faces) {
            level.trianglePlane[face.source] = face.plane;
        }
        std::vector<Tile> tiles(planes->planes.size());
        for (std::size_t i = 0; i < planes->planes.size(); ++i) {
            level.quads.push_back(planeQuad(model, planes->planes[i], *planes, source.positions,
                                            texelsPerMetre, options, tiles[i]));
        }
        packAtlas(tiles, level);
        previousPlanes = int(planes->planes.size());
        input = std::move(planes->positions);
        cloud.levels.push_back(std::move(level));
    }
    if (cloud.levels.empty()) {
        return Error{"billboard cloud of '" + model.name + "': no level fits " +
                     std::to_string(options.minimumPlanes) + " to " +
                     std::to_string(options.maximumPlanes) + " planes"};
    }
    return cloud;
}

PlantModel BillboardCloudBuilder::levelModel(const BillboardLevel& level, const std::string& name) {
    PlantModel model;
    model.name = name;
    PlantMaterial material;
    material.name = "billboards";
    material.baseColorTexture = level.atlas;
    material.alphaMasked = true;
    model.materials.push_back(material);
    for (PlantPart part : {PlantPart::Leaf, PlantPart::Branch}) {
        PlantMesh mesh;
        mesh.part = part;
        mesh.material = 0;
        mesh.name = part == PlantPart::Leaf ? "leaf billboards" : "branch billboards";
        for (const BillboardQuad& quad : level.quads) {
            if (quad.part != part) {
                continue;
            }
            const std::uint32_t first = std::uint32_t(mesh.positions.size());
            for (int c = 0; c < 4; ++c) {
                mesh.positions.push_back(quad.corners[c]);
                mesh.normals.push_back(quad.normal);
                mesh.uvs.push_back(quad.atlasUvs[c]);
            }
            mesh.indices.insert(mesh.indices.end(),
                                {first, first + 1, first + 2, first, first + 2, first + 3});
        }
        if (!mesh.indices.empty()) {
            model.meshes.push_back(std::move(mesh));
        }
    }
    return model;
}

}  // namespace sylva
