#include "sylva/core/plantlod/AmbientOcclusion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <random>

#include "sylva/core/base/WorkerPool.h"

namespace sylva {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

WorkerPool& poolOf(const AmbientOcclusionOptions& options) {
    return options.pool != nullptr ? *options.pool : WorkerPool::shared();
}

float luminance(const glm::vec3& c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

struct Box {
    glm::vec3 minimum{kInfinity};
    glm::vec3 maximum{-kInfinity};
    void add(const Box& b) {
        minimum = glm::min(minimum, b.minimum);
        maximum = glm::max(maximum, b.maximum);
    }
    void add(const glm::vec3& p) {
        minimum = glm::min(minimum, p);
        maximum = glm::max(maximum, p);
    }
};

enum class ItemKind : std::uint8_t { Ellipsoid, Line, Triangle };

struct Item {
    ItemKind kind;
    std::uint32_t index;  // into ellipsoids, lines or triangles
    Box box;
    float errorMinimum = 0.0f;
    float errorMaximum = kInfinity;
};

struct Triangle {
    glm::vec3 a, b, c;
    glm::vec2 ta, tb, tc;
    const PlantMaterial* material = nullptr;
    float albedo = 0.5f;
};

struct Hit {
    float t = kInfinity;
    glm::vec3 normal{0.0f};
    float albedo = 0.0f;
    std::uint32_t item = 0;  // index into TraceScene::items
};

// The scene the tracer sees: LoD primitives or source triangles, in a median-split BVH.
class TraceScene {
public:
    std::vector<LodEllipsoid> ellipsoids;
    std::vector<LodLine> lines;
    std::vector<Triangle> triangles;
    std::vector<Item> items;

    void build() {
        order_.resize(items.size());
        for (std::size_t i = 0; i < items.size(); ++i) {
            order_[i] = static_cast<std::uint32_t>(i);
        }
        nodes_.clear();
        if (!items.empty()) {
            buildNode(0, static_cast<std::uint32_t>(items.size()));
        }
    }

    // Nearest hit along o + t d, t in (0, tMax), among items visible at `error`.
    std::optional<Hit> trace(const glm::vec3& o, const glm::vec3& d, float error) const {
        if (nodes_.empty()) {
            return std::nullopt;
        }
        Hit best;
        const glm::vec3 inverse = 1.0f / d;
        std::uint32_t stack[64];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (!slab(node.box, o, inverse, best.t)) {
                continue;
            }
            if (node.count > 0) {
                for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
                    const Item& item = items[order_[i]];
                    if (item.errorMinimum <= error && error < item.errorMaximum) {
                        intersect(item, order_[i], o, d, best);
                    }
                }
            } else if (top + 2 <= 64) {
                stack[top++] = node.first;
                stack[top++] = node.first + 1;
            }
        }
        if (best.t == kInfinity) {
            return std::nullopt;
        }
        return best;
    }

    // True when p lies inside a (volumetric) primitive other than `self` visible at `error`.
    bool inside(const glm::vec3& p, float error, std::uint32_t selfItem) const {
        if (nodes_.empty()) {
            return false;
        }
        std::uint32_t stack[64];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (glm::any(glm::lessThan(p, node.box.minimum)) ||
                glm::any(glm::greaterThan(p, node.box.maximum))) {
                continue;
            }
            if (node.count > 0) {
                for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
                    const Item& item = items[order_[i]];
                    if (order_[i] == selfItem ||
                        !(item.errorMinimum <= error && error < item.errorMaximum)) {
                        continue;
                    }
                    if (contains(item, p)) {
                        return true;
                    }
                }
            } else if (top + 2 <= 64) {
                stack[top++] = node.first;
                stack[top++] = node.first + 1;
            }
        }
        return false;
    }

private:
    struct Node {
        Box box;
        std::uint32_t first = 0;  // leaf: first item in order_; inner: left child (right = +1)
        std::uint32_t count = 0;  // > 0 for leaves
    };

    void buildNode(std::uint32_t begin, std::uint32_t end) {
        const std::uint32_t index = static_cast<std::uint32_t>(nodes_.size());
        nodes_.emplace_back();
        Box box, centroids;
        for (std::uint32_t i = begin; i < end; ++i) {
            box.add(items[order_[i]].box);
            centroids.add(0.5f * (items[order_[i]].box.minimum + items[order_[i]].box.maximum));
        }
        nodes_[index].box = box;
        if (end - begin <= 4) {
            nodes_[index].first = begin;
            nodes_[index].count = end - begin;
            return;
        }
        const glm::vec3 extent = centroids.maximum - centroids.minimum;
        const int axis =
            extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const std::uint32_t mid = (begin + end) / 2;
        std::nth_element(
            order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
            [&](std::uint32_t a, std::uint32_t b) {
                const float ca = items[a].box.minimum[axis] + items[a].box.maximum[axis];
                const float cb = items[b].box.minimum[axis] + items[b].box.maximum[axis];
                return ca < cb || (ca == cb && a < b);
            });
        const std::uint32_t left = static_cast<std::uint32_t>(nodes_.size());
        nodes_[index].first = left;
        nodes_.emplace_back();  // reserve the pair so children are adjacent
        nodes_.emplace_back();
        buildInto(left, begin, mid);
        buildInto(left + 1, mid, end);
    }

    // Builds the subtree for [begin, end) into the pre-allocated node `slot`.
    void buildInto(std::uint32_t slot, std::uint32_t begin, std::uint32_t end) {
        const std::uint32_t built = static_cast<std::uint32_t>(nodes_.size());
        buildNode(begin, end);
        nodes_[slot] = nodes_[built];
        // The copied node keeps its children's indices; the slot at `built` is unused.
    }

    static bool slab(const Box& box, const glm::vec3& o, const glm::vec3& inverse, float tMax) {
        float t0 = 0.0f, t1 = tMax;
        for (int a = 0; a < 3; ++a) {
            float near = (box.minimum[a] - o[a]) * inverse[a];
            float far = (box.maximum[a] - o[a]) * inverse[a];
            if (near > far) {
                std::swap(near, far);
            }
            t0 = std::max(t0, near);
            t1 = std::min(t1, far);
            if (t0 > t1) {
                return false;
            }
        }
        return true;
    }

    void intersect(const Item& item, std::uint32_t itemIndex, const glm::vec3& o,
                   const glm::vec3& d, Hit& best) const {
        constexpr float kEpsilon = 1e-5f;
        if (item.kind == ItemKind::Ellipsoid) {
            const LodEllipsoid& e = ellipsoids[item.index];
            glm::vec3 p, g;
            for (int i = 0; i < 3; ++i) {
                const float r = std::max(e.radii[i], 1e-6f);
                p[i] = glm::dot(o - e.center, e.axes[i]) / r;
                g[i] = glm::dot(d, e.axes[i]) / r;
            }
            const float a = glm::dot(g, g), b = glm::dot(p, g), c = glm::dot(p, p) - 1.0f;
            const float disc = b * b - a * c;
            if (disc < 0.0f) {
                return;
            }
            const float root = std::sqrt(disc);
            float t = (-b - root) / a;
            if (t <= kEpsilon) {
                t = (-b + root) / a;
            }
            if (t <= kEpsilon || t >= best.t) {
                return;
            }
            const glm::vec3 q = p + t * g;
            glm::vec3 n(0.0f);
            for (int i = 0; i < 3; ++i) {
                n += e.axes[i] * (q[i] / std::max(e.radii[i], 1e-6f));
            }
            best = {t, glm::normalize(n), luminance(e.color), itemIndex};
        } else if (item.kind == ItemKind::Line) {
            const LodLine& l = lines[item.index];
            const float r = 0.5f * (l.startRadius + l.endRadius);
            const auto hit = capsule(o, d, l.start, l.end, r);
            if (hit && *hit > kEpsilon && *hit < best.t) {
                const glm::vec3 x = o + *hit * d;
                const glm::vec3 axis = l.end - l.start;
                const float aa = glm::dot(axis, axis);
                const float s =
                    aa > 0.0f ? std::clamp(glm::dot(x - l.start, axis) / aa, 0.0f, 1.0f) : 0.0f;
                const glm::vec3 n = x - (l.start + s * axis);
                best = {*hit, glm::length(n) > 0.0f ? glm::normalize(n) : -d, luminance(l.color),
                        itemIndex};
            }
        } else {
            const Triangle& tri = triangles[item.index];
            const glm::vec3 e1 = tri.b - tri.a, e2 = tri.c - tri.a;
            const glm::vec3 pv = glm::cross(d, e2);
            const float det = glm::dot(e1, pv);
            if (std::abs(det) < 1e-12f) {
                return;
            }
            const float inv = 1.0f / det;
            const glm::vec3 tv = o - tri.a;
            const float u = glm::dot(tv, pv) * inv;
            if (u < 0.0f || u > 1.0f) {
                return;
            }
            const glm::vec3 qv = glm::cross(tv, e1);
            const float v = glm::dot(d, qv) * inv;
            if (v < 0.0f || u + v > 1.0f) {
                return;
            }
            const float t = glm::dot(e2, qv) * inv;
            if (t <= kEpsilon || t >= best.t) {
                return;
            }
            if (tri.material && tri.material->alphaMasked) {
                const PlantTexture& tex = tri.material->baseColorTexture;
                float alpha = tri.material->baseColor.a;
                if (tex.width > 0 &&
                    tex.rgba.size() == static_cast<std::size_t>(tex.width) * tex.height * 4) {
                    const glm::vec2 uv = (1.0f - u - v) * tri.ta + u * tri.tb + v * tri.tc;
                    const int tx = std::clamp(
                        static_cast<int>((uv.x - std::floor(uv.x)) * tex.width), 0, tex.width - 1);
                    const int ty =
                        std::clamp(static_cast<int>((uv.y - std::floor(uv.y)) * tex.height), 0,
                                   tex.height - 1);
                    alpha *=
                        tex.rgba[(static_cast<std::size_t>(ty) * tex.width + tx) * 4 + 3] / 255.0f;
                }
                if (alpha < tri.material->alphaCutoff) {
                    return;
                }
            }
            glm::vec3 n = glm::normalize(glm::cross(e1, e2));
            if (glm::dot(n, d) > 0.0f) {
                n = -n;
            }
            best = {t, n, tri.albedo, itemIndex};
        }
    }

    static std::optional<float> capsule(const glm::vec3& o, const glm::vec3& d, const glm::vec3& a,
                                        const glm::vec3& b, float r) {
        // Ray against the swept sphere: the cylinder body, then the end caps.
        const glm::vec3 ba = b - a, oa = o - a;
        const float baba = glm::dot(ba, ba), bard = glm::dot(ba, d), baoa = glm::dot(ba, oa);
        const float rdoa = glm::dot(d, oa), oaoa = glm::dot(oa, oa);
        const float dd = glm::dot(d, d);
        const float qa = baba * dd - bard * bard;
        const float qb = baba * rdoa - baoa * bard;
        const float qc = baba * oaoa - baoa * baoa - r * r * baba;
        std::optional<float> result;
        if (qa > 1e-12f) {
            const float h = qb * qb - qa * qc;
            if (h >= 0.0f) {
                const float t = (-qb - std::sqrt(h)) / qa;
                const float y = baoa + t * bard;
                if (y > 0.0f && y < baba && t > 0.0f) {
                    return t;
                }
            }
        }
        for (const glm::vec3& center : {a, b}) {
            const glm::vec3 oc = o - center;
            const float hb = glm::dot(oc, d);
            const float hc = glm::dot(oc, oc) - r * r;
            const float h = hb * hb - dd * hc;
            if (h >= 0.0f) {
                const float t = (-hb - std::sqrt(h)) / dd;
                if (t > 0.0f && (!result || t < *result)) {
                    result = t;
                }
            }
        }
        return result;
    }

    bool contains(const Item& item, const glm::vec3& p) const {
        if (item.kind == ItemKind::Ellipsoid) {
            const LodEllipsoid& e = ellipsoids[item.index];
            float sum = 0.0f;
            for (int i = 0; i < 3; ++i) {
                const float q = glm::dot(p - e.center, e.axes[i]) / std::max(e.radii[i], 1e-6f);
                sum += q * q;
            }
            return sum < 0.98f;
        }
        if (item.kind == ItemKind::Line) {
            const LodLine& l = lines[item.index];
            const glm::vec3 axis = l.end - l.start;
            const float aa = glm::dot(axis, axis);
            const float s =
                aa > 0.0f ? std::clamp(glm::dot(p - l.start, axis) / aa, 0.0f, 1.0f) : 0.0f;
            const float r = 0.99f * (l.startRadius + s * (l.endRadius - l.startRadius));
            const glm::vec3 off = p - (l.start + s * axis);
            return glm::dot(off, off) < r * r;
        }
        return false;
    }

    std::vector<Node> nodes_;
    std::vector<std::uint32_t> order_;
};

Box ellipsoidBox(const LodEllipsoid& e) {
    glm::vec3 half(0.0f);
    for (int i = 0; i < 3; ++i) {
        half += glm::abs(e.axes[i]) * e.radii[i];
    }
    return {e.center - half, e.center + half};
}

Box lineBox(const LodLine& l) {
    const float r = std::max(l.startRadius, l.endRadius);
    return {glm::min(l.start, l.end) - glm::vec3(r), glm::max(l.start, l.end) + glm::vec3(r)};
}

// Cosine-distributed direction around n.
glm::vec3 cosineDirection(const glm::vec3& n, std::mt19937_64& random) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float u = unit(random), v = unit(random);
    const float r = std::sqrt(u), phi = 2.0f * std::numbers::pi_v<float> * v;
    const glm::vec3 a = std::abs(n.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    const glm::vec3 t = glm::normalize(glm::cross(n, a));
    const glm::vec3 b = glm::cross(n, t);
    return glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * b +
                          std::sqrt(std::max(0.0f, 1.0f - u)) * n);
}

// Incoming ambient light at p with normal n in a white environment (radiance 1).
float incoming(const TraceScene& scene, glm::vec3 p, glm::vec3 n, float error, int bounces,
               std::mt19937_64& random) {
    float throughput = 1.0f;
    for (int depth = 0;; ++depth) {
        const glm::vec3 d = cosineDirection(n, random);
        const auto hit = scene.trace(p + n * 1e-4f, d, error);
        if (!hit) {
            return throughput;
        }
        if (depth >= bounces) {
            return 0.0f;
        }
        throughput *= hit->albedo;
        p = p + n * 1e-4f + hit->t * d;
        n = hit->normal;
    }
}

glm::vec3 randomUnit(std::mt19937_64& random) {
    std::normal_distribution<float> normal(0.0f, 1.0f);
    glm::vec3 v;
    do {
        v = glm::vec3(normal(random), normal(random), normal(random));
    } while (glm::dot(v, v) < 1e-12f);
    return glm::normalize(v);
}

// Average ambient term at the first hits of rays from a sphere around the plant.
template <typename Value>
double outsideAverage(const TraceScene& scene, const Box& bounds, float error,
                      const AmbientOcclusionOptions& options, std::uint64_t salt, Value value) {
    const glm::vec3 center = 0.5f * (bounds.minimum + bounds.maximum);
    const float radius = 0.5f * glm::length(bounds.maximum - bounds.minimum) + 1e-3f;
    const int rays = options.calibrationRays;
    std::vector<double> sums(rays, 0.0);
    std::vector<char> hits(rays, 0);
    poolOf(options).run(rays, [&](int i) {
        std::mt19937_64 random(options.seed * 0x9E3779B97F4A7C15ull + salt * 7919ull + i);
        const glm::vec3 origin = center + radius * randomUnit(random);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        const glm::vec3 target =
            bounds.minimum +
            (bounds.maximum - bounds.minimum) * glm::vec3(unit(random), unit(random), unit(random));
        const glm::vec3 d = glm::normalize(target - origin);
        const auto hit = scene.trace(origin, d, error);
        if (hit) {
            sums[i] = value(*hit, origin + hit->t * d, random);
            hits[i] = 1;
        }
    });
    double sum = 0.0;
    int count = 0;
    for (int i = 0; i < rays; ++i) {
        if (hits[i]) {
            sum += sums[i];
            ++count;
        }
    }
    return count > 0 ? sum / count : 1.0;
}

TraceScene sourceScene(const PlantModel& model, bool branchesOnly) {
    TraceScene scene;
    for (const PlantMesh& mesh : model.meshes) {
        if (branchesOnly && mesh.part != PlantPart::Branch) {
            continue;
        }
        const PlantMaterial* material =
            mesh.material >= 0 && mesh.material < static_cast<int>(model.materials.size())
                ? &model.materials[mesh.material]
                : nullptr;
        const bool uvs = mesh.uvs.size() == mesh.positions.size();
        const float albedo = material ? luminance(glm::vec3(material->baseColor)) *
                                            (mesh.part == PlantPart::Leaf ? 0.5f : 1.0f)
                                      : 0.3f;
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1],
                                c = mesh.indices[t + 2];
            if (a >= mesh.positions.size() || b >= mesh.positions.size() ||
                c >= mesh.positions.size()) {
                continue;
            }
            Triangle tri{mesh.positions[a],
                         mesh.positions[b],
                         mesh.positions[c],
                         uvs ? mesh.uvs[a] : glm::vec2(0.0f),
                         uvs ? mesh.uvs[b] : glm::vec2(0.0f),
                         uvs ? mesh.uvs[c] : glm::vec2(0.0f),
                         material,
                         albedo};
            Item item{ItemKind::Triangle,
                      static_cast<std::uint32_t>(scene.triangles.size()),
                      {},
                      0.0f,
                      kInfinity};
            item.box.add(tri.a);
            item.box.add(tri.b);
            item.box.add(tri.c);
            scene.triangles.push_back(tri);
            scene.items.push_back(item);
        }
    }
    scene.build();
    return scene;
}

Box sceneBounds(const PlantModel& model) {
    Box box;
    for (const PlantMesh& mesh : model.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            box.add(p);
        }
    }
    for (const SkeletonSegment& s : model.skeleton) {
        box.add(s.start);
        box.add(s.end);
    }
    return box;
}

// The mean ambient term outside rays see on the source mesh (four paths per hit).
double sourceAverage(const TraceScene& source, const Box& bounds,
                     const AmbientOcclusionOptions& options) {
    return outsideAverage(source, bounds, 0.0f, options, 1,
                          [&](const Hit& hit, const glm::vec3& at, std::mt19937_64& random) {
                              double sum = 0.0;
                              for (int k = 0; k < 4; ++k) {
                                  sum += incoming(source, at, hit.normal, 0.0f, options.bounces,
                                                  random);
                              }
                              return sum / 4.0;
                          });
}

// The scene of one ellipsoid level: its ellipsoids and the lines whose interval meets
// the level's [low, high), ellipsoid items first.
struct LevelScene {
    TraceScene scene;
    std::vector<std::size_t> ellipsoidIds, lineIds;  // global indices of the scene's items
    std::size_t lineBase = 0;                        // the first line item

    bool isEllipsoid(std::uint32_t item) const { return item < lineBase; }
    float errorMinimum(std::uint32_t item) const {
        return isEllipsoid(item) ? scene.ellipsoids[scene.items[item].index].errorMinimum
                                 : scene.lines[scene.items[item].index].errorMinimum;
    }
};

LevelScene levelScene(const PlantLod& lod, float low, float high) {
    LevelScene level;
    TraceScene& scene = level.scene;
    for (std::size_t i = 0; i < lod.ellipsoids.size(); ++i) {
        const LodEllipsoid& e = lod.ellipsoids[i];
        if (e.errorMinimum < high && low < e.errorMaximum) {
            scene.items.push_back({ItemKind::Ellipsoid,
                                   static_cast<std::uint32_t>(scene.ellipsoids.size()),
                                   ellipsoidBox(e), e.errorMinimum, e.errorMaximum});
            scene.ellipsoids.push_back(e);
            level.ellipsoidIds.push_back(i);
        }
    }
    level.lineBase = scene.items.size();
    for (std::size_t i = 0; i < lod.lines.size(); ++i) {
        const LodLine& l = lod.lines[i];
        if (l.errorMinimum < high && low < l.errorMaximum) {
            scene.items.push_back({ItemKind::Line, static_cast<std::uint32_t>(scene.lines.size()),
                                   lineBox(l), l.errorMinimum, l.errorMaximum});
            scene.lines.push_back(l);
            level.lineIds.push_back(i);
        }
    }
    scene.build();
    return level;
}

// A random point on an item's surface with its outward normal; false for a degenerate
// line sample (to be skipped).
bool surfaceSample(const LevelScene& level, std::uint32_t item, std::mt19937_64& random,
                   glm::vec3& p, glm::vec3& n) {
    const TraceScene& scene = level.scene;
    if (level.isEllipsoid(item)) {
        const LodEllipsoid& e = scene.ellipsoids[scene.items[item].index];
        const glm::vec3 q = randomUnit(random);
        p = e.center;
        n = glm::vec3(0.0f);
        for (int a = 0; a < 3; ++a) {
            p += e.axes[a] * (e.radii[a] * q[a]);
            n += e.axes[a] * (q[a] / std::max(e.radii[a], 1e-6f));
        }
        n = glm::normalize(n);
        return true;
    }
    const LodLine& l = scene.lines[scene.items[item].index];
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float t = unit(random);
    const glm::vec3 axis = l.end - l.start;
    const glm::vec3 around = randomUnit(random);
    const glm::vec3 radial =
        around - glm::dot(around, axis) / std::max(glm::dot(axis, axis), 1e-20f) * axis;
    if (glm::dot(radial, radial) < 1e-12f) {
        return false;
    }
    n = glm::normalize(radial);
    p = l.start + t * axis + n * (l.startRadius + t * (l.endRadius - l.startRadius));
    return true;
}

// The ambient term of one item: the mean over up to `samples` surface points that are
// not hidden inside another primitive of the same LoD (0 when all are).
float itemOcclusion(const LevelScene& level, std::uint32_t item, std::size_t global,
                    const AmbientOcclusionOptions& options) {
    std::mt19937_64 random(options.seed * 0xD1B54A32D192ED03ull +
                           static_cast<std::uint64_t>(global));
    const float error = level.errorMinimum(item);
    double sum = 0.0;
    int count = 0;
    for (int s = 0; s < options.samples * 2 && count < options.samples; ++s) {
        glm::vec3 p, n;
        if (!surfaceSample(level, item, random, p, n)) {
            continue;
        }
        if (level.scene.inside(p, error, item)) {
            continue;  // hidden inside another primitive of the same LoD
        }
        sum += incoming(level.scene, p, n, error, options.bounces, random);
        ++count;
    }
    return count > 0 ? static_cast<float>(sum / count) : 0.0f;
}

}  // namespace

double sourceMeshAmbientOcclusion(const PlantModel& model, const AmbientOcclusionOptions& options) {
    return sourceAverage(sourceScene(model, false), sceneBounds(model), options);
}

void computeAmbientOcclusion(const PlantModel& model, PlantLod& lod,
                             const AmbientOcclusionOptions& options) {
    // One scene per ellipsoid level: its ellipsoids and the lines whose interval meets
    // the level's. The error filter still decides visibility exactly; the split only
    // keeps coarse levels' huge ellipsoids out of the fine levels' hierarchy.
    std::vector<std::pair<float, float>> ranges;
    for (const PlantLodLevel& level : lod.levels) {
        ranges.emplace_back(level.errorMinimum, level.errorMaximum);
    }
    if (ranges.empty()) {
        ranges.emplace_back(0.0f, kInfinity);
    }
    const Box bounds = sceneBounds(model);
    const double target = sourceAverage(sourceScene(model, false), bounds, options);
    for (std::size_t k = 0; k < ranges.size(); ++k) {
        const auto [low, high] = ranges[k];
        LevelScene level = levelScene(lod, low, high);
        TraceScene& scene = level.scene;
        // Primitives computed in this scene: ellipsoids starting in the level, lines
        // whose own error falls in it (each primitive exactly once).
        std::vector<std::uint32_t> work;
        for (std::size_t item = 0; item < scene.items.size(); ++item) {
            const float own = level.errorMinimum(static_cast<std::uint32_t>(item));
            if (low <= own && own < high) {
                work.push_back(static_cast<std::uint32_t>(item));
            }
        }
        std::vector<float> values(work.size(), 1.0f);
        poolOf(options).run(static_cast<int>(work.size()), [&](int w) {
            const std::uint32_t item = work[w];
            const std::size_t global =
                level.isEllipsoid(item)
                    ? level.ellipsoidIds[scene.items[item].index]
                    : level.lineIds[scene.items[item].index] + lod.ellipsoids.size();
            values[w] = itemOcclusion(level, item, global, options);
        });
        for (std::size_t w = 0; w < work.size(); ++w) {
            const Item& item = scene.items[work[w]];
            if (level.isEllipsoid(work[w])) {
                lod.ellipsoids[level.ellipsoidIds[item.index]].ambientOcclusion = values[w];
                scene.ellipsoids[item.index].ambientOcclusion = values[w];
            } else {
                lod.lines[level.lineIds[item.index]].ambientOcclusion = values[w];
                scene.lines[item.index].ambientOcclusion = values[w];
            }
        }
        // Calibration (§6.5.3): the mean term the outside rays see at the level's error
        // against the source mesh's; the level's ellipsoids are scaled to match.
        const double seen = outsideAverage(
            scene, bounds, low, options, 100 + k,
            [&](const Hit& hit, const glm::vec3&, std::mt19937_64&) {
                const Item& item = scene.items[hit.item];
                return static_cast<double>(item.kind == ItemKind::Ellipsoid
                                               ? scene.ellipsoids[item.index].ambientOcclusion
                                               : scene.lines[item.index].ambientOcclusion);
            });
        if (seen > 0.0) {
            const float factor = static_cast<float>(target / seen);
            for (std::size_t w = 0; w < work.size(); ++w) {
                if (level.isEllipsoid(work[w])) {
                    LodEllipsoid& e =
                        lod.ellipsoids[level.ellipsoidIds[scene.items[work[w]].index]];
                    e.ambientOcclusion = std::clamp(e.ambientOcclusion * factor, 0.0f, 1.0f);
                }
            }
        }
    }
}

}  // namespace sylva
