// Seed 000 ch. 5.2–5.3: the displacement of each billboard plane, generated from the
// triangles the billboard-cloud level assigned to that plane (its simplified faces).
#include "sylva/core/plantlod/DisplacedBillboardBuilder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace sylva {

namespace {

constexpr float kEmpty = std::numeric_limits<float>::infinity();

// The atlas texel rectangle of a quad and the map from texel centres to the plane.
struct QuadTexels {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) × [y0, y1)
    glm::vec3 origin{0.0f}, edgeS{0.0f}, edgeT{0.0f}, normal{0.0f};
};

QuadTexels quadTexels(const BillboardQuad& quad, int width, int height) {
    QuadTexels q;
    q.x0 = int(std::lround(quad.atlasUvs[0].x * float(width)));
    q.x1 = int(std::lround(quad.atlasUvs[1].x * float(width)));
    q.y0 = int(std::lround(quad.atlasUvs[3].y * float(height)));
    q.y1 = int(std::lround(quad.atlasUvs[0].y * float(height)));
    q.origin = quad.corners[0];
    q.edgeS = quad.corners[1] - quad.corners[0];  // atlas +x
    q.edgeT = quad.corners[3] - quad.corners[0];  // atlas −y (rows from the top)
    q.normal = quad.normal;
    return q;
}

// Rasterizes one triangle (model frame) into its quad's texels: per covered texel centre
// the interpolated height widens the texel's (lowest, highest) interval.
void rasterizeTriangle(const QuadTexels& q, const glm::vec3 (&vertices)[3], int width,
                       std::vector<glm::vec2>& heights) {
    glm::vec2 texel[3];
    float h[3];
    const float sLength2 = glm::dot(q.edgeS, q.edgeS), tLength2 = glm::dot(q.edgeT, q.edgeT);
    for (int k = 0; k < 3; ++k) {
        const glm::vec3 offset = vertices[k] - q.origin;
        const float s = glm::dot(offset, q.edgeS) / sLength2;
        const float t = glm::dot(offset, q.edgeT) / tLength2;
        texel[k] =
            glm::vec2(float(q.x0) + s * float(q.x1 - q.x0), float(q.y1) - t * float(q.y1 - q.y0));
        h[k] = glm::dot(offset, q.normal);
    }
    const float area = (texel[1].x - texel[0].x) * (texel[2].y - texel[0].y) -
                       (texel[2].x - texel[0].x) * (texel[1].y - texel[0].y);
    if (std::abs(area) < 1e-9f) {
        return;  // edge-on to the plane: its texels come from the neighbours
    }
    const int xMin =
        std::max(q.x0, int(std::floor(std::min({texel[0].x, texel[1].x, texel[2].x}))));
    const int xMax =
        std::min(q.x1 - 1, int(std::ceil(std::max({texel[0].x, texel[1].x, texel[2].x}))));
    const int yMin =
        std::max(q.y0, int(std::floor(std::min({texel[0].y, texel[1].y, texel[2].y}))));
    const int yMax =
        std::min(q.y1 - 1, int(std::ceil(std::max({texel[0].y, texel[1].y, texel[2].y}))));
    for (int y = yMin; y <= yMax; ++y) {
        for (int x = xMin; x <= xMax; ++x) {
            const glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
            const auto edge = [&](int a, int b) {
                return ((texel[b].x - texel[a].x) * (p.y - texel[a].y) -
                        (p.x - texel[a].x) * (texel[b].y - texel[a].y)) /
                       area;
            };
            const float w0 = edge(1, 2), w1 = edge(2, 0), w2 = edge(0, 1);
            constexpr float kInside = -1e-4f;
            if (w0 < kInside || w1 < kInside || w2 < kInside) {
                continue;
            }
            const float height = w0 * h[0] + w1 * h[1] + w2 * h[2];
            glm::vec2& interval = heights[std::size_t(y) * width + x];
            if (interval.x == kEmpty) {
                interval = glm::vec2(height);
            } else {
                interval = glm::vec2(std::min(interval.x, height), std::max(interval.y, height));
            }
        }
    }
}

// Texels no triangle centre covers but whose atlas alpha is set (the atlas is
// supersampled) take a neighbour's interval within the same quad, a few rounds.
void fillFromNeighbours(const BillboardLevel& level, const std::vector<int>& owner,
                        std::vector<glm::vec2>& heights) {
    const int width = level.atlas.width, height = level.atlas.height;
    for (int round = 0; round < 4; ++round) {
        std::vector<glm::vec2> next = heights;
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const std::size_t i = std::size_t(y) * width + x;
                if (heights[i].x != kEmpty || owner[i] < 0 || level.atlas.rgba[i * 4 + 3] == 0) {
                    continue;
                }
                constexpr int kOffsets[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
                for (const auto& o : kOffsets) {
                    const int nx = x + o[0], ny = y + o[1];
                    if (nx < 0 || ny < 0 || nx >= width || ny >= height) {
                        continue;
                    }
                    const std::size_t n = std::size_t(ny) * width + nx;
                    if (owner[n] == owner[i] && heights[n].x != kEmpty) {
                        next[i] = heights[n];
                        break;
                    }
                }
            }
        }
        heights = std::move(next);
    }
}

// Heights are sampled at texel centres, so a sloped surface becomes a staircase of flat
// plates that a ray can slip between. Each texel's interval is widened half-way to each
// neighbour's (same quad, both set): the shell then spans the surface over the whole
// texel, and a continuous surface stays closed.
void widenToNeighbours(const std::vector<int>& owner, int width, int height,
                       std::vector<glm::vec2>& heights) {
    const std::vector<glm::vec2> sampled = heights;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * width + x;
            if (sampled[i].x == kEmpty) {
                continue;
            }
            constexpr int kOffsets[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
            for (const auto& o : kOffsets) {
                const int nx = x + o[0], ny = y + o[1];
                if (nx < 0 || ny < 0 || nx >= width || ny >= height) {
                    continue;
                }
                const std::size_t n = std::size_t(ny) * width + nx;
                if (owner[n] != owner[i] || sampled[n].x == kEmpty) {
                    continue;
                }
                heights[i].x = std::min(heights[i].x, 0.5f * (sampled[i].x + sampled[n].x));
                heights[i].y = std::max(heights[i].y, 0.5f * (sampled[i].y + sampled[n].y));
            }
        }
    }
}

}  // namespace

Result<DisplacementAtlas> DisplacedBillboardBuilder::build(const PlantModel& model,
                                                           const BillboardLevel& level) {
    std::size_t triangles = 0;
    for (const PlantMesh& mesh : model.meshes) {
        triangles += mesh.indices.size() / 3;
    }
    if (triangles != level.trianglePlane.size() || level.atlas.width <= 0 ||
        level.atlas.height <= 0) {
        return Error{"displaced billboards of '" + model.name +
                     "': the billboard level was not built from this model (" +
                     std::to_string(level.trianglePlane.size()) +
                     " triangles assigned, the model has " + std::to_string(triangles) + ")"};
    }
    DisplacementAtlas atlas;
    atlas.width = level.atlas.width;
    atlas.height = level.atlas.height;
    atlas.heights.assign(std::size_t(atlas.width) * atlas.height, glm::vec2(kEmpty));
    std::vector<int> owner(atlas.heights.size(), -1);
    std::vector<QuadTexels> quads;
    for (std::size_t k = 0; k < level.quads.size(); ++k) {
        quads.push_back(quadTexels(level.quads[k], atlas.width, atlas.height));
        const QuadTexels& q = quads.back();
        for (int y = std::max(q.y0, 0); y < std::min(q.y1, atlas.height); ++y) {
            for (int x = std::max(q.x0, 0); x < std::min(q.x1, atlas.width); ++x) {
                owner[std::size_t(y) * atlas.width + x] = int(k);
            }
        }
    }
    std::size_t source = 0;
    for (const PlantMesh& mesh : model.meshes) {
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3, ++source) {
            const int plane = level.trianglePlane[source];
            if (plane < 0 || std::size_t(plane) >= quads.size()) {
                continue;
            }
            const glm::vec3 vertices[3] = {mesh.positions[mesh.indices[t]],
                                           mesh.positions[mesh.indices[t + 1]],
                                           mesh.positions[mesh.indices[t + 2]]};
            rasterizeTriangle(quads[std::size_t(plane)], vertices, atlas.width, atlas.heights);
        }
    }
    fillFromNeighbours(level, owner, atlas.heights);
    widenToNeighbours(owner, atlas.width, atlas.height, atlas.heights);
    atlas.halfThickness.assign(level.quads.size(), 1e-3f);
    for (std::size_t i = 0; i < atlas.heights.size(); ++i) {
        glm::vec2& interval = atlas.heights[i];
        if (interval.x == kEmpty) {
            interval = glm::vec2(0.0f);
        } else if (owner[i] >= 0) {
            float& half = atlas.halfThickness[std::size_t(owner[i])];
            half = std::max({half, std::abs(interval.x), std::abs(interval.y)});
        }
    }
    return atlas;
}

}  // namespace sylva
