#include "sylva/core/plantlod/LineHierarchy.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "sylva/core/base/Check.h"
#include "sylva/core/base/WorkerPool.h"

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

namespace {

// The line images the merges are measured on (seed 001 §3.4.2): per view the original
// skeleton (the reference), the current state, every node's screen bounds, and a
// uniform grid of node ids by bounds, so a render visits only the lines near its
// rectangle instead of every live line. Grid entries are never removed: dead nodes and
// outdated bounds are filtered at lookup.
class LineImages {
public:
    LineImages(const LineSkeleton& skeleton, const PrimitiveRasterizer& rasterizer, float scale)
        : skeleton_(skeleton),
          rasterizer_(rasterizer),
          views_(rasterizer.viewCount()),
          scale_(scale),
          bounds_(views_),
          cellPixels_((rasterizer.renderSize() + kGridCells - 1) / kGridCells),
          grid_(views_, std::vector<std::vector<int>>(kGridCells * kGridCells)) {
        const std::vector<LineNode>& nodes = skeleton.nodes();
        for (int v = 0; v < views_; ++v) {
            RasterFrame frame = rasterizer.blankFrame();
            for (const LineNode& node : nodes) {
                rasterizer.drawLine(node.line, v, frame, scale);
                bounds_[v].push_back(rasterizer.lineBounds(node.line, v, scale));
            }
            current_.push_back(frame);
            reference_.push_back(std::move(frame));
        }
        for (int v = 0; v < views_; ++v) {
            for (std::size_t id = 0; id < nodes.size(); ++id) {
                insertIntoGrid(v, static_cast<int>(id));
            }
        }
    }

    int views() const { return views_; }
    double pixelCount() const {
        return static_cast<double>(views_) * rasterizer_.renderSize() * rasterizer_.renderSize();
    }

    // Renders the tiles a merge changes and returns the change of the squared error;
    // `footprint` receives the rectangle per view that the measurement depends on.
    double measure(LineMergeKind kind, int a, int b, std::vector<RasterFrame>* tiles,
                   std::vector<PixelRect>* footprint) const {
        const LineMergePreview p = skeleton_.preview(kind, a, b);
        double delta = 0.0;
        if (footprint) {
            footprint->assign(views_, PixelRect{});
        }
        for (int v = 0; v < views_; ++v) {
            PixelRect rect = unite(bounds_[v][a], bounds_[v][b]);
            rect = unite(rect, rasterizer_.lineBounds(p.merged, v, scale_));
            for (const auto& [id, line] : p.moved) {
                rect = unite(rect, unite(bounds_[v][id], rasterizer_.lineBounds(line, v, scale_)));
            }
            if (footprint) {
                (*footprint)[v] = rect;
            }
            RasterFrame tile = rasterizer_.blankFrame(rect);
            if (!rect.empty()) {
                drawMerged(v, a, b, p, rect, tile);
                delta += squaredErrorChange(v, tile);
            }
            if (tiles) {
                tiles->push_back(std::move(tile));
            }
        }
        return delta;
    }

    // An applied merge: its tiles become the current images; the created node and the
    // moved lines get their bounds.
    void commit(const std::vector<RasterFrame>& tiles, int created,
                const LineMergePreview& preview) {
        const int full = rasterizer_.renderSize();
        for (int v = 0; v < views_; ++v) {
            const RasterFrame& tile = tiles[v];
            for (int y = tile.rect.y0; y < tile.rect.y1; ++y) {
                for (int x = tile.rect.x0; x < tile.rect.x1; ++x) {
                    current_[v].value[static_cast<std::size_t>(y) * full + x] =
                        tile.value[static_cast<std::size_t>(y - tile.rect.y0) * tile.width() +
                                   (x - tile.rect.x0)];
                }
            }
        }
        const std::vector<LineNode>& nodes = skeleton_.nodes();
        for (int v = 0; v < views_; ++v) {
            bounds_[v].push_back(rasterizer_.lineBounds(nodes[created].line, v, scale_));
            insertIntoGrid(v, created);
            for (const auto& [id, line] : preview.moved) {
                bounds_[v][id] = rasterizer_.lineBounds(line, v, scale_);
                insertIntoGrid(v, id);
            }
        }
    }

private:
    static constexpr int kGridCells = 16;

    // The lines of the merged state inside `rect` of view v: the live lines near it
    // (moved ones at their new starts) except a and b, lines moved into it, the merge.
    void drawMerged(int v, int a, int b, const LineMergePreview& p, const PixelRect& rect,
                    RasterFrame& tile) const {
        const std::vector<LineNode>& nodes = skeleton_.nodes();
        for (int id : linesNear(v, rect)) {
            if (id == a || id == b) {
                continue;
            }
            auto moved = std::find_if(p.moved.begin(), p.moved.end(),
                                      [&](const auto& m) { return m.first == id; });
            rasterizer_.drawLine(moved != p.moved.end() ? moved->second : nodes[id].line, v, tile,
                                 scale_);
        }
        for (const auto& [id, line] : p.moved) {
            if (!overlaps(bounds_[v][id], rect)) {  // moved into the rectangle
                rasterizer_.drawLine(line, v, tile, scale_);
            }
        }
        rasterizer_.drawLine(p.merged, v, tile, scale_);
    }

    // Σ (tile − reference)² − (current − reference)² over the tile's rectangle.
    double squaredErrorChange(int v, const RasterFrame& tile) const {
        const PixelRect& rect = tile.rect;
        const int full = rasterizer_.renderSize();
        double delta = 0.0;
        for (int y = rect.y0; y < rect.y1; ++y) {
            for (int x = rect.x0; x < rect.x1; ++x) {
                const std::size_t at = static_cast<std::size_t>(y) * full + x;
                const double ref = reference_[v].value[at];
                const double now = tile.value[static_cast<std::size_t>(y - rect.y0) * tile.width() +
                                              (x - rect.x0)];
                const double before = current_[v].value[at];
                delta += (now - ref) * (now - ref) - (before - ref) * (before - ref);
            }
        }
        return delta;
    }

    template <typename Visit>
    void cellRange(const PixelRect& rect, Visit&& visit) const {
        if (rect.empty()) {
            return;
        }
        const int cx0 = std::clamp(rect.x0 / cellPixels_, 0, kGridCells - 1);
        const int cx1 = std::clamp((rect.x1 - 1) / cellPixels_, 0, kGridCells - 1);
        const int cy0 = std::clamp(rect.y0 / cellPixels_, 0, kGridCells - 1);
        const int cy1 = std::clamp((rect.y1 - 1) / cellPixels_, 0, kGridCells - 1);
        for (int cy = cy0; cy <= cy1; ++cy) {
            for (int cx = cx0; cx <= cx1; ++cx) {
                visit(cy * kGridCells + cx);
            }
        }
    }

    void insertIntoGrid(int v, int id) {
        cellRange(bounds_[v][id], [&](int cell) { grid_[v][cell].push_back(id); });
    }

    // The live lines whose bounds overlap `rect`, ascending.
    std::vector<int> linesNear(int v, const PixelRect& rect) const {
        const std::vector<LineNode>& nodes = skeleton_.nodes();
        std::vector<int> found;
        cellRange(rect, [&](int cell) {
            for (int id : grid_[v][cell]) {
                if (nodes[id].alive && overlaps(bounds_[v][id], rect)) {
                    found.push_back(id);
                }
            }
        });
        std::sort(found.begin(), found.end());
        found.erase(std::unique(found.begin(), found.end()), found.end());
        return found;
    }

    const LineSkeleton& skeleton_;
    const PrimitiveRasterizer& rasterizer_;
    const int views_;
    const float scale_;
    std::vector<RasterFrame> reference_, current_;
    std::vector<std::vector<PixelRect>> bounds_;  // per view, per node
    const int cellPixels_;
    std::vector<std::vector<std::vector<int>>> grid_;  // per view, per cell: node ids
};

// A merge candidate. `error` is the change of the squared error the merge would cause.
// It depends only on the pixels of the candidate's footprint (and on the lines a, b and
// b's children), so it stays exact until an applied merge touches them; only then is it
// re-measured (seed 001 Algorithm 2 re-measures every cached candidate after each merge,
// which made the heap dominate the build for skeletons of thousands of lines).
struct Candidate {
    double error = 0.0;
    bool stale = false;
    LineMergeKind kind = LineMergeKind::Straighten;
    int a = -1, b = -1;
    std::vector<PixelRect> footprint;  // per view
};

// The heap order: the lowest error on top; ties by (a, b, kind).
bool worse(const Candidate& x, const Candidate& y) {
    if (x.error != y.error) {
        return x.error > y.error;
    }
    return std::tie(x.a, x.b, x.kind) > std::tie(y.a, y.b, y.kind);
}

// Algorithm 2's search: random candidates ranked by a local estimate, measured, kept on
// a heap of at most N_cache; the best valid, current one is applied.
class MergeSearch {
public:
    MergeSearch(LineSkeleton& skeleton, LineImages& images, const LineHierarchyOptions& options)
        : skeleton_(skeleton),
          images_(images),
          options_(options),
          random_(options.seed * 0x2545F4914F6CDD1Dull + 17) {
        for (std::size_t i = 0; i < skeleton.nodes().size(); ++i) {
            alive_.push_back(static_cast<int>(i));
        }
    }

    // One merge (as `step`); false when nothing is mergeable (cannot happen for a
    // forest; kept as a guard).
    bool step(int step, std::vector<LineMergeRecord>& merges) {
        std::vector<Candidate> gathered = gather();
        if (gathered.empty() && heap_.empty()) {
            return false;
        }
        std::stable_sort(gathered.begin(), gathered.end(),
                         [&](const Candidate& x, const Candidate& y) {
                             return localEstimate(x) < localEstimate(y);
                         });
        if (static_cast<int>(gathered.size()) > options_.newCandidates) {
            gathered.resize(options_.newCandidates);
        }
        dropKnown(gathered);
        std::make_heap(heap_.begin(), heap_.end(), worse);
        measure(gathered);
        for (Candidate& c : gathered) {
            heap_.push_back(std::move(c));
            std::push_heap(heap_.begin(), heap_.end(), worse);
        }
        applyBest(step, merges);
        prune();
        return true;
    }

private:
    // The local estimate of Fig. 3.11: the angle between the two lines times the shorter
    // length.
    float localEstimate(const Candidate& c) const {
        const LodLine& x = skeleton_.nodes()[c.a].line;
        const LodLine& y = skeleton_.nodes()[c.b].line;
        const float shorter = std::min(glm::length(x.end - x.start), glm::length(y.end - y.start));
        return (angleBetween(x, y) + 1e-3f) * (shorter + 1e-6f);
    }

    // The merges of node x: with its only child, or with a childless sibling (every one,
    // or one at random).
    void candidatesOf(int x, std::vector<Candidate>& out, bool everySibling) {
        const std::vector<LineNode>& nodes = skeleton_.nodes();
        const LineNode& node = nodes[x];
        if (node.children.size() == 1) {
            out.push_back({0.0, false, LineMergeKind::Straighten, x, node.children[0], {}});
            return;
        }
        if (!node.children.empty()) {
            return;
        }
        std::vector<int> partners;
        for (int s : skeleton_.siblings(x)) {
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
            const int s = partners[random_() % partners.size()];
            out.push_back({0.0, false, LineMergeKind::Combine, std::min(x, s), std::max(x, s), {}});
        }
    }

    // N_new · N_local random candidates (every one when there are few lines).
    std::vector<Candidate> gather() {
        std::vector<Candidate> gathered;
        const int wanted = options_.newCandidates * options_.localCandidates;
        if (static_cast<int>(alive_.size()) <= wanted) {
            for (int x : alive_) {
                candidatesOf(x, gathered, true);
            }
            return gathered;
        }
        for (int attempt = 0; attempt < 4 * wanted && static_cast<int>(gathered.size()) < wanted;
             ++attempt) {
            candidatesOf(alive_[random_() % alive_.size()], gathered, false);
        }
        if (gathered.empty()) {
            for (int x : alive_) {
                candidatesOf(x, gathered, true);
            }
        }
        return gathered;
    }

    // A candidate already in the heap with a current measurement would measure the same
    // again: keep the heap's. A stale copy in the heap is dropped for the new one.
    // Duplicates among the new ones go too.
    void dropKnown(std::vector<Candidate>& gathered) {
        std::erase_if(gathered, [&](const Candidate& c) {
            for (Candidate& h : heap_) {
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
    }

    void measure(std::vector<Candidate>& candidates) {
        WorkerPool& pool = options_.pool != nullptr ? *options_.pool : WorkerPool::shared();
        pool.run(static_cast<int>(candidates.size()), [&](int i) {
            Candidate& c = candidates[i];
            c.error = images_.measure(c.kind, c.a, c.b, nullptr, &c.footprint);
        });
    }

    // Pops until a valid, current candidate is applied. Stale candidates at the top are
    // re-measured together (in parallel); the batch size is fixed, so the merge order
    // does not depend on the thread count.
    void applyBest(int step, std::vector<LineMergeRecord>& merges) {
        while (!heap_.empty()) {
            std::pop_heap(heap_.begin(), heap_.end(), worse);
            Candidate best = heap_.back();
            heap_.pop_back();
            if (!skeleton_.valid(best.kind, best.a, best.b)) {
                continue;
            }
            if (!best.stale) {
                apply(best, step, merges);
                return;
            }
            std::vector<Candidate> batch;
            batch.push_back(std::move(best));
            while (!heap_.empty() && static_cast<int>(batch.size()) < kRemeasureBatch &&
                   heap_.front().stale) {
                std::pop_heap(heap_.begin(), heap_.end(), worse);
                if (skeleton_.valid(heap_.back().kind, heap_.back().a, heap_.back().b)) {
                    batch.push_back(std::move(heap_.back()));
                }
                heap_.pop_back();
            }
            measure(batch);
            for (Candidate& c : batch) {
                c.stale = false;
                heap_.push_back(std::move(c));
                std::push_heap(heap_.begin(), heap_.end(), worse);
            }
        }
    }

    void apply(const Candidate& best, int step, std::vector<LineMergeRecord>& merges) {
        std::vector<RasterFrame> tiles;
        totalSquared_ += images_.measure(best.kind, best.a, best.b, &tiles, nullptr);
        totalSquared_ = std::max(totalSquared_, 0.0);
        const LineMergePreview p = skeleton_.preview(best.kind, best.a, best.b);
        const int created = skeleton_.apply(best.kind, best.a, best.b, step);
        images_.commit(tiles, created, p);
        markStale(best, p, tiles);
        std::erase_if(alive_, [&](int i) { return i == best.a || i == best.b; });
        alive_.push_back(created);
        merges.push_back(
            {best.kind, best.a, best.b, created, std::sqrt(totalSquared_ / images_.pixelCount())});
    }

    // Candidates whose footprint or lines the merge touched must be re-measured.
    void markStale(const Candidate& best, const LineMergePreview& p,
                   const std::vector<RasterFrame>& tiles) {
        const std::vector<LineNode>& nodes = skeleton_.nodes();
        for (Candidate& c : heap_) {
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
            for (int v = 0; v < images_.views() && !touched; ++v) {
                touched = overlaps(c.footprint[v], tiles[v].rect);
            }
            c.stale = touched;
        }
    }

    // Keeps the N_cache best.
    void prune() {
        if (static_cast<int>(heap_.size()) > options_.cachedCandidates) {
            std::sort(heap_.begin(), heap_.end(),
                      [&](const Candidate& x, const Candidate& y) { return worse(y, x); });
            heap_.resize(options_.cachedCandidates);
            std::make_heap(heap_.begin(), heap_.end(), worse);
        }
    }

    LineSkeleton& skeleton_;
    LineImages& images_;
    const LineHierarchyOptions& options_;
    std::mt19937_64 random_;
    std::vector<int> alive_;  // live node ids
    std::vector<Candidate> heap_;
    double totalSquared_ = 0.0;
};

}  // namespace

LineHierarchyResult buildLineHierarchy(const std::vector<SkeletonSegment>& segments,
                                       const glm::vec3& color,
                                       const PrimitiveRasterizer& rasterizer,
                                       const LineHierarchyOptions& options,
                                       const PlantLodProgressCallback& progress,
                                       double progressStart, double progressEnd) {
    LineSkeleton skeleton(segments, color);
    LineHierarchyResult result;
    result.widthScale = options.widthScale;
    LineImages images(skeleton, rasterizer, options.widthScale);
    MergeSearch search(skeleton, images, options);
    const int totalSteps = std::max(static_cast<int>(skeleton.nodes().size()) - 1, 1);
    int step = 0;
    while (skeleton.aliveCount() > 1) {
        const std::size_t merged = result.merges.size();
        if (!search.step(step + 1, result.merges)) {
            break;
        }
        step += static_cast<int>(result.merges.size() - merged);
        if (progress && (step % 64 == 0 || skeleton.aliveCount() == 1)) {
            PlantLodProgress p;
            p.stage = "lines";
            p.level = step;
            p.levelCount = totalSteps;
            p.fraction = progressStart + (progressEnd - progressStart) * step / totalSteps;
            progress(p);
        }
    }
    result.nodes = skeleton.nodes();
    return result;
}

}  // namespace sylva
