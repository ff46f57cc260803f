// Weber & Penn 1995, "Creation and Rendering of Realistic Trees": the stem recursion
// (§4.1–4.7 of the paper: curvature, splitting, child placement by down and rotate
// angles, lengths by the shape ratio, radii by ratio and taper, leaves as one more
// level). Departures, on purpose: leaves are distributed to an exact target count
// (the paper's "leaf quality" only scales them), and every stem and clone is its own
// unwelded tube so that an importer can find stems as connected components.
#include "sylva/core/plantlod/PlantGenerator.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "TexelColour.h"

namespace sylva {

namespace {

constexpr float kPi = 3.14159265358979f;

float degrees(float value) {
    return value * kPi / 180.0f;
}

// splitmix64: a small, portable generator (std:: distributions differ between
// standard libraries, which would break byte-identical output).
class Random {
public:
    explicit Random(std::uint64_t seed)
        : state_(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    float uniform() { return float(next() >> 40) * (1.0f / 16777216.0f); }  // [0, 1)
    float symmetric() { return uniform() * 2.0f - 1.0f; }                   // [-1, 1)

private:
    std::uint64_t state_;
};

// Weber & Penn's ShapeRatio(shape, ratio); ratio 1 at the crown base, 0 at the top.
float shapeRatio(TreeShape shape, float ratio) {
    ratio = std::clamp(ratio, 0.0f, 1.0f);
    switch (shape) {
        case TreeShape::Conical:
            return 0.2f + 0.8f * ratio;
        case TreeShape::Spherical:
            return 0.2f + 0.8f * std::sin(kPi * ratio);
        case TreeShape::Hemispherical:
            return 0.2f + 0.8f * std::sin(0.5f * kPi * ratio);
        case TreeShape::Cylindrical:
            return 1.0f;
        case TreeShape::TaperedCylindrical:
            return 0.5f + 0.5f * ratio;
        case TreeShape::Flame:
            return ratio <= 0.7f ? ratio / 0.7f : (1.0f - ratio) / 0.3f;
        case TreeShape::InverseConical:
            return 1.0f - 0.8f * ratio;
        case TreeShape::TendFlame:
            return ratio <= 0.7f ? 0.5f + 0.5f * ratio / 0.7f : 0.5f + 0.5f * (1.0f - ratio) / 0.3f;
    }
    return 1.0f;
}

// Rodrigues rotation of v about the unit axis.
glm::vec3 rotateAbout(const glm::vec3& v, const glm::vec3& axis, float angle) {
    const float c = std::cos(angle);
    const float s = std::sin(angle);
    return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0f - c);
}

// An orthonormal stem frame: `direction` is the stem axis, `side` and `up` span the
// cross-section (parallel-transported along the stem so tubes do not twist).
struct Frame {
    glm::vec3 side{1.0f, 0.0f, 0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    glm::vec3 direction{0.0f, 0.0f, 1.0f};

    void rotate(const glm::vec3& axis, float angle) {
        side = glm::normalize(rotateAbout(side, axis, angle));
        up = glm::normalize(rotateAbout(up, axis, angle));
        direction = glm::normalize(rotateAbout(direction, axis, angle));
        // Re-orthonormalise against float drift over long chains.
        up = glm::normalize(glm::cross(direction, side));
        side = glm::cross(up, direction);
    }
};

// One generated stem (or clone): the axis polyline with radii and its skeleton ids.
struct Stem {
    int level = 0;
    std::vector<glm::vec3> points;
    std::vector<Frame> frames;
    std::vector<float> radii;
    std::vector<int> segments;    // skeleton index of points[i] → points[i + 1]
    float length = 0.0f;          // of the whole stem (clones share their stem's)
    float offsetStart = 0.0f;     // distance from the stem base at points[0]
    float offsetInParent = 0.0f;  // where this stem sits on its parent
    float parentLength = 0.0f;
    float childDensity = 1.0f;  // share of children after splits
};

struct StemStart {
    int level = 0;
    glm::vec3 position{0.0f};
    Frame frame;
    float length = 0.0f;
    float baseRadius = 0.0f;
    int parentSegment = -1;
    float offsetInParent = 0.0f;
    float parentLength = 0.0f;
    // Clone continuation: segments already grown and the stem offset at the start.
    int firstSegment = 0;
    float offsetStart = 0.0f;
    float splitError = 0.0f;
    float childDensity = 1.0f;
};

class TreeBuilder {
public:
    TreeBuilder(const TreeParameters& parameters, std::uint64_t seed)
        : parameters_(parameters), random_(seed) {}

    void build() {
        const StemLevelParameters& trunk = parameters_.levels[0];
        const float scale = parameters_.scale + parameters_.scaleVariation * random_.symmetric();
        StemStart start;
        start.length =
            std::max(0.05f, scale * (trunk.length + trunk.lengthVariation * random_.symmetric()));
        start.baseRadius = start.length * parameters_.ratio;
        start.parentLength = start.length;
        // A slight random lean so two seeds never share the trunk.
        const float azimuth = 2.0f * kPi * random_.uniform();
        start.frame.rotate(glm::vec3(std::cos(azimuth), std::sin(azimuth), 0.0f),
                           degrees(2.0f) * random_.uniform());
        trunkLength_ = start.length;
        pending_.push_back(start);
        // Breadth of the recursion is bounded by the preset; process in FIFO order.
        for (std::size_t i = 0; i < pending_.size(); ++i) {
            grow(pending_[i]);
        }
    }

    std::vector<Stem> stems;
    std::vector<SkeletonSegment> skeleton;

private:
    float radiusAt(const StemStart& stem, float offset) const {
        const float taper = parameters_.levels[std::size_t(stem.level)].taper;
        const float t = std::clamp(offset / stem.length, 0.0f, 1.0f);
        float radius = stem.baseRadius * (1.0f - taper * t);
        if (stem.level == 0) {
            // Weber & Penn's flare: y = max(0, 1 - 8z); r *= 1 + Flare (100^y - 1) / 100.
            const float y = std::max(0.0f, 1.0f - 8.0f * t);
            radius *= 1.0f + parameters_.flare * (std::pow(100.0f, y) - 1.0f) / 100.0f;
        }
        return std::max(radius, 0.0005f);
    }

    // Curvature (paper §4.3): nCurve spread over the segments, or split into a first
    // half and a back-bend half when nCurveBack is set, plus nCurveV noise; then the
    // upward attraction of §4.8.
    void bend(Frame& frame, const StemLevelParameters& level, int stemLevel, int segment,
              int resolution) {
        float bend;
        if (level.curveBack == 0.0f) {
            bend = level.curve / float(resolution);
        } else {
            const float half = std::max(1.0f, float(resolution) / 2.0f);
            bend = (segment < resolution / 2 ? level.curve : level.curveBack) / half;
        }
        bend += level.curveVariation * random_.symmetric() / float(resolution);
        if (segment == 0) {
            bend *= 0.5f;
        }
        frame.rotate(frame.side, bend);
        if (stemLevel >= 2 && parameters_.attractionUp != 0.0f) {
            // Paper §4.8 (AttractionUp): bend towards the sky in proportion to the
            // declination, never past vertical.
            const glm::vec3 axis = glm::cross(frame.direction, glm::vec3(0.0f, 0.0f, 1.0f));
            const float axisLength = glm::length(axis);
            if (axisLength > 1e-4f) {
                const float declination = std::acos(std::clamp(frame.direction.z, -1.0f, 1.0f));
                const float amount = parameters_.attractionUp * declination *
                                     std::abs(std::sin(declination)) / float(resolution);
                frame.rotate(axis / axisLength, std::clamp(amount, -declination, declination));
            }
        }
    }

    // Splitting (paper §4.4): nSegSplits clones per segment, error-diffused; the trunk's
    // base splits happen where the crown begins.
    int clonesAfter(const StemStart& start, const StemLevelParameters& level, int segment,
                    int resolution, float offset, float& splitError) {
        if (segment + 1 >= resolution) {
            return 0;
        }
        if (start.level == 0 && parameters_.baseSplits > 0 &&
            offset >= parameters_.baseSize * start.length && !baseSplitDone_) {
            baseSplitDone_ = true;
            return parameters_.baseSplits;
        }
        if (level.segmentSplits > 0.0f) {
            const float wanted = level.segmentSplits + splitError;
            const int clones = int(std::lround(wanted));
            splitError = wanted - float(clones);
            return clones;
        }
        return 0;
    }

    // The stem split at the end of `segment` (skeleton `index`, point `position`):
    // `clones` deflected continuations and the original with the last deflection, each
    // a new tube (so every clone is alike), queued to grow.
    void split(const StemStart& start, const StemLevelParameters& level, int clones, Frame frame,
               int segment, int index, const glm::vec3& position, float offset, float splitError) {
        const float share = start.childDensity / float(clones + 1);
        const auto continueAs = [&](const Frame& direction) {
            StemStart continuation = start;
            continuation.position = position;
            continuation.frame = direction;
            continuation.parentSegment = index;
            continuation.firstSegment = segment + 1;
            continuation.offsetStart = offset;
            continuation.splitError = splitError;
            continuation.childDensity = share;
            pending_.push_back(continuation);
        };
        const float baseAzimuth = 2.0f * kPi * random_.uniform();
        for (int clone = 0; clone <= clones; ++clone) {
            const float angle =
                std::max(0.0f, level.splitAngle + level.splitAngleVariation * random_.symmetric());
            const float azimuth = baseAzimuth + 2.0f * kPi * float(clone) / float(clones + 1);
            const glm::vec3 axis =
                glm::normalize(rotateAbout(frame.side, frame.direction, azimuth));
            Frame cloneFrame = frame;
            cloneFrame.rotate(axis, angle);
            if (clone == clones) {
                frame = cloneFrame;  // the original stem continues with the last deflection
                continue;
            }
            continueAs(cloneFrame);
        }
        continueAs(frame);
    }

    void grow(StemStart start) {
        const StemLevelParameters& level = parameters_.levels[std::size_t(start.level)];
        const int resolution = std::max(1, level.curveResolution);
        const float segmentLength = start.length / float(resolution);
        Stem stem;
        stem.level = start.level;
        stem.length = start.length;
        stem.offsetStart = start.offsetStart;
        stem.offsetInParent = start.offsetInParent;
        stem.parentLength = start.parentLength;
        stem.childDensity = start.childDensity;
        Frame frame = start.frame;
        glm::vec3 position = start.position;
        stem.points.push_back(position);
        stem.frames.push_back(frame);
        stem.radii.push_back(radiusAt(start, start.offsetStart));
        float splitError = start.splitError;
        int parentSegment = start.parentSegment;
        for (int segment = start.firstSegment; segment < resolution; ++segment) {
            if (segment > 0 || start.level > 0) {
                bend(frame, level, start.level, segment, resolution);
            }
            const glm::vec3 next = position + frame.direction * segmentLength;
            const float offset0 = float(segment) * segmentLength;
            const float offset1 = float(segment + 1) * segmentLength;
            SkeletonSegment piece;
            piece.start = position;
            piece.end = next;
            piece.startRadius = radiusAt(start, offset0);
            piece.endRadius = radiusAt(start, offset1);
            piece.parent = parentSegment;
            const int index = int(skeleton.size());
            skeleton.push_back(piece);
            stem.segments.push_back(index);
            stem.points.push_back(next);
            stem.frames.push_back(frame);
            stem.radii.push_back(piece.endRadius);
            parentSegment = index;
            position = next;
            const int clones = clonesAfter(start, level, segment, resolution, offset1, splitError);
            if (clones > 0) {
                split(start, level, clones, frame, segment, index, next, offset1, splitError);
                break;
            }
        }
        spawnChildren(start, stem);
        stems.push_back(std::move(stem));
    }

    // Children (paper §4.5–4.6): count by level, length by the shape ratio (level 1)
    // or the parent's remaining length, placed along the stem with down and rotate angles.
    void spawnChildren(const StemStart& start, const Stem& stem) {
        const std::size_t childLevel = std::size_t(start.level) + 1;
        if (childLevel >= parameters_.levels.size()) {
            return;
        }
        const StemLevelParameters& child = parameters_.levels[childLevel];
        float count;
        float from = 0.0f;
        if (start.level == 0) {
            count = float(child.branches);
            from = parameters_.baseSize * start.length;
        } else if (start.level == 1) {
            const float lengthMax = parameters_.levels[1].length;
            count = float(child.branches) *
                    (0.2f + 0.8f * (start.length / start.parentLength) / lengthMax);
        } else {
            count =
                float(child.branches) * (1.0f - 0.5f * start.offsetInParent / start.parentLength);
        }
        count *= start.childDensity;
        const float span = start.length - from;
        if (span <= 0.0f || count <= 0.0f) {
            return;
        }
        const float segmentLength =
            start.length /
            float(std::max(1, parameters_.levels[std::size_t(start.level)].curveResolution));
        const float stemStart = stem.points.size() > 1 ? start.offsetStart : start.length;
        const float stemEnd = start.offsetStart + segmentLength * float(stem.points.size() - 1);
        const float first = std::max(from, stemStart);
        if (stemEnd <= first) {
            return;
        }
        const int children = int(std::lround(count * (stemEnd - first) / span));
        for (int i = 0; i < children; ++i) {
            const float offset = first + (stemEnd - first) *
                                             (float(i) + 0.5f + 0.3f * random_.symmetric()) /
                                             float(children);
            const float local = std::clamp((offset - start.offsetStart) / segmentLength, 0.0f,
                                           float(stem.points.size() - 1) - 1e-4f);
            const std::size_t segment = std::size_t(local);
            const float t = local - float(segment);
            const glm::vec3 position = glm::mix(stem.points[segment], stem.points[segment + 1], t);
            const Frame& parentFrame = stem.frames[segment + 1];

            float length;
            if (start.level == 0) {
                const float ratio = (start.length - offset) / (start.length - from);
                length = trunkLength_ *
                         (child.length + child.lengthVariation * random_.symmetric()) *
                         shapeRatio(parameters_.shape, ratio);
            } else {
                length = (child.length + child.lengthVariation * random_.symmetric()) *
                         (start.length - 0.6f * offset);
            }
            if (length <= 0.01f) {
                continue;
            }
            float down;
            if (child.downAngleVariation >= 0.0f) {
                down = child.downAngle + child.downAngleVariation * random_.symmetric();
            } else {
                const float ratio = (start.length - offset) / std::max(1e-3f, start.length - from);
                down = child.downAngle + child.downAngleVariation *
                                             (1.0f - 2.0f * shapeRatio(TreeShape::Conical, ratio));
            }
            if (child.rotate >= 0.0f) {
                rotation_ += child.rotate + child.rotateVariation * random_.symmetric();
            } else {
                rotation_ += kPi + child.rotateVariation * random_.symmetric();
            }
            Frame frame = parentFrame;
            const glm::vec3 tilt =
                glm::normalize(rotateAbout(frame.side, frame.direction, rotation_));
            frame.rotate(tilt, down);

            StemStart next;
            next.level = int(childLevel);
            next.position = position;
            next.frame = frame;
            next.length = length;
            const float parentRadius = radiusAt(start, offset);
            next.baseRadius = std::min(
                parentRadius * 0.9f,
                start.baseRadius * std::pow(length / start.length, parameters_.ratioPower));
            next.parentSegment = stem.segments[segment];
            next.offsetInParent = offset;
            next.parentLength = start.length;
            pending_.push_back(next);
        }
    }

    const TreeParameters& parameters_;
    Random random_;
    std::vector<StemStart> pending_;
    float trunkLength_ = 1.0f;
    float rotation_ = 0.0f;
    bool baseSplitDone_ = false;
};

void appendTube(PlantMesh& mesh, const Stem& stem, int sides) {
    const std::uint32_t base = std::uint32_t(mesh.positions.size());
    float along = 0.0f;
    for (std::size_t i = 0; i < stem.points.size(); ++i) {
        if (i > 0) {
            along += glm::length(stem.points[i] - stem.points[i - 1]);
        }
        const Frame& frame = stem.frames[i];
        for (int k = 0; k <= sides; ++k) {
            const float angle = 2.0f * kPi * float(k % sides) / float(sides);
            const glm::vec3 radial = frame.side * std::cos(angle) + frame.up * std::sin(angle);
            mesh.positions.push_back(stem.points[i] + radial * stem.radii[i]);
            mesh.normals.push_back(radial);
            const float circumference = std::max(1e-3f, 2.0f * kPi * stem.radii[0]);
            mesh.uvs.emplace_back(float(k) / float(sides), along / circumference);
        }
    }
    const std::uint32_t ring = std::uint32_t(sides + 1);
    for (std::uint32_t i = 0; i + 1 < stem.points.size(); ++i) {
        for (std::uint32_t k = 0; k < std::uint32_t(sides); ++k) {
            const std::uint32_t a = base + i * ring + k;
            const std::uint32_t b = a + 1;
            const std::uint32_t c = a + ring;
            const std::uint32_t d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
        }
    }
}

Status validate(const TreeParameters& parameters) {
    const std::string where = "tree parameters '" + parameters.name + "': ";
    if (parameters.levels.empty() || parameters.levels.size() > 5) {
        return Error{where + "levels must have 1 to 5 entries"};
    }
    if (!(parameters.scale > 0.0f)) {
        return Error{where + "scale must be positive"};
    }
    if (!(parameters.ratio > 0.0f)) {
        return Error{where + "ratio must be positive"};
    }
    if (!(parameters.leafScale > 0.0f) || !(parameters.leafScaleX > 0.0f)) {
        return Error{where + "leafScale and leafScaleX must be positive"};
    }
    for (std::size_t i = 0; i < parameters.levels.size(); ++i) {
        const StemLevelParameters& level = parameters.levels[i];
        if (level.curveResolution < 1 || level.curveResolution > 32 || level.radialSegments < 3 ||
            level.radialSegments > 32 || level.branches < 0 || level.branches > 500 ||
            level.segmentSplits < 0.0f || level.segmentSplits > 2.0f) {
            return Error{
                where + "level " + std::to_string(i) +
                ": curveResolution in [1, 32], radialSegments in [3, 32], branches in [0, 500], "
                "segmentSplits in [0, 2]"};
        }
    }
    return Status::success();
}

float smoothstep(float edge0, float edge1, float x) {
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// The presets, one function each (listed in kPresets below).
TreeParameters oakPreset() {
    TreeParameters tree;
    // After the paper's black oak (Table 1), broadened into a round crown.
    tree.shape = TreeShape::Hemispherical;
    tree.baseSize = 0.25f;
    tree.scale = 12.0f;
    tree.scaleVariation = 1.0f;
    tree.ratio = 0.025f;
    tree.ratioPower = 1.3f;
    tree.flare = 1.0f;
    tree.baseSplits = 2;
    tree.levels = {
        {1.0f, 0.0f, 0.95f, 8, 0.0f, 0.0f, degrees(50.0f), 0.3f, degrees(25.0f), degrees(5.0f), 0,
         0, 0, 0, 0, 10},
        {0.6f, 0.1f, 0.9f, 6, degrees(-25.0f), degrees(0.0f), degrees(90.0f), 0.15f, degrees(20.0f),
         0.0f, 36, degrees(50.0f), degrees(-25.0f), degrees(140.0f), degrees(20.0f), 6},
        {0.4f, 0.05f, 1.0f, 3, 0.0f, 0.0f, degrees(60.0f), 0.0f, 0.0f, 0.0f, 28, degrees(45.0f),
         degrees(10.0f), degrees(140.0f), degrees(20.0f), 4},
    };
    tree.leaves = 22;
    tree.leafScale = 0.2f;
    tree.leafScaleX = 0.65f;
    tree.leafDownAngle = degrees(50.0f);
    tree.leafRotate = degrees(137.5f);
    tree.barkColor = {0.10f, 0.075f, 0.05f};
    tree.leafColor = {0.05f, 0.16f, 0.025f};
    tree.attractionUp = 0.5f;
    return tree;
}

TreeParameters coniferPreset() {
    TreeParameters tree;
    // A fir: conical crown, whorls of near-horizontal branches drooping at the base.
    tree.shape = TreeShape::Conical;
    tree.baseSize = 0.12f;
    tree.scale = 16.0f;
    tree.scaleVariation = 1.5f;
    tree.ratio = 0.018f;
    tree.ratioPower = 1.4f;
    tree.flare = 0.5f;
    tree.levels = {
        {1.0f, 0.0f, 1.0f, 12, 0.0f, 0.0f, degrees(8.0f), 0.0f, 0.0f, 0.0f, 0, 0, 0, 0, 0, 8},
        {0.32f, 0.03f, 1.0f, 4, degrees(-10.0f), 0.0f, degrees(15.0f), 0.0f, 0.0f, 0.0f, 70,
         degrees(75.0f), degrees(-25.0f), degrees(137.5f), degrees(10.0f), 4},
        {0.4f, 0.05f, 1.0f, 2, 0.0f, 0.0f, degrees(10.0f), 0.0f, 0.0f, 0.0f, 14, degrees(55.0f),
         degrees(10.0f), degrees(-90.0f), degrees(15.0f), 3},
    };
    tree.leaves = 22;
    tree.leafScale = 0.34f;
    tree.leafScaleX = 0.55f;
    tree.leafDownAngle = degrees(40.0f);
    tree.leafRotate = degrees(-90.0f);
    tree.needles = true;
    tree.barkColor = {0.08f, 0.05f, 0.035f};
    tree.leafColor = {0.015f, 0.07f, 0.025f};
    tree.attractionUp = 0.2f;
    return tree;
}

TreeParameters birchPreset() {
    TreeParameters tree;
    // Slender, white bark, a tall flame-shaped crown with drooping twigs.
    tree.shape = TreeShape::TendFlame;
    tree.baseSize = 0.3f;
    tree.scale = 15.0f;
    tree.scaleVariation = 1.5f;
    tree.ratio = 0.014f;
    tree.ratioPower = 1.2f;
    tree.flare = 0.4f;
    tree.levels = {
        {1.0f, 0.0f, 1.0f, 10, 0.0f, 0.0f, degrees(20.0f), 0.0f, 0.0f, 0.0f, 0, 0, 0, 0, 0, 8},
        {0.35f, 0.05f, 1.0f, 5, degrees(-35.0f), 0.0f, degrees(30.0f), 0.0f, 0.0f, 0.0f, 35,
         degrees(40.0f), degrees(10.0f), degrees(137.5f), degrees(15.0f), 5},
        {0.55f, 0.1f, 1.0f, 4, degrees(-70.0f), 0.0f, degrees(30.0f), 0.0f, 0.0f, 0.0f, 16,
         degrees(40.0f), degrees(10.0f), degrees(140.0f), degrees(20.0f), 3},
    };
    tree.leaves = 18;
    tree.leafScale = 0.14f;
    tree.leafScaleX = 0.7f;
    tree.leafDownAngle = degrees(60.0f);
    tree.leafRotate = degrees(137.5f);
    tree.barkColor = {0.75f, 0.72f, 0.66f};
    tree.leafColor = {0.09f, 0.25f, 0.03f};
    tree.attractionUp = -0.6f;
    return tree;
}

TreeParameters bushPreset() {
    TreeParameters tree;
    // A short stump that fans out at once into many upright stems.
    tree.shape = TreeShape::Hemispherical;
    tree.baseSize = 0.0f;
    tree.scale = 0.4f;
    tree.scaleVariation = 0.05f;
    tree.ratio = 0.09f;
    tree.ratioPower = 1.1f;
    tree.flare = 0.2f;
    tree.levels = {
        {1.0f, 0.0f, 0.5f, 2, 0.0f, 0.0f, degrees(10.0f), 0.0f, 0.0f, 0.0f, 0, 0, 0, 0, 0, 6},
        {4.5f, 0.8f, 0.9f, 5, degrees(-40.0f), 0.0f, degrees(40.0f), 0.15f, degrees(20.0f), 0.0f,
         14, degrees(35.0f), degrees(20.0f), degrees(137.5f), degrees(30.0f), 5},
        {0.45f, 0.1f, 1.0f, 3, 0.0f, 0.0f, degrees(40.0f), 0.0f, 0.0f, 0.0f, 18, degrees(50.0f),
         degrees(15.0f), degrees(140.0f), degrees(20.0f), 3},
    };
    tree.leaves = 12;
    tree.leafScale = 0.09f;
    tree.leafScaleX = 0.6f;
    tree.leafDownAngle = degrees(50.0f);
    tree.leafRotate = degrees(137.5f);
    tree.barkColor = {0.12f, 0.09f, 0.06f};
    tree.leafColor = {0.06f, 0.18f, 0.03f};
    tree.attractionUp = 0.3f;
    return tree;
}

TreeParameters palmPreset() {
    TreeParameters tree;
    // A coconut-like palm: one slender, slightly bent trunk without branches and a
    // crown of drooping fronds at its top, leaflets alternating along each frond.
    tree.shape = TreeShape::Cylindrical;
    tree.baseSize = 0.9f;
    tree.scale = 9.0f;
    tree.scaleVariation = 1.0f;
    tree.ratio = 0.025f;
    tree.ratioPower = 2.0f;
    tree.flare = 0.4f;
    tree.levels = {
        {1.0f, 0.0f, 0.3f, 10, degrees(15.0f), 0.0f, degrees(6.0f), 0.0f, 0.0f, 0.0f, 0, 0, 0, 0, 0,
         8},
        {0.4f, 0.05f, 1.0f, 6, degrees(110.0f), 0.0f, degrees(10.0f), 0.0f, 0.0f, 0.0f, 22,
         degrees(70.0f), degrees(20.0f), degrees(137.5f), degrees(10.0f), 4},
    };
    tree.leaves = 40;
    tree.leafScale = 0.55f;
    tree.leafScaleX = 0.14f;
    tree.leafDownAngle = degrees(65.0f);
    tree.leafRotate = degrees(-90.0f);
    tree.barkColor = {0.22f, 0.17f, 0.12f};
    tree.leafColor = {0.07f, 0.2f, 0.03f};
    return tree;
}

struct Preset {
    const char* name;
    TreeParameters (*make)();
};

constexpr Preset kPresets[] = {{"oak", oakPreset},
                               {"conifer", coniferPreset},
                               {"birch", birchPreset},
                               {"bush", bushPreset},
                               {"palm", palmPreset}};

}  // namespace

std::vector<std::string> PlantGenerator::presetNames() {
    std::vector<std::string> names;
    for (const Preset& preset : kPresets) {
        names.emplace_back(preset.name);
    }
    return names;
}

Result<TreeParameters> PlantGenerator::preset(const std::string& name) {
    for (const Preset& preset : kPresets) {
        if (name == preset.name) {
            TreeParameters tree = preset.make();
            tree.name = name;
            return tree;
        }
    }
    std::string names;
    for (const std::string& known : presetNames()) {
        names += (names.empty() ? "" : ", ") + known;
    }
    return Error{"unknown plant preset '" + name + "' (presets: " + names + ")"};
}

PlantTexture PlantGenerator::drawLeafTexture(int size, glm::vec3 linearColor, bool needles) {
    SYLVA_CHECK(size >= 8 && size <= 4096);
    PlantTexture texture;
    texture.width = size;
    texture.height = size;
    texture.rgba.assign(std::size_t(size) * std::size_t(size) * 4, 0);
    // 4×4 supersampling of an analytic shape; u across (0 = left), v along the leaf
    // (0 = top = tip, 1 = stalk) since rows run from the top.
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            float coverage = 0.0f;
            float shade = 0.0f;
            for (int sy = 0; sy < 4; ++sy) {
                for (int sx = 0; sx < 4; ++sx) {
                    const float u = (float(x) + (float(sx) + 0.5f) / 4.0f) / float(size) * 2.0f -
                                    1.0f;  // [-1, 1]
                    const float v = (float(y) + (float(sy) + 0.5f) / 4.0f) / float(size);  // [0, 1]
                    const float along = 1.0f - v;  // 0 at the stalk, 1 at the tip
                    float inside = 0.0f;
                    float vein = 0.0f;
                    if (!needles) {
                        // Blade: a pointed ellipse, widest at 40 % with a short stalk.
                        const float blade = (along - 0.06f) / 0.94f;
                        const float halfWidth =
                            blade <= 0.0f
                                ? 0.0f
                                : 0.95f * std::pow(std::sin(kPi * std::pow(blade, 0.8f)), 0.9f);
                        const bool stalk = along < 0.08f && std::abs(u) < 0.04f;
                        inside = (std::abs(u) <= halfWidth || stalk) ? 1.0f : 0.0f;
                        // Midrib and paired side veins running to the margin.
                        const float midrib = 1.0f - smoothstep(0.015f, 0.04f, std::abs(u));
                        const float veinPhase = (blade - 0.9f * std::abs(u)) * 7.0f;
                        const float side =
                            1.0f -
                            smoothstep(0.02f, 0.07f, std::abs(veinPhase - std::round(veinPhase)));
                        vein = std::max(midrib, 0.6f * side * (blade > 0.05f ? 1.0f : 0.0f));
                    } else {
                        // A sprig: a central twig with dense needles slanting to the tip.
                        const float twig = std::abs(u) < 0.035f ? 1.0f : 0.0f;
                        const float reach =
                            0.9f * std::sin(kPi * std::clamp(along * 1.05f, 0.0f, 1.0f));
                        const float phase = (along - 0.45f * std::abs(u)) * 24.0f;
                        const float needle =
                            std::abs(phase - std::round(phase)) < 0.2f && std::abs(u) < reach
                                ? 1.0f
                                : 0.0f;
                        inside = std::max(twig, needle);
                        vein = twig;
                    }
                    coverage += inside;
                    shade += inside * (1.0f - 0.45f * vein + 0.15f * std::abs(u));
                }
            }
            std::uint8_t* pixel =
                &texture.rgba[(std::size_t(y) * std::size_t(size) + std::size_t(x)) * 4];
            const float brightness = coverage > 0.0f ? shade / coverage : 1.0f;
            // Veins a little lighter and yellower than the blade.
            const glm::vec3 colour =
                linearColor * brightness + glm::vec3(0.03f, 0.03f, 0.0f) * (1.0f - brightness);
            pixel[0] = linearToTexel(colour.r);
            pixel[1] = linearToTexel(colour.g);
            pixel[2] = linearToTexel(colour.b);
            pixel[3] = std::uint8_t(std::lround(coverage / 16.0f * 255.0f));
        }
    }
    return texture;
}

namespace {

// The leaf-bearing stems (the last stem level) and how many leaves each gets: weighted
// like one more level of children (paper §4.7: Leaves × ShapeRatio(4, offset / parent
// length)) and distributed to the exact target by largest remainders.
struct LeafDistribution {
    std::vector<std::size_t> bearers;  // indices into the stems
    std::vector<int> counts;
    float quality = 1.0f;  // the paper's leaf quality: weight sum / target
};

LeafDistribution distributeLeaves(const TreeParameters& parameters, const std::vector<Stem>& stems,
                                  std::optional<int> leafCount) {
    const int lastLevel = int(parameters.levels.size()) - 1;
    LeafDistribution result;
    std::vector<double> weights;
    for (std::size_t i = 0; i < stems.size(); ++i) {
        const Stem& stem = stems[i];
        if (stem.level != lastLevel || stem.points.size() < 2) {
            continue;
        }
        const float parentRatio =
            stem.parentLength > 0.0f ? stem.offsetInParent / stem.parentLength : 0.0f;
        const float grown =
            float(stem.points.size() - 1) /
            float(std::max(1, parameters.levels[std::size_t(lastLevel)].curveResolution));
        result.bearers.push_back(i);
        weights.push_back(double(parameters.leaves) *
                          shapeRatio(TreeShape::TaperedCylindrical, parentRatio) *
                          stem.childDensity * grown);
    }
    const double weightSum = std::accumulate(weights.begin(), weights.end(), 0.0);
    result.counts.assign(result.bearers.size(), 0);
    int target = leafCount ? *leafCount : int(std::lround(weightSum));
    if (result.bearers.empty() || weightSum <= 0.0) {
        target = 0;
    }
    if (target > 0) {
        std::vector<std::pair<double, std::size_t>> remainders;
        int assigned = 0;
        for (std::size_t i = 0; i < result.bearers.size(); ++i) {
            const double exact = weights[i] / weightSum * double(target);
            result.counts[i] = int(std::floor(exact));
            assigned += result.counts[i];
            remainders.emplace_back(exact - std::floor(exact), i);
        }
        std::stable_sort(remainders.begin(), remainders.end(),
                         [](const auto& a, const auto& b) { return a.first > b.first; });
        for (std::size_t k = 0; assigned < target; ++k, ++assigned) {
            result.counts[remainders[k % remainders.size()].second] += 1;
        }
    }
    result.quality = target > 0 && weightSum > 0.0 ? float(weightSum / double(target)) : 1.0f;
    return result;
}

// One leaf quad at `position` on a stem whose frame there is `frame`: turned about the
// stem by the running `rotation`, tilted down, its face turned towards the sky (the
// paper's leaf bend: the blade's width axis horizontal, perpendicular to the leaf).
void appendLeaf(PlantMesh& leaves, const TreeParameters& parameters, Frame frame,
                const glm::vec3& position, float& rotation, float leafLength, float leafWidth,
                Random& random) {
    rotation += parameters.leafRotate >= 0.0f ? parameters.leafRotate + 0.3f * random.symmetric()
                                              : kPi + 0.3f * random.symmetric();
    const glm::vec3 tilt = glm::normalize(rotateAbout(frame.side, frame.direction, rotation));
    frame.rotate(tilt, parameters.leafDownAngle + 0.2f * random.symmetric());
    glm::vec3 along = frame.direction;
    glm::vec3 across = glm::cross(glm::vec3(0.0f, 0.0f, 1.0f), along);
    if (glm::length(across) < 1e-3f) {
        across = frame.side;
    }
    across = glm::normalize(rotateAbout(glm::normalize(across), along, 0.4f * random.symmetric()));
    glm::vec3 normal = glm::normalize(glm::cross(along, across));
    if (normal.z < 0.0f) {
        normal = -normal;
    }
    const glm::vec3 base = position;
    const glm::vec3 tip = position + along * leafLength;
    const glm::vec3 halfWidth = across * (0.5f * leafWidth);
    const std::uint32_t first = std::uint32_t(leaves.positions.size());
    // Texture: v = 1 at the stalk (bottom row), v = 0 at the tip.
    leaves.positions.insert(leaves.positions.end(),
                            {base - halfWidth, base + halfWidth, tip + halfWidth, tip - halfWidth});
    leaves.uvs.insert(leaves.uvs.end(), {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}});
    leaves.normals.insert(leaves.normals.end(), 4, normal);
    leaves.indices.insert(leaves.indices.end(),
                          {first, first + 1, first + 2, first, first + 2, first + 3});
}

// The leaves of every bearer, spread evenly along it with jitter; the leaf size makes
// up for the leaf quality (fewer leaves than the weights ask for are larger).
PlantMesh makeLeaves(const TreeParameters& parameters, const std::vector<Stem>& stems,
                     const LeafDistribution& distribution, std::uint64_t seed) {
    const float leafLength = parameters.leafScale * std::sqrt(distribution.quality);
    const float leafWidth = leafLength * parameters.leafScaleX;
    PlantMesh leaves;
    leaves.part = PlantPart::Leaf;
    leaves.material = 1;
    leaves.name = "leaves";
    for (std::size_t b = 0; b < distribution.bearers.size(); ++b) {
        const Stem& stem = stems[distribution.bearers[b]];
        Random random(seed * 0x2545F4914F6CDD1Dull +
                      distribution.bearers[b] * 0x9E3779B97F4A7C15ull + 0x1EAF);
        float rotation = 2.0f * kPi * random.uniform();
        const int count = distribution.counts[b];
        for (int i = 0; i < count; ++i) {
            const float local = float(stem.points.size() - 1) *
                                (float(i) + 0.5f + 0.4f * random.symmetric()) / float(count);
            const std::size_t segment =
                std::min(stem.points.size() - 2, std::size_t(std::max(0.0f, local)));
            const float t = std::clamp(local - float(segment), 0.0f, 1.0f);
            const glm::vec3 position = glm::mix(stem.points[segment], stem.points[segment + 1], t);
            appendLeaf(leaves, parameters, stem.frames[segment + 1], position, rotation, leafLength,
                       leafWidth, random);
        }
    }
    return leaves;
}

}  // namespace

Result<PlantModel> PlantGenerator::generate(const TreeParameters& parameters,
                                            const PlantGeneratorOptions& options) {
    if (Status valid = validate(parameters); !valid) {
        return valid.error();
    }
    if (options.leafCount && (*options.leafCount < 0 || *options.leafCount > 2000000)) {
        return Error{"leaf count " + std::to_string(*options.leafCount) +
                     " is outside [0, 2000000]"};
    }
    TreeBuilder builder(parameters, options.seed);
    builder.build();

    PlantModel model;
    model.name = parameters.name;
    PlantMaterial bark;
    bark.name = "bark";
    bark.baseColor = glm::vec4(parameters.barkColor, 1.0f);
    PlantMaterial leaf;
    leaf.name = "leaf";
    leaf.baseColor = glm::vec4(1.0f);
    leaf.alphaMasked = true;
    leaf.alphaCutoff = 0.5f;
    leaf.baseColorTexture =
        drawLeafTexture(options.leafTextureSize, parameters.leafColor, parameters.needles);
    model.materials = {bark, leaf};

    PlantMesh branches;
    branches.part = PlantPart::Branch;
    branches.material = 0;
    branches.name = "bark";
    for (const Stem& stem : builder.stems) {
        appendTube(branches, stem, parameters.levels[std::size_t(stem.level)].radialSegments);
    }
    model.skeleton = builder.skeleton;
    PlantMesh leaves =
        makeLeaves(parameters, builder.stems,
                   distributeLeaves(parameters, builder.stems, options.leafCount), options.seed);
    model.meshes.push_back(std::move(branches));
    if (!leaves.indices.empty()) {
        model.meshes.push_back(std::move(leaves));
    }
    return model;
}

}  // namespace sylva
