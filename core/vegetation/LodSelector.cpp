#include "sylva/core/vegetation/LodSelector.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "DrawnExtent.h"
#include "sylva/core/base/Check.h"
#include "sylva/core/base/Hash.h"

namespace sylva {

namespace {

// Number of elements of a coarse → fine array (errorMaximum descending) whose
// errorMaximum exceeds `error`: the prefix drawn at that error.
template <typename Primitive>
std::uint32_t prefixAbove(const std::vector<Primitive>& primitives, float error) {
    const auto end =
        std::partition_point(primitives.begin(), primitives.end(),
                             [error](const Primitive& p) { return p.errorMaximum > error; });
    return static_cast<std::uint32_t>(end - primitives.begin());
}

// bucketOf for the per-instance pass: log2 from the float's exponent and a cubic for the
// mantissa (off by at most 0.5 % of a bucket near a boundary: harmless, the prefixes are
// widened by half the transition band, 78 % of a bucket's width at the default band).
int fastBucketOf(float error, float smallestError) {
    const float ratio = error / smallestError;
    if (!(ratio > 1.0f)) {
        return 0;
    }
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(ratio);
    const float exponent = float(int(bits >> 23) - 127);
    const float m = std::bit_cast<float>((bits & 0x007FFFFFu) | 0x3F800000u) - 1.0f;  // [0, 1)
    // log2(1 + m) on [0, 1): cubic through both ends, max error 0.0016.
    const float log2Mantissa = m * (1.4333f + m * (-0.6110f + m * 0.1777f));
    constexpr float kBucketsPerOctave = 3.10628372f;  // 1 / log2(1.25)
    const int bucket = int((exponent + log2Mantissa) * kBucketsPerOctave);
    return std::min(bucket, LodSelector::kBucketCount - 1);
}

}  // namespace

int LodSelector::bucketOf(double error) {
    if (!(error > kSmallestError)) {
        return 0;
    }
    const int bucket = static_cast<int>(std::log(error / kSmallestError) / std::log(kBucketRatio));
    return std::min(bucket, kBucketCount - 1);
}

double LodSelector::bucketLowerError(int bucket) {
    return kSmallestError * std::pow(kBucketRatio, bucket);
}

SpeciesLod LodSelector::describe(const PlantAsset& asset, double transitionBand) {
    const PlantLod& lod = asset.lod;
    SpeciesLod species;
    species.sphereCenter = 0.5f * (lod.boundsMinimum + lod.boundsMaximum);
    species.sphereRadius = 0.5f * glm::length(lod.boundsMaximum - lod.boundsMinimum);
    species.height = lod.boundsMaximum.z;
    species.ellipsoidCount = static_cast<std::uint32_t>(lod.ellipsoids.size());
    species.lineCount = static_cast<std::uint32_t>(lod.lines.size());
    species.drawnRadius = drawnExtentRadius(asset, species.sphereCenter);

    // The finest level's own error (its mean ellipsoid diameter over ~5 pixels, the same
    // rule PlantLodBuilder uses for the coarser levels): closer than this a leaf covers
    // more than the ellipsoid target size and the source mesh looks better.
    double weighted = 0.0, weight = 0.0;
    for (const LodEllipsoid& e : lod.ellipsoids) {
        if (e.level == 0) {
            weighted += double(e.weight) * (e.radii.x + e.radii.y);
            weight += e.weight;
        }
    }
    constexpr double kEllipsoidPixels = 5.0;
    species.meshError = weight > 0.0 ? float(weighted / weight / kEllipsoidPixels) : 0.0f;

    // The prefix of bucket b must hold every primitive any error in the bucket may fade
    // in: errorMaximum > lower(b) × exp(-band / 2).
    const double widen = std::exp(-0.5 * transitionBand);
    species.ellipsoidPrefix.resize(kBucketCount);
    species.linePrefix.resize(kBucketCount);
    species.ellipsoidRadius.assign(kBucketCount, 0.0f);
    for (int b = 0; b < kBucketCount; ++b) {
        const float error = float(bucketLowerError(b) * widen);
        species.ellipsoidPrefix[b] = prefixAbove(lod.ellipsoids, error);
        species.linePrefix[b] = prefixAbove(lod.lines, error);
        // Visible in the bucket: errorMinimum below the bucket's upper end widened by half
        // the band (the last bucket has no upper end).
        const double upper = b + 1 < kBucketCount ? bucketLowerError(b + 1) / widen
                                                  : std::numeric_limits<double>::infinity();
        for (std::uint32_t i = 0; i < species.ellipsoidPrefix[b]; ++i) {
            const LodEllipsoid& e = lod.ellipsoids[i];
            if (double(e.errorMinimum) < upper) {
                species.ellipsoidRadius[b] = std::max(species.ellipsoidRadius[b],
                                                      std::max({e.radii.x, e.radii.y, e.radii.z}));
            }
        }
    }
    return species;
}

InstanceBatch LodSelector::makeBatch(const glm::dvec3& origin,
                                     const std::vector<InstancePlacement>& placements,
                                     const std::vector<SpeciesLod>& species) {
    InstanceBatch batch;
    batch.origin = origin;
    batch.instances.reserve(placements.size());
    batch.spheres.reserve(placements.size());
    for (const InstancePlacement& p : placements) {
        SYLVA_CHECK(p.species < species.size());
        const double sinLat = std::sin(p.latitude), cosLat = std::cos(p.latitude);
        const double sinLon = std::sin(p.longitude), cosLon = std::cos(p.longitude);
        const glm::dvec3 east(-sinLon, cosLon, 0.0);
        const glm::dvec3 north(-sinLat * cosLon, -sinLat * sinLon, cosLat);
        const glm::dvec3 up(cosLat * cosLon, cosLat * sinLon, sinLat);
        // Model +Y points to the heading (clockwise from north), +X to its right.
        const double s = std::sin(p.heading), c = std::cos(p.heading);
        const glm::dvec3 forward = north * c + east * s;
        const glm::dvec3 right = east * c - north * s;
        InstanceBatch::Instance instance;
        instance.base = glm::vec3(p.baseEcef - origin);
        instance.axes[0] = glm::vec3(right * double(p.scale));
        instance.axes[1] = glm::vec3(forward * double(p.scale));
        instance.axes[2] = glm::vec3(up * double(p.scale * p.heightScale));
        const SpeciesLod& lod = species[p.species];
        instance.center = instance.base + instance.axes[0] * lod.sphereCenter.x +
                          instance.axes[1] * lod.sphereCenter.y +
                          instance.axes[2] * lod.sphereCenter.z;
        instance.radius = lod.sphereRadius * p.scale * std::max(1.0f, p.heightScale);
        instance.tint = p.tint;
        instance.species = p.species;
        // A hash of the position's bits: neighbours dither differently.
        std::uint32_t h = std::bit_cast<std::uint32_t>(instance.base.x) * 0x9E3779B1u;
        h ^= std::bit_cast<std::uint32_t>(instance.base.y) * 0x85EBCA77u;
        h ^= std::bit_cast<std::uint32_t>(instance.base.z) * 0xC2B2AE3Du;
        instance.hash = h ^ (h >> 15);
        batch.instances.push_back(instance);
        batch.spheres.emplace_back(instance.center, instance.radius);
    }
    if (!batch.instances.empty()) {
        glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
        for (const InstanceBatch::Instance& instance : batch.instances) {
            low = glm::min(low, instance.center);
            high = glm::max(high, instance.center);
        }
        batch.boundsCenter = 0.5f * (low + high);
        for (const InstanceBatch::Instance& instance : batch.instances) {
            batch.boundsRadius =
                std::max(batch.boundsRadius,
                         glm::distance(batch.boundsCenter, instance.center) + instance.radius);
            batch.largestInstanceRadius = std::max(batch.largestInstanceRadius, instance.radius);
        }
    }
    ContentHash hash;
    hash.add(origin.x).add(origin.y).add(origin.z).add(batch.instances.size());
    static_assert(sizeof(InstanceBatch::Instance) == 21 * 4);  // no padding bytes
    hash.add(batch.instances.data(), batch.instances.size() * sizeof(InstanceBatch::Instance));
    batch.contentHash = hash.value();
    return batch;
}

void LodSelector::setFrustum(LodSelectionSettings& settings, double verticalFov, double aspect) {
    const double ty = std::tan(verticalFov / 2), tx = ty * aspect;
    // Inward normals of the planes through the eye and the image borders (view looks -Z).
    settings.sidePlanes[0] = glm::vec3(glm::normalize(glm::dvec3(1.0, 0.0, -tx)));   // left
    settings.sidePlanes[1] = glm::vec3(glm::normalize(glm::dvec3(-1.0, 0.0, -tx)));  // right
    settings.sidePlanes[2] = glm::vec3(glm::normalize(glm::dvec3(0.0, 1.0, -ty)));   // bottom
    settings.sidePlanes[3] = glm::vec3(glm::normalize(glm::dvec3(0.0, -1.0, -ty)));  // top
}

LodSelector::LodSelector(WorkerPool* pool)
    : pool_(pool != nullptr ? pool : &WorkerPool::shared()) {}

Status LodSelector::checkSpecies(std::size_t index, std::size_t billboardLevels,
                                 const std::string& name) {
    if (index >= std::size_t(kMaxSpecies)) {
        return Error{"plant '" + name + "': species " + std::to_string(index + 1) +
                     " is one too many, the vegetation renderer draws at most " +
                     std::to_string(kMaxSpecies) + " species"};
    }
    if (billboardLevels > std::size_t(kMaxBillboardLevels)) {
        return Error{"plant '" + name + "': " + std::to_string(billboardLevels) +
                     " billboard levels, the vegetation renderer draws at most " +
                     std::to_string(kMaxBillboardLevels) + " per species"};
    }
    return Status::success();
}

namespace {

constexpr int kMeshSlot = LodSelector::kBucketCount;
constexpr int kBillboardSlot = LodSelector::kBucketCount + 1;
constexpr std::uint16_t kNoKey = 0xFFFF;

}  // namespace

// Everything the passes of one select() read: its inputs and per-frame constants.
struct LodSelector::Frame {
    const std::vector<SpeciesLod>& species;
    const Camera& camera;
    const LodSelectionSettings& settings;
    glm::dmat3 rotation;
    glm::mat3 rotationFloat;
    double errorPerMetre = 0.0;
    float fadeUp = 1.0f, fadeDown = 1.0f;  // exp(±band / 2)
    float near = 0.0f;
    float maximumDistance = 0.0f;  // infinity when unlimited
    glm::vec3 planes[4];
    float offsets[4];
    float fixedDistance = 0.0f;  // > 0: orthographic (LodSelectionSettings::fixedDistance)
    std::size_t total = 0;       // instances of the batches that passed the culling
    float minimumDistance = 0.0f;
    // The largest drawnRadius / sphereRadius of the species (≥ 1): widens batch spheres.
    float largestDrawnRatio = 1.0f;
    int chunks = 1;

    Frame(const std::vector<SpeciesLod>& s, const Camera& c, const LodSelectionSettings& set)
        : species(s),
          camera(c),
          settings(set),
          rotation(c.viewRotation()),
          rotationFloat(rotation),
          errorPerMetre(set.pixelAngle / std::max(set.quality, 1e-6)),
          fadeUp(std::exp(float(0.5 * set.transitionBand))),
          fadeDown(std::exp(-float(0.5 * set.transitionBand))),
          near(float(set.near)),
          maximumDistance(set.maximumDistance > 0 ? float(set.maximumDistance)
                                                  : std::numeric_limits<float>::infinity()),
          planes{set.sidePlanes[0], set.sidePlanes[1], set.sidePlanes[2], set.sidePlanes[3]},
          offsets{set.sideOffsets[0], set.sideOffsets[1], set.sideOffsets[2], set.sideOffsets[3]},
          fixedDistance(float(std::max(set.fixedDistance, 0.0))),
          minimumDistance(float(set.minimumDistance)) {
        for (const SpeciesLod& lod : s) {
            largestDrawnRatio = std::max(largestDrawnRatio, drawnRatio(lod));
        }
    }

    // How much larger than the instance sphere the drawn sphere of a species is (≥ 1).
    static float drawnRatio(const SpeciesLod& lod) {
        return lod.sphereRadius > 0.0f ? std::max(1.0f, lod.drawnRadius / lod.sphereRadius) : 1.0f;
    }
};

namespace {

// The run keys of one visible instance at tolerated error `error`: key (and key2 during a
// handover: the mesh next to the finest primitives, or the neighbouring billboard level
// within the fade band). `base` is the species' first key.
void assignKeys(float error, const SpeciesLod& lod, const LodSelectionSettings& settings,
                float fadeUp, float fadeDown, std::uint16_t base, std::uint16_t& key,
                std::uint16_t& key2) {
    key2 = kNoKey;
    switch (settings.method) {
        case VegetationMethod::Mesh:
        case VegetationMethod::Impostors:
            key = std::uint16_t(base + kMeshSlot);
            return;
        case VegetationMethod::Points:
            key = std::uint16_t(base + fastBucketOf(error, float(LodSelector::kSmallestError)));
            return;
        case VegetationMethod::Lod: {
            const bool mesh = settings.closeUpMesh && error < lod.meshError * fadeUp;
            const bool primitives =
                !settings.closeUpMesh || lod.meshError <= 0.0f || error >= lod.meshError * fadeDown;
            if (primitives) {
                key = std::uint16_t(base + fastBucketOf(error, float(LodSelector::kSmallestError)));
                if (mesh) {
                    key2 = std::uint16_t(base + kMeshSlot);
                }
            } else {
                key = std::uint16_t(base + kMeshSlot);
            }
            return;
        }
        case VegetationMethod::DisplacedBillboard:
        case VegetationMethod::Billboard: {
            // The level whose interval holds the error, and its neighbour in the fade band.
            const std::vector<float>& levels = lod.billboardError;
            if (levels.empty()) {
                key = std::uint16_t(base + kMeshSlot);
                return;
            }
            int level = 0;
            while (level + 1 < int(levels.size()) && error >= levels[level + 1]) {
                ++level;
            }
            key = std::uint16_t(base + kBillboardSlot + level);
            if (level + 1 < int(levels.size()) && error * fadeUp > levels[level + 1]) {
                key2 = std::uint16_t(base + kBillboardSlot + level + 1);
            } else if (level > 0 && error * fadeDown < levels[level]) {
                key2 = std::uint16_t(base + kBillboardSlot + level - 1);
            }
            return;
        }
    }
}

}  // namespace

void LodSelector::select(const std::vector<const InstanceBatch*>& allBatches,
                         const std::vector<SpeciesLod>& species, const Camera& camera,
                         const LodSelectionSettings& settings, LodSelection& out) {
    SYLVA_CHECK(species.size() <= std::size_t(kMaxSpecies));
    for (const SpeciesLod& lod : species) {
        SYLVA_CHECK(lod.billboardError.size() <= std::size_t(kMaxBillboardLevels));
    }
    out.instances.clear();
    out.runs.clear();
    out.visibleInstances = 0;
    out.drawnEllipsoids = 0;
    out.drawnLines = 0;
    out.occludedInstances = 0;

    Frame frame(species, camera, settings);
    out.consideredInstances = cullBatches(allBatches, frame);
    frame.total = batchStart_.back();
    frame.chunks =
        std::max(1, std::min<int>(pool_->threadCount() * 4, int(frame.total / 4096) + 1));

    // Pass 1 (parallel over chunks of instances): cull, error, run keys.
    decided_.resize(std::size_t(frame.chunks));
    for (std::vector<Decision>& decisions : decided_) {
        decisions.clear();
    }
    occluded_.assign(std::size_t(frame.chunks), 0);
    pool_->run(frame.chunks, [&](int chunk) { decideChunk(chunk, frame); });
    out.occludedInstances = occludedBatchInstances_;
    for (std::size_t hidden : occluded_) {
        out.occludedInstances += hidden;
    }

    sortRuns(frame, out);
    writeInstances(frame, out);
}

// Per batch (tile): keeps those whose bounding sphere is inside the frustum and near
// enough for one of its plants to cover minimumPixels. Returns the instances considered.
std::size_t LodSelector::cullBatches(const std::vector<const InstanceBatch*>& allBatches,
                                     const Frame& frame) {
    const LodSelectionSettings& settings = frame.settings;
    batches_.clear();
    batchStart_.clear();
    occludedBatchInstances_ = 0;
    std::size_t considered = 0, total = 0;
    for (const InstanceBatch* batch : allBatches) {
        considered += batch->instances.size();
        const glm::vec3 center(frame.rotation * (batch->origin - frame.camera.position +
                                                 glm::dvec3(batch->boundsCenter)));
        const float r = batch->boundsRadius;
        bool inside = center.z <= r - float(settings.near);
        for (int p = 0; p < 4 && inside; ++p) {
            inside = glm::dot(settings.sidePlanes[p], center) + frame.offsets[p] >= -r;
        }
        const float nearest = frame.fixedDistance > 0.0f ? frame.fixedDistance
                                                         : std::max(glm::length(center) - r, 0.0f);
        const bool large = 2.0f * batch->largestInstanceRadius >=
                           float(settings.minimumPixels * nearest * frame.errorPerMetre);
        const bool withinDistance =
            settings.maximumDistance <= 0.0 || nearest <= settings.maximumDistance;
        const bool beyondMinimum = glm::length(center) + r > frame.minimumDistance;
        if (inside && large && withinDistance && beyondMinimum && !batch->instances.empty() &&
            settings.occlusion != nullptr &&
            settings.occlusion->hidden(
                center, r + batch->largestInstanceRadius * (frame.largestDrawnRatio - 1.0f))) {
            occludedBatchInstances_ += batch->instances.size();
            continue;
        }
        if (inside && large && withinDistance && beyondMinimum && !batch->instances.empty()) {
            batches_.push_back(batch);
            batchStart_.push_back(total);
            total += batch->instances.size();
        }
    }
    batchStart_.push_back(total);
    return considered;
}

// Pass 1 over instances [total × chunk / chunks, total × (chunk + 1) / chunks) of the
// kept batches: frustum, near and size culling per instance, then the run keys.
void LodSelector::decideChunk(int chunk, const Frame& frame) {
    const std::size_t first = frame.total * std::size_t(chunk) / std::size_t(frame.chunks);
    const std::size_t last = frame.total * std::size_t(chunk + 1) / std::size_t(frame.chunks);
    std::vector<Decision>& decisions = decided_[std::size_t(chunk)];
    decisions.reserve((last - first) / 4 + 16);
    const float minimumPixels = float(frame.settings.minimumPixels);
    const glm::vec3* planes = frame.planes;
    const float* offsets = frame.offsets;
    const DepthPyramid* occlusion = frame.settings.occlusion;
    std::size_t b =
        std::upper_bound(batchStart_.begin(), batchStart_.end(), first) - batchStart_.begin() - 1;
    for (std::size_t i = first; i < last;) {
        while (batchStart_[b + 1] <= i) {
            ++b;
        }
        const InstanceBatch& batch = *batches_[b];
        const glm::vec3 originView(frame.rotation * (batch.origin - frame.camera.position));
        const std::size_t end = std::min(last, batchStart_[b + 1]);
        for (std::size_t k = i - batchStart_[b]; k < end - batchStart_[b]; ++k) {
            const glm::vec4 sphere = batch.spheres[k];
            const glm::vec3 center = originView + frame.rotationFloat * glm::vec3(sphere);
            const float r = sphere.w;
            if (center.z > r - frame.near || glm::dot(planes[0], center) + offsets[0] < -r ||
                glm::dot(planes[1], center) + offsets[1] < -r ||
                glm::dot(planes[2], center) + offsets[2] < -r ||
                glm::dot(planes[3], center) + offsets[3] < -r) {
                continue;
            }
            const float distance =
                frame.fixedDistance > 0.0f ? frame.fixedDistance : glm::length(center);
            const float error = float(distance * frame.errorPerMetre);
            if (distance > frame.maximumDistance || 2.0f * r < minimumPixels * error ||
                distance <= frame.minimumDistance) {
                continue;
            }
            const std::uint32_t speciesIndex = batch.instances[k].species;
            if (occlusion != nullptr &&
                occlusion->hidden(center, r * Frame::drawnRatio(frame.species[speciesIndex]))) {
                ++occluded_[std::size_t(chunk)];
                continue;
            }
            Decision d;
            d.batch = std::uint32_t(b);
            d.index = std::uint32_t(k);
            d.error = error;
            d.originView = originView;
            assignKeys(error, frame.species[speciesIndex], frame.settings, frame.fadeUp,
                       frame.fadeDown, std::uint16_t(speciesIndex * kSlotsPerSpecies), d.key,
                       d.key2);
            decisions.push_back(d);
        }
        i = end;
    }
}

// Counting sort by run key (two entries for instances in a handover band): the first
// instance of every key in start_, one DrawRun per non-empty key.
void LodSelector::sortRuns(const Frame& frame, LodSelection& out) {
    const std::size_t keys = frame.species.size() * kSlotsPerSpecies;
    start_.assign(keys + 1, 0);  // counts of key k in start_[k + 1] first
    std::size_t visible = 0;
    for (const std::vector<Decision>& decisions : decided_) {
        visible += decisions.size();
        for (const Decision& d : decisions) {
            ++start_[d.key + 1];
            if (d.key2 != kNoKey) {
                ++start_[d.key2 + 1];
            }
        }
    }
    out.visibleInstances = visible;
    for (std::size_t k = 0; k < keys; ++k) {
        start_[k + 1] += start_[k];
    }
    out.instances.resize(start_[keys]);
    for (std::size_t k = 0; k < keys; ++k) {
        const std::uint32_t count = start_[k + 1] - start_[k];
        if (count == 0) {
            continue;
        }
        DrawRun run;
        run.species = std::uint32_t(k / kSlotsPerSpecies);
        const int slot = int(k % kSlotsPerSpecies);
        run.firstInstance = start_[k];
        run.instanceCount = count;
        const SpeciesLod& lod = frame.species[run.species];
        if (slot < kBucketCount) {
            run.kind = DrawRun::Kind::Primitives;
            run.bucket = std::uint32_t(slot);
            run.ellipsoids = lod.ellipsoidPrefix[std::size_t(slot)];
            run.lines = lod.linePrefix[std::size_t(slot)];
            out.drawnEllipsoids += std::size_t(run.ellipsoids) * count;
            out.drawnLines += std::size_t(run.lines) * count;
        } else if (slot == kMeshSlot) {
            run.kind = DrawRun::Kind::Mesh;
        } else {
            run.kind = DrawRun::Kind::Billboard;
            run.bucket = std::uint32_t(slot - kBillboardSlot);
        }
        out.runs.push_back(run);
    }
}

// Pass 2: each decision's view transform into its slots. The slots are claimed serially
// in chunk order (cheap; it keeps every run in instance order), then filled in parallel.
void LodSelector::writeInstances(const Frame& frame, LodSelection& out) {
    slots_.resize(std::size_t(frame.chunks));
    std::vector<std::uint32_t>& cursor = start_;  // start_ is not needed after this
    for (int chunk = 0; chunk < frame.chunks; ++chunk) {
        std::vector<std::uint32_t>& s = slots_[std::size_t(chunk)];
        s.clear();
        s.reserve(2 * decided_[std::size_t(chunk)].size());
        for (const Decision& d : decided_[std::size_t(chunk)]) {
            s.push_back(cursor[d.key]++);
            s.push_back(d.key2 != kNoKey ? cursor[d.key2]++ : 0xFFFFFFFFu);
        }
    }
    const glm::mat3& rotation = frame.rotationFloat;
    pool_->run(frame.chunks, [&](int chunk) {
        const std::vector<Decision>& decisions = decided_[std::size_t(chunk)];
        const std::vector<std::uint32_t>& s = slots_[std::size_t(chunk)];
        for (std::size_t n = 0; n < decisions.size(); ++n) {
            const Decision& d = decisions[n];
            const InstanceBatch::Instance& instance = batches_[d.batch]->instances[d.index];
            DrawInstance draw;
            draw.axisX = glm::vec4(rotation * instance.axes[0], d.error);
            draw.axisY =
                glm::vec4(rotation * instance.axes[1], float(instance.hash >> 8) / 16777216.0f);
            draw.axisZ = glm::vec4(rotation * instance.axes[2], 0.0f);
            draw.origin = glm::vec4(d.originView + rotation * instance.base, 1.0f);
            draw.tint = glm::vec4(instance.tint, 1.0f);
            out.instances[s[2 * n]] = draw;
            if (s[2 * n + 1] != 0xFFFFFFFFu) {
                out.instances[s[2 * n + 1]] = draw;
            }
        }
    });
}

}  // namespace sylva
