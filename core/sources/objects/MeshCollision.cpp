#include "sylva/core/sources/objects/MeshCollision.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {

namespace {

constexpr double kMinimumCell = 2.0;  // metres
constexpr int kMaximumCells = 128;    // per side of a tile's grid

// The nearest front-face crossing along a segment so far (fraction in [0, 1]).
struct Nearest {
    double fraction = std::numeric_limits<double>::infinity();
    glm::dvec3 normal{0.0};  // unnormalized, in the frame of the test that set it
};

// Möller and Trumbore, "Fast, minimum storage ray/triangle intersection" (1997), on the
// segment start + t·direction, t in [0, 1], in double. A crossing counts only from the
// front: dot(direction, n) < 0 with n the counter-clockwise geometric normal.
// Keeps the nearest in `nearest`.
void crossTriangle(const glm::dvec3& start, const glm::dvec3& direction, const glm::dvec3& v0,
                   const glm::dvec3& v1, const glm::dvec3& v2, Nearest& nearest) {
    const glm::dvec3 edge1 = v1 - v0;
    const glm::dvec3 edge2 = v2 - v0;
    const glm::dvec3 normal = glm::cross(edge1, edge2);
    if (glm::dot(direction, normal) >= 0.0) {
        return;  // from behind, or along the plane
    }
    const glm::dvec3 p = glm::cross(direction, edge2);
    const double determinant = glm::dot(edge1, p);
    if (determinant == 0.0) {
        return;
    }
    const double inverse = 1.0 / determinant;
    const glm::dvec3 s = start - v0;
    const double u = glm::dot(s, p) * inverse;
    if (u < 0.0 || u > 1.0) {
        return;
    }
    const glm::dvec3 q = glm::cross(s, edge1);
    const double v = glm::dot(direction, q) * inverse;
    if (v < 0.0 || u + v > 1.0) {
        return;
    }
    const double t = glm::dot(edge2, q) * inverse;
    if (t >= 0.0 && t <= 1.0 && t < nearest.fraction) {
        nearest.fraction = t;
        nearest.normal = normal;
    }
}

// Whether the segment passes within `radius` of `center`.
bool segmentNearSphere(const glm::dvec3& start, const glm::dvec3& end, const glm::dvec3& center,
                       double radius) {
    const glm::dvec3 direction = end - start;
    const double length2 = glm::dot(direction, direction);
    const double t =
        length2 > 0.0 ? std::clamp(glm::dot(center - start, direction) / length2, 0.0, 1.0) : 0.0;
    const glm::dvec3 closest = start + direction * t;
    return glm::dot(closest - center, closest - center) <= radius * radius;
}

glm::dvec3 vertexOf(const MeshGeometry& geometry, std::uint32_t index) {
    return glm::dvec3(geometry.vertices[index].position);
}

// The placed models of `tile`: the segment in each part's frame (an affine map keeps
// fractions), placements culled by their bounding spheres (every articulation inside).
void crossPlacements(const MeshTile& tile, const glm::dvec3& start, const glm::dvec3& end,
                     Nearest& nearest) {
    if (!tile.model) {
        return;
    }
    const glm::dvec3 direction = end - start;
    const MeshModel& model = *tile.model;
    for (const ModelPlacement& placement : tile.placements) {
        const double scale =
            std::max({glm::length(placement.axes[0]), glm::length(placement.axes[1]),
                      glm::length(placement.axes[2])});
        if (!segmentNearSphere(start, end, placement.position + placement.axes * model.boundsCenter,
                               model.boundsRadius * scale)) {
            continue;
        }
        const std::vector<glm::dmat4> transforms = model.partTransforms(placement.partAngles);
        for (std::size_t p = 0; p < model.parts.size(); ++p) {
            const glm::dmat3 linear = placement.axes * glm::dmat3(transforms[p]);
            const double determinant = glm::determinant(linear);
            if (determinant == 0.0) {
                continue;
            }
            const glm::dvec3 translation =
                placement.position + placement.axes * glm::dvec3(transforms[p][3]);
            const glm::dmat3 inverse = glm::inverse(linear);
            const glm::dvec3 a = inverse * (start - translation);
            const glm::dvec3 d = inverse * direction;
            Nearest part;
            part.fraction = nearest.fraction;
            const MeshGeometry& geometry = model.parts[p].geometry;
            for (std::size_t i = 0; i + 2 < geometry.indices.size(); i += 3) {
                crossTriangle(a, d, vertexOf(geometry, geometry.indices[i]),
                              vertexOf(geometry, geometry.indices[i + 1]),
                              vertexOf(geometry, geometry.indices[i + 2]), part);
            }
            if (part.fraction < nearest.fraction) {
                // Outward normals map by the inverse transpose, mirrored or not (the
                // winding flips in ECEF under a mirroring placement, the outside does not:
                // the front test is the part frame's).
                nearest.fraction = part.fraction;
                nearest.normal = glm::transpose(inverse) * part.normal;
            }
        }
    }
}

}  // namespace

// A grid over the tile's local east/north plane (at its origin) holding, per cell, the
// static triangles whose plan bounds touch it (compressed rows: cellStart[c] ..
// cellStart[c + 1] in `triangles`).
struct MeshCollision::TileIndex {
    glm::dvec3 east{1, 0, 0}, north{0, 1, 0};
    glm::dvec2 minimum{0.0};
    double cellSize = kMinimumCell;
    int columns = 0, rows = 0;
    std::vector<std::uint32_t> cellStart;
    std::vector<std::uint32_t> triangles;

    glm::dvec2 plan(const glm::dvec3& offset) const {
        return {glm::dot(offset, east), glm::dot(offset, north)};
    }
    // Cells covering plan bounds [low, high], clamped to the grid.
    glm::ivec4 cellRange(const glm::dvec2& low, const glm::dvec2& high) const {
        const auto cell = [&](double value, double origin, int count) {
            return std::clamp(int(std::floor((value - origin) / cellSize)), 0, count - 1);
        };
        return {cell(low.x, minimum.x, columns), cell(low.y, minimum.y, rows),
                cell(high.x, minimum.x, columns), cell(high.y, minimum.y, rows)};
    }
};

MeshCollision::MeshCollision() = default;
MeshCollision::~MeshCollision() = default;
MeshCollision::MeshCollision(MeshCollision&&) noexcept = default;
MeshCollision& MeshCollision::operator=(MeshCollision&&) noexcept = default;

void MeshCollision::setTiles(const std::vector<std::shared_ptr<const MeshTile>>& tiles) {
    tiles_ = tiles;
    std::erase_if(indexes_, [&](const auto& entry) {
        return std::none_of(tiles_.begin(), tiles_.end(),
                            [&](const auto& tile) { return tile.get() == entry.first; });
    });
}

const MeshCollision::TileIndex& MeshCollision::indexOf(
    const std::shared_ptr<const MeshTile>& tile) const {
    std::unique_ptr<TileIndex>& slot = indexes_[tile.get()];
    if (slot) {
        return *slot;
    }
    slot = std::make_unique<TileIndex>();
    TileIndex& index = *slot;
    const Geodetic at = Ellipsoid::toGeodetic(tile->origin);
    const glm::dmat3 frame = Ellipsoid::localFrame(at.latitude, at.longitude);
    index.east = frame[0];
    index.north = frame[1];
    const MeshGeometry& geometry = tile->geometry;
    const std::size_t count = geometry.indices.size() / 3;
    // Plan bounds of every triangle, then of the tile.
    std::vector<glm::dvec4> bounds(count);
    glm::dvec2 low(std::numeric_limits<double>::infinity()), high(-low);
    for (std::size_t i = 0; i < count; ++i) {
        glm::dvec2 a(std::numeric_limits<double>::infinity()), b(-a);
        for (int corner = 0; corner < 3; ++corner) {
            const glm::dvec2 p = index.plan(vertexOf(geometry, geometry.indices[3 * i + corner]));
            a = glm::min(a, p);
            b = glm::max(b, p);
        }
        bounds[i] = {a.x, a.y, b.x, b.y};
        low = glm::min(low, a);
        high = glm::max(high, b);
    }
    if (count == 0) {
        return index;
    }
    const double extent = std::max(high.x - low.x, high.y - low.y);
    index.cellSize = std::max(kMinimumCell, extent / kMaximumCells);
    index.minimum = low;
    index.columns = std::max(1, int(std::ceil((high.x - low.x) / index.cellSize)));
    index.rows = std::max(1, int(std::ceil((high.y - low.y) / index.cellSize)));
    // Two passes over the triangles' cells: counts, then the compressed rows.
    index.cellStart.assign(std::size_t(index.columns) * index.rows + 1, 0);
    const auto forCells = [&](std::size_t i, auto&& visit) {
        const glm::ivec4 r =
            index.cellRange({bounds[i].x, bounds[i].y}, {bounds[i].z, bounds[i].w});
        for (int y = r.y; y <= r.w; ++y) {
            for (int x = r.x; x <= r.z; ++x) {
                visit(std::size_t(y) * index.columns + x);
            }
        }
    };
    for (std::size_t i = 0; i < count; ++i) {
        forCells(i, [&](std::size_t cell) { ++index.cellStart[cell + 1]; });
    }
    for (std::size_t c = 1; c < index.cellStart.size(); ++c) {
        index.cellStart[c] += index.cellStart[c - 1];
    }
    index.triangles.resize(index.cellStart.back());
    std::vector<std::uint32_t> filled(index.cellStart.begin(), index.cellStart.end() - 1);
    for (std::size_t i = 0; i < count; ++i) {
        forCells(i, [&](std::size_t cell) { index.triangles[filled[cell]++] = std::uint32_t(i); });
    }
    return index;
}

std::optional<MeshHit> MeshCollision::firstHit(const glm::dvec3& start,
                                               const glm::dvec3& end) const {
    const glm::dvec3 direction = end - start;
    if (glm::dot(direction, direction) == 0.0) {
        return std::nullopt;
    }
    Nearest nearest;
    for (const std::shared_ptr<const MeshTile>& tile : tiles_) {
        if (tile->empty() ||
            !segmentNearSphere(start, end, tile->boundsCenter, tile->boundsRadius)) {
            continue;
        }
        // Static triangles: offsets from the tile's origin in ECEF orientation.
        if (!tile->geometry.empty()) {
            const TileIndex& index = indexOf(tile);
            const glm::dvec3 a = start - tile->origin;
            const glm::dvec2 pa = index.plan(a), pb = index.plan(end - tile->origin);
            const glm::ivec4 r = index.cellRange(glm::min(pa, pb), glm::max(pa, pb));
            const MeshGeometry& geometry = tile->geometry;
            for (int y = r.y; y <= r.w; ++y) {
                for (int x = r.x; x <= r.z; ++x) {
                    const std::size_t cell = std::size_t(y) * index.columns + x;
                    for (std::uint32_t k = index.cellStart[cell]; k < index.cellStart[cell + 1];
                         ++k) {
                        const std::uint32_t* corner = &geometry.indices[3 * index.triangles[k]];
                        crossTriangle(a, direction, vertexOf(geometry, corner[0]),
                                      vertexOf(geometry, corner[1]), vertexOf(geometry, corner[2]),
                                      nearest);
                    }
                }
            }
        }
        crossPlacements(*tile, start, end, nearest);
    }
    if (!std::isfinite(nearest.fraction)) {
        return std::nullopt;
    }
    return MeshHit{nearest.fraction, glm::normalize(nearest.normal)};
}

}  // namespace sylva
