#include "sylva/core/plantlod/LineHierarchy.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "sylva/core/base/Check.h"
#include "sylva/core/plantlod/PlantThreads.h"

namespace sylva {

namespace {

// Stale candidates re-measured together (in parallel) when one reaches the heap's top.
constexpr int kRemeasureBatch = 4;

float coneVolume(const LodLine& line) {
    const float h = glm::length(line.end - line.start);
    const float a = line.startRadius, b = line.endRadius;
    return std::numbers::pi_v<float> * h * (a * a + a * b + b * b) / 3.0f;
}

glm::vec3 closestOnSegment(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b) {
    const glm::vec3 e = b - a;
    const float ee = glm::dot(e, e);
    const float t = ee > 0.0f ? std::clamp(glm::dot(p - a, e) / ee, 0.0f, 1.0f) : 0.0f;
    return a + t * e;
}

float angleBetween(const LodLine& a, const LodLine& b) {
    const glm::vec3 da = a.end - a.start, db = b.end - b.start;
    const float la = glm::length(da), lb = glm::length(db);
    if (la <= 0.0f || lb <= 0.0f) {
        return 0.0f;
    }
    return std::acos(std::clamp(glm::dot(da, db) / (la * lb), -1.0f, 1.0f));
}

PixelRect unite(const PixelRect& a, const PixelRect& b) {
    if (a.empty()) {
        return b;
    }
    if (b.empty()) {
        return a;
    }
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

bool overlaps(const PixelRect& a, const PixelRect& b) {
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

}  // namespace

LineSkeleton::LineSkeleton(const std::vector<SkeletonSegment>& segments, const glm::vec3& color) {
    const int count = static_cast<int>(segments.size());
    nodes_.resize(count);
    for (int i = 0; i < count; ++i) {
        const SkeletonSegment& s = segments[i];
        LineNode& node = nodes_[i];
        node.line.start = s.start;
        node.line.end = s.end;
        node.line.startRadius = std::max(s.startRadius, 0.0f);
        node.line.endRadius = std::max(s.endRadius, 0.0f);
        node.line.color = color;
        node.line.weight = std::max(coneVolume(node.line), 1e-12f);
        // A parent out of range, or one whose chain loops, makes the segment a root.
        int parent = s.parent;
        bool valid = parent >= 0 && parent < count && parent != i;
        for (int walk = parent, steps = 0; valid && walk >= 0;
             walk = segments[walk].parent, ++steps) {
            if (walk >= count || steps > count || walk == i) {
                valid = false;
            }
        }
        node.parent = valid ? parent : -1;
    }
    for (int i = 0; i < count; ++i) {
        if (nodes_[i].parent >= 0) {
            nodes_[nodes_[i].parent].children.push_back(i);
        } else {
            roots_.push_back(i);
        }
    }
    initialRoots_ = static_cast<int>(roots_.size());
    aliveCount_ = count;
}

bool LineSkeleton::canStraighten(int parent, int child) const {
    const int n = static_cast<int>(nodes_.size());
    if (parent < 0 || child < 0 || parent >= n || child >= n || !nodes_[parent].alive ||
        !nodes_[child].alive) {
        return false;
    }
    return nodes_[parent].children.size() == 1 && nodes_[parent].children[0] == child;
}

bool LineSkeleton::canCombine(int first, int second) const {
    const int n = static_cast<int>(nodes_.size());
    if (first < 0 || second < 0 || first >= n || second >= n || first == second ||
        !nodes_[first].alive || !nodes_[second].alive) {
        return false;
    }
    return nodes_[first].parent == nodes_[second].parent && nodes_[first].children.empty() &&
           nodes_[second].children.empty();
}

bool LineSkeleton::valid(LineMergeKind kind, int first, int second) const {
    return kind == LineMergeKind::Straighten ? canStraighten(first, second)
                                             : canCombine(first, second);
}

std::vector<int> LineSkeleton::siblings(int node) const {
    const int parent = nodes_[node].parent;
    return parent >= 0 ? nodes_[parent].children : roots_;
}

LineMergePreview LineSkeleton::preview(LineMergeKind kind, int first, int second) const {
    SYLVA_CHECK(valid(kind, first, second));
    const LodLine& a = nodes_[first].line;
    const LodLine& b = nodes_[second].line;
    const float wa = a.weight, wb = b.weight, w = wa + wb;
    LineMergePreview result;
    LodLine& m = result.merged;
    m.weight = w;
    m.color = (wa * a.color + wb * b.color) / w;
    if (kind == LineMergeKind::Straighten) {
        m.start = a.start;
        m.end = b.end;
        m.startRadius = a.startRadius;
        m.endRadius = b.endRadius;
        for (int child : nodes_[second].children) {
            LodLine moved = nodes_[child].line;
            moved.start = closestOnSegment(moved.start, m.start, m.end);
            result.moved.emplace_back(child, moved);
        }
    } else {
        m.start = (wa * a.start + wb * b.start) / w;
        m.end = (wa * a.end + wb * b.end) / w;
        m.startRadius = (wa * a.startRadius + wb * b.startRadius) / w;
        m.endRadius = (wa * a.endRadius + wb * b.endRadius) / w;
    }
    return result;
}

int LineSkeleton::apply(LineMergeKind kind, int first, int second, int step) {
    LineMergePreview p = preview(kind, first, second);
    const int index = static_cast<int>(nodes_.size());
    LineNode node;
    node.line = p.merged;
    node.parent = nodes_[first].parent;
    node.birthStep = step;
    if (kind == LineMergeKind::Straighten) {
        node.children = nodes_[second].children;
        for (const auto& [child, line] : p.moved) {
            nodes_[child].line = line;
            nodes_[child].parent = index;
        }
    }
    std::vector<int>& group = node.parent >= 0 ? nodes_[node.parent].children : roots_;
    std::erase_if(group, [&](int i) { return i == first || i == second; });
    group.push_back(index);
    for (int dead : {first, second}) {
        nodes_[dead].alive = false;
        nodes_[dead].deathStep = step;
        nodes_[dead].children.clear();
    }
    nodes_.push_back(std::move(node));
    --aliveCount_;
    return index;
}

bool LineSkeleton::connected(float tolerance) const {
    int roots = 0;
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        const LineNode& node = nodes_[i];
        if (!node.alive) {
            continue;
        }
        if (node.parent < 0) {
            ++roots;
            continue;
        }
        const LineNode& parent = nodes_[node.parent];
        if (!parent.alive || std::find(parent.children.begin(), parent.children.end(),
                                       static_cast<int>(i)) == parent.children.end()) {
            return false;
        }
        const glm::vec3 onParent =
            closestOnSegment(node.line.start, parent.line.start, parent.line.end);
        if (glm::length(onParent - node.line.start) > tolerance) {
            return false;
        }
    }
    return roots <= initialRoots_;
}

LineHierarchyResult buildLineHierarchy(const std::vector<SkeletonSegment>& segments,
                                       const glm::vec3& color,
                                       const PrimitiveRasterizer& rasterizer,
                                       const LineHierarchyOptions& options,
                                       const PlantLodProgressCallback& progress,
                                       double progressStart, double progressEnd) {
    LineSkeleton skeleton(segments, color);
    LineHierarchyResult result;
    result.widthScale = options.widthScale;
    const int views = rasterizer.viewCount();
    const float scale = options.widthScale;
    const std::vector<LineNode>& nodes = skeleton.nodes();

    // Per view: the original skeleton (reference), the current state, bounds per node.
    std::vector<RasterFrame> reference, current;
    std::vector<std::vector<PixelRect>> bounds(views);
    std::vector<int> alive;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        alive.push_back(static_cast<int>(i));
    }
    for (int v = 0; v < views; ++v) {
        RasterFrame frame = rasterizer.blankFrame();
        for (const LineNode& node : nodes) {
            rasterizer.drawLine(node.line, v, frame, scale);
            bounds[v].push_back(rasterizer.lineBounds(node.line, v, scale));
        }
        current.push_back(frame);
        reference.push_back(std::move(frame));
    }
    // Per view, a uniform grid of node ids by screen bounds, so a render visits only the
    // lines near its rectangle instead of every live line. Entries are never removed:
    // dead nodes and outdated bounds are filtered at lookup.
    constexpr int kGridCells = 16;
    const int cellPixels = (rasterizer.renderSize() + kGridCells - 1) / kGridCells;
    std::vector<std::vector<std::vector<int>>> grid(
        views, std::vector<std::vector<int>>(kGridCells * kGridCells));
    const auto cellRange = [&](const PixelRect& rect, auto&& visit) {
        if (rect.empty()) {
            return;
        }
        const int cx0 = std::clamp(rect.x0 / cellPixels, 0, kGridCells - 1);
        const int cx1 = std::clamp((rect.x1 - 1) / cellPixels, 0, kGridCells - 1);
        const int cy0 = std::clamp(rect.y0 / cellPixels, 0, kGridCells - 1);
        const int cy1 = std::clamp((rect.y1 - 1) / cellPixels, 0, kGridCells - 1);
        for (int cy = cy0; cy <= cy1; ++cy) {
            for (int cx = cx0; cx <= cx1; ++cx) {
                visit(cy * kGridCells + cx);
            }
        }
    };
    const auto insertIntoGrid = [&](int v, int id) {
        cellRange(bounds[v][id], [&](int cell) { grid[v][cell].push_back(id); });
    };
    // The live lines whose bounds overlap `rect`, ascending (= the order of `alive`).
    const auto linesNear = [&](int v, const PixelRect& rect) {
        std::vector<int> found;
        cellRange(rect, [&](int cell) {
            for (int id : grid[v][cell]) {
                if (nodes[id].alive && overlaps(bounds[v][id], rect)) {
                    found.push_back(id);
                }
            }
        });
        std::sort(found.begin(), found.end());
        found.erase(std::unique(found.begin(), found.end()), found.end());
        return found;
    };
    for (int v = 0; v < views; ++v) {
        for (int id : alive) {
            insertIntoGrid(v, id);
        }
    }

    double totalSquared = 0.0;
    const double pixelCount =
        static_cast<double>(views) * rasterizer.renderSize() * rasterizer.renderSize();

    // Renders the tiles a merge changes and returns the change of the squared error;
    // `footprint` receives the rectangle per view that the measurement depends on.
    const auto render = [&](LineMergeKind kind, int a, int b, std::vector<RasterFrame>* tiles,
                            std::vector<PixelRect>* footprint) {
        const LineMergePreview p = skeleton.preview(kind, a, b);
        double delta = 0.0;
        if (footprint) {
            footprint->assign(views, PixelRect{});
        }
        for (int v = 0; v < views; ++v) {
            PixelRect rect = unite(bounds[v][a], bounds[v][b]);
            rect = unite(rect, rasterizer.lineBounds(p.merged, v, scale));
            for (const auto& [id, line] : p.moved) {
                rect = unite(rect, unite(bounds[v][id], rasterizer.lineBounds(line, v, scale)));
            }
            if (footprint) {
                (*footprint)[v] = rect;
            }
            RasterFrame tile = rasterizer.blankFrame(rect);
            if (!rect.empty()) {
                for (int id : linesNear(v, rect)) {
                    if (id == a || id == b) {
                        continue;
                    }
                    auto moved = std::find_if(p.moved.begin(), p.moved.end(),
                                              [&](const auto& m) { return m.first == id; });
                    rasterizer.drawLine(moved != p.moved.end() ? moved->second : nodes[id].line, v,
                                        tile, scale);
                }
                for (const auto& [id, line] : p.moved) {
                    if (!overlaps(bounds[v][id], rect)) {  // moved into the rectangle
                        rasterizer.drawLine(line, v, tile, scale);
                    }
                }
                rasterizer.drawLine(p.merged, v, tile, scale);
                const int full = rasterizer.renderSize();
                for (int y = rect.y0; y < rect.y1; ++y) {
                    for (int x = rect.x0; x < rect.x1; ++x) {
                        const std::size_t at = static_cast<std::size_t>(y) * full + x;
                        const double ref = reference[v].value[at];
                        const double now =
                            tile.value[static_cast<std::size_t>(y - rect.y0) * tile.width() +
                                       (x - rect.x0)];
                        const double before = current[v].value[at];
                        delta += (now - ref) * (now - ref) - (before - ref) * (before - ref);
                    }
                }
            }
            if (tiles) {
                tiles->push_back(std::move(tile));
            }
        }
        return delta;
    };

    // `error` is the change of the squared error the merge would cause. It depends only
    // on the pixels of the candidate's footprint (and on the lines a, b and b's children),
    // so it stays exact until an applied merge touches them; only then is it re-measured
    // (seed 001 Algorithm 2 re-measures every cached candidate after each merge, which
    // made the heap dominate the build for skeletons of thousands of lines).
    struct Candidate {
        double error = 0.0;
        bool stale = false;
        LineMergeKind kind = LineMergeKind::Straighten;
        int a = -1, b = -1;
        std::vector<PixelRect> footprint;  // per view
    };
    const auto worse = [](const Candidate& x, const Candidate& y) {
        if (x.error != y.error) {
            return x.error > y.error;
        }
        return std::tie(x.a, x.b, x.kind) > std::tie(y.a, y.b, y.kind);
    };
    std::vector<Candidate> heap;
    std::mt19937_64 random(options.seed * 0x2545F4914F6CDD1Dull + 17);
    const int totalSteps = std::max(static_cast<int>(nodes.size()) - 1, 1);

    const auto localEstimate = [&](const Candidate& c) {
        const LodLine& x = nodes[c.a].line;
        const LodLine& y = nodes[c.b].line;
        const float shorter = std::min(glm::length(x.end - x.start), glm::length(y.end - y.start));
        return (angleBetween(x, y) + 1e-3f) * (shorter + 1e-6f);
    };
    const auto candidateFor = [&](int x, std::vector<Candidate>& out, bool everySibling) {
        const LineNode& node = nodes[x];
        if (node.children.size() == 1) {
            out.push_back({0.0, false, LineMergeKind::Straighten, x, node.children[0], {}});
        } else if (node.children.empty()) {
            std::vector<int> partners;
            for (int s : skeleton.siblings(x)) {
                if (s != x && nodes[s].children.empty()) {
                    partners.push_back(s);
                }
            }
            if (partners.empty()) {
                return;
            }
            if (everySibling) {
                for (int s : partners) {
                    if (x < s) {
                        out.push_back({0.0, false, LineMergeKind::Combine, x, s, {}});
                    }
                }
            } else {
                const int s = partners[random() % partners.size()];
                out.push_back(
                    {0.0, false, LineMergeKind::Combine, std::min(x, s), std::max(x, s), {}});
            }
        }
    };

    int step = 0;
    while (skeleton.aliveCount() > 1) {
        // Gather N_new · N_local random candidates, keep the N_new best by local estimate.
        std::vector<Candidate> gathered;
        const int wanted = options.newCandidates * options.localCandidates;
        if (static_cast<int>(alive.size()) <= wanted) {
            for (int x : alive) {
                candidateFor(x, gathered, true);
            }
        } else {
            for (int attempt = 0;
                 attempt < 4 * wanted && static_cast<int>(gathered.size()) < wanted; ++attempt) {
                candidateFor(alive[random() % alive.size()], gathered, false);
            }
            if (gathered.empty()) {
                for (int x : alive) {
                    candidateFor(x, gathered, true);
                }
            }
        }
        if (gathered.empty() && heap.empty()) {
            break;  // nothing mergeable (cannot happen for a forest; kept as a guard)
        }
        std::stable_sort(gathered.begin(), gathered.end(),
                         [&](const Candidate& x, const Candidate& y) {
                             return localEstimate(x) < localEstimate(y);
                         });
        if (static_cast<int>(gathered.size()) > options.newCandidates) {
            gathered.resize(options.newCandidates);
        }
        // A candidate already in the heap with a current measurement would measure the
        // same again: keep the heap's. A stale copy in the heap is dropped for the new one.
        std::erase_if(gathered, [&](const Candidate& c) {
            for (Candidate& h : heap) {
                if (h.kind == c.kind && h.a == c.a && h.b == c.b) {
                    if (!h.stale) {
                        return true;
                    }
                    h.a = h.b = -1;  // invalid: discarded when popped
                }
            }
            return false;
        });
        for (std::size_t i = 0; i < gathered.size(); ++i) {
            for (std::size_t j = i + 1; j < gathered.size(); ++j) {
                if (gathered[j].kind == gathered[i].kind && gathered[j].a == gathered[i].a &&
                    gathered[j].b == gathered[i].b) {
                    gathered[j].a = gathered[j].b = -1;
                }
            }
        }
        std::erase_if(gathered, [](const Candidate& c) { return c.a < 0; });
        std::make_heap(heap.begin(), heap.end(), worse);
        runOnThreads(static_cast<int>(gathered.size()), options.threads, [&](int i) {
            Candidate& c = gathered[i];
            c.error = render(c.kind, c.a, c.b, nullptr, &c.footprint);
        });
        for (Candidate& c : gathered) {
            heap.push_back(std::move(c));
            std::push_heap(heap.begin(), heap.end(), worse);
        }
        bool applied = false;
        while (!heap.empty() && !applied) {
            std::pop_heap(heap.begin(), heap.end(), worse);
            Candidate best = heap.back();
            heap.pop_back();
            if (!skeleton.valid(best.kind, best.a, best.b)) {
                continue;
            }
            if (best.stale) {
                // Re-measure the stale candidates at the top of the heap together, on all
                // threads. The batch size is fixed, so the merge order does not depend on
                // the thread count.
                std::vector<Candidate> batch;
                batch.push_back(std::move(best));
                while (!heap.empty() && static_cast<int>(batch.size()) < kRemeasureBatch &&
                       heap.front().stale) {
                    std::pop_heap(heap.begin(), heap.end(), worse);
                    if (skeleton.valid(heap.back().kind, heap.back().a, heap.back().b)) {
                        batch.push_back(std::move(heap.back()));
                    }
                    heap.pop_back();
                }
                runOnThreads(static_cast<int>(batch.size()), options.threads, [&](int i) {
                    Candidate& c = batch[i];
                    c.error = render(c.kind, c.a, c.b, nullptr, &c.footprint);
                });
                for (Candidate& c : batch) {
                    c.stale = false;
                    heap.push_back(std::move(c));
                    std::push_heap(heap.begin(), heap.end(), worse);
                }
                continue;
            }
            std::vector<RasterFrame> tiles;
            totalSquared += render(best.kind, best.a, best.b, &tiles, nullptr);
            totalSquared = std::max(totalSquared, 0.0);
            for (int v = 0; v < views; ++v) {
                const RasterFrame& tile = tiles[v];
                const int full = rasterizer.renderSize();
                for (int y = tile.rect.y0; y < tile.rect.y1; ++y) {
                    for (int x = tile.rect.x0; x < tile.rect.x1; ++x) {
                        current[v].value[static_cast<std::size_t>(y) * full + x] =
                            tile.value[static_cast<std::size_t>(y - tile.rect.y0) * tile.width() +
                                       (x - tile.rect.x0)];
                    }
                }
            }
            ++step;
            const LineMergePreview p = skeleton.preview(best.kind, best.a, best.b);
            const int created = skeleton.apply(best.kind, best.a, best.b, step);
            for (int v = 0; v < views; ++v) {
                bounds[v].push_back(rasterizer.lineBounds(nodes[created].line, v, scale));
                insertIntoGrid(v, created);
                for (const auto& [id, line] : p.moved) {
                    bounds[v][id] = rasterizer.lineBounds(line, v, scale);
                    insertIntoGrid(v, id);
                }
            }
            // Candidates whose footprint or lines the merge touched must be re-measured.
            for (Candidate& c : heap) {
                if (c.stale) {
                    continue;
                }
                bool touched = c.a == best.a || c.a == best.b || c.b == best.a || c.b == best.b;
                for (const auto& [id, line] : p.moved) {
                    touched = touched || id == c.a || id == c.b;
                }
                for (int involved : {best.a, best.b}) {
                    const int parent = nodes[involved].parent;
                    touched = touched || parent == c.a || parent == c.b;
                }
                for (int v = 0; v < views && !touched; ++v) {
                    touched = overlaps(c.footprint[v], tiles[v].rect);
                }
                c.stale = touched;
            }
            std::erase_if(alive, [&](int i) { return i == best.a || i == best.b; });
            alive.push_back(created);
            result.merges.push_back(
                {best.kind, best.a, best.b, created, std::sqrt(totalSquared / pixelCount)});
            applied = true;
        }
        // Prune to the N_cache best.
        if (static_cast<int>(heap.size()) > options.cachedCandidates) {
            std::sort(heap.begin(), heap.end(),
                      [&](const Candidate& x, const Candidate& y) { return worse(y, x); });
            heap.resize(options.cachedCandidates);
            std::make_heap(heap.begin(), heap.end(), worse);
        }
        if (progress && (step % 64 == 0 || skeleton.aliveCount() == 1)) {
            PlantLodProgress p;
            p.stage = "lines";
            p.level = step;
            p.levelCount = totalSteps;
            p.fraction = progressStart + (progressEnd - progressStart) * step / totalSteps;
            progress(p);
        }
    }
    result.nodes = nodes;
    return result;
}

}  // namespace sylva
