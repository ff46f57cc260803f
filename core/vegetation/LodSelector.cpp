#include "sylva/core/vegetation/LodSelector.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <thread>

#include "sylva/core/base/Check.h"
#include "sylva/core/base/ParallelFor.h"

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
    species.ellipsoidCount = static_cast<std::uint32_t>(lod.ellipsoids.size());
    species.lineCount = static_cast<std::uint32_t>(lod.lines.size());

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
        instance.axes[2] = glm::vec3(up * double(p.scale));
        const SpeciesLod& lod = species[p.species];
        instance.center = instance.base + instance.axes[0] * lod.sphereCenter.x +
                          instance.axes[1] * lod.sphereCenter.y +
                          instance.axes[2] * lod.sphereCenter.z;
        instance.radius = lod.sphereRadius * p.scale;
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

namespace {

// The per-instance decision of one frame.
struct Decision {
    std::uint32_t batch = 0, index = 0;
    float error = 0.0f;
    glm::vec3 originView{0.0f};
    std::uint16_t key = 0;   // run key: species × slots + slot
    std::uint16_t key2 = 0;  // second run during a handover (0xFFFF: none)
};

}  // namespace

void LodSelector::select(const std::vector<const InstanceBatch*>& allBatches,
                         const std::vector<SpeciesLod>& species, const Camera& camera,
                         const LodSelectionSettings& settings, LodSelection& out) {
    out.instances.clear();
    out.runs.clear();
    out.consideredInstances = 0;
    out.visibleInstances = 0;
    out.drawnEllipsoids = 0;
    out.drawnLines = 0;

    // Slots per species: kBucketCount primitive buckets, then the mesh, then the
    // billboard levels (at most kBucketCount - 2 of them).
    constexpr int kSlots = kBucketCount + 1 + 16;
    constexpr int kMeshSlot = kBucketCount;
    constexpr int kBillboardSlot = kBucketCount + 1;
    SYLVA_CHECK(species.size() * kSlots < 0xFFFF);

    const glm::dmat3 rotation = camera.viewRotation();
    const glm::mat3 rotationFloat(rotation);
    const double errorPerMetre = settings.pixelAngle / std::max(settings.quality, 1e-6);
    const float halfBand = float(0.5 * settings.transitionBand);
    const float fadeUp = std::exp(halfBand), fadeDown = std::exp(-halfBand);

    // Per batch (tile): drop those whose bounding sphere is outside the frustum or too
    // far for any of its plants to cover minimumPixels.
    std::vector<const InstanceBatch*> batches;
    std::size_t considered = 0;
    for (const InstanceBatch* batch : allBatches) {
        considered += batch->instances.size();
        const glm::vec3 center(rotation *
                               (batch->origin - camera.position + glm::dvec3(batch->boundsCenter)));
        const float r = batch->boundsRadius;
        bool inside = center.z <= r - float(settings.near);
        for (int p = 0; p < 4 && inside; ++p) {
            inside = glm::dot(settings.sidePlanes[p], center) >= -r;
        }
        const float nearest = std::max(glm::length(center) - r, 0.0f);
        const bool large = 2.0f * batch->largestInstanceRadius >=
                           float(settings.minimumPixels * nearest * errorPerMetre);
        const bool withinDistance =
            settings.maximumDistance <= 0.0 || nearest <= settings.maximumDistance;
        if (inside && large && withinDistance && !batch->instances.empty()) {
            batches.push_back(batch);
        }
    }

    // Pass 1 (parallel over chunks of batches): cull, error, run keys.
    std::size_t total = 0;
    std::vector<std::size_t> batchStart(batches.size() + 1, 0);
    for (std::size_t b = 0; b < batches.size(); ++b) {
        batchStart[b] = total;
        total += batches[b]->instances.size();
    }
    batchStart[batches.size()] = total;
    out.consideredInstances = considered;

    const int chunks = std::max(
        1, std::min<int>(int(std::thread::hardware_concurrency()) * 4, int(total / 4096) + 1));
    // Scratch kept between frames (per calling thread): fresh buffers would be paged in
    // again every frame. (The lambdas below run on other threads: they must see this
    // thread's buffers through the references, never name the thread_local itself.)
    thread_local std::vector<std::vector<Decision>> decidedScratch;
    std::vector<std::vector<Decision>>& decided = decidedScratch;
    decided.resize(chunks);
    for (std::vector<Decision>& decisions : decided) {
        decisions.clear();
    }
    const float near = float(settings.near);
    const float smallestError = float(kSmallestError);
    const glm::vec3 planes[4] = {settings.sidePlanes[0], settings.sidePlanes[1],
                                 settings.sidePlanes[2], settings.sidePlanes[3]};
    const float maximumDistance = settings.maximumDistance > 0
                                      ? float(settings.maximumDistance)
                                      : std::numeric_limits<float>::infinity();
    parallelFor(0, chunks, [&](int chunk) {
        const std::size_t first = total * chunk / chunks, last = total * (chunk + 1) / chunks;
        std::vector<Decision>& decisions = decided[chunk];
        decisions.reserve((last - first) / 4 + 16);
        std::size_t b =
            std::upper_bound(batchStart.begin(), batchStart.end(), first) - batchStart.begin() - 1;
        std::size_t i = first;
        while (i < last) {
            while (batchStart[b + 1] <= i) {
                ++b;
            }
            const InstanceBatch& batch = *batches[b];
            const glm::vec3 originView(rotation * (batch.origin - camera.position));
            const std::size_t end = std::min(last, batchStart[b + 1]);
            for (std::size_t k = i - batchStart[b]; k < end - batchStart[b]; ++k) {
                const glm::vec4 sphere = batch.spheres[k];
                const glm::vec3 center = originView + rotationFloat * glm::vec3(sphere);
                const float r = sphere.w;
                if (center.z > r - near || glm::dot(planes[0], center) < -r ||
                    glm::dot(planes[1], center) < -r || glm::dot(planes[2], center) < -r ||
                    glm::dot(planes[3], center) < -r) {
                    continue;
                }
                const float distance = glm::length(center);
                const float error = float(distance * errorPerMetre);
                if (distance > maximumDistance ||
                    2.0f * r < float(settings.minimumPixels) * error) {
                    continue;
                }
                const std::uint32_t speciesIndex = batch.instances[k].species;
                const SpeciesLod& lod = species[speciesIndex];
                Decision d;
                d.batch = std::uint32_t(b);
                d.index = std::uint32_t(k);
                d.error = error;
                d.originView = originView;
                d.key2 = 0xFFFF;
                const std::uint16_t base = std::uint16_t(speciesIndex * kSlots);
                switch (settings.method) {
                    case VegetationMethod::Mesh:
                        d.key = std::uint16_t(base + kMeshSlot);
                        break;
                    case VegetationMethod::Lod: {
                        const bool mesh = settings.closeUpMesh && error < lod.meshError * fadeUp;
                        const bool primitives = !settings.closeUpMesh || lod.meshError <= 0.0f ||
                                                error >= lod.meshError * fadeDown;
                        if (primitives) {
                            d.key = std::uint16_t(base + fastBucketOf(error, smallestError));
                            if (mesh) {
                                d.key2 = std::uint16_t(base + kMeshSlot);
                            }
                        } else {
                            d.key = std::uint16_t(base + kMeshSlot);
                        }
                        break;
                    }
                    case VegetationMethod::Billboard: {
                        // The level whose interval holds the error, and its neighbour in
                        // the fade band.
                        const std::vector<float>& levels = lod.billboardError;
                        if (levels.empty()) {
                            d.key = std::uint16_t(base + kMeshSlot);
                            break;
                        }
                        int level = 0;
                        while (level + 1 < int(levels.size()) && error >= levels[level + 1]) {
                            ++level;
                        }
                        d.key = std::uint16_t(base + kBillboardSlot + level);
                        if (level + 1 < int(levels.size()) && error * fadeUp > levels[level + 1]) {
                            d.key2 = std::uint16_t(base + kBillboardSlot + level + 1);
                        } else if (level > 0 && error * fadeDown < levels[level]) {
                            d.key2 = std::uint16_t(base + kBillboardSlot + level - 1);
                        }
                        break;
                    }
                }
                decisions.push_back(d);
            }
            i = end;
        }
    });

    // Counting sort by run key (two entries for instances in a handover band).
    const std::size_t keys = species.size() * kSlots;
    std::vector<std::uint32_t> counts(keys + 1, 0);
    std::size_t visible = 0;
    for (const std::vector<Decision>& decisions : decided) {
        visible += decisions.size();
        for (const Decision& d : decisions) {
            ++counts[d.key + 1];
            if (d.key2 != 0xFFFF) {
                ++counts[d.key2 + 1];
            }
        }
    }
    out.visibleInstances = visible;
    std::vector<std::uint32_t> start(keys + 1, 0);
    for (std::size_t k = 0; k < keys; ++k) {
        start[k + 1] = start[k] + counts[k + 1];
    }
    const std::size_t drawn = start[keys];
    out.instances.resize(drawn);
    for (std::size_t k = 0; k < keys; ++k) {
        const std::uint32_t count = start[k + 1] - start[k];
        if (count == 0) {
            continue;
        }
        DrawRun run;
        run.species = std::uint32_t(k / kSlots);
        const int slot = int(k % kSlots);
        run.firstInstance = start[k];
        run.instanceCount = count;
        const SpeciesLod& lod = species[run.species];
        if (slot < kBucketCount) {
            run.kind = DrawRun::Kind::Primitives;
            run.bucket = std::uint32_t(slot);
            run.ellipsoids = lod.ellipsoidPrefix[slot];
            run.lines = lod.linePrefix[slot];
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

    // Pass 2 (parallel): write each decision's view transform into its slots. Each chunk
    // claims its slots serially first (cheap), then fills them in parallel.
    thread_local std::vector<std::vector<std::uint32_t>> slotsScratch;
    std::vector<std::vector<std::uint32_t>>& slots = slotsScratch;
    slots.resize(chunks);
    std::vector<std::uint32_t> cursor(start.begin(), start.end() - 1);
    for (int chunk = 0; chunk < chunks; ++chunk) {
        std::vector<std::uint32_t>& s = slots[chunk];
        s.clear();
        s.reserve(2 * decided[chunk].size());
        for (const Decision& d : decided[chunk]) {
            s.push_back(cursor[d.key]++);
            s.push_back(d.key2 != 0xFFFF ? cursor[d.key2]++ : 0xFFFFFFFFu);
        }
    }
    parallelFor(0, chunks, [&](int chunk) {
        const std::vector<Decision>& decisions = decided[chunk];
        for (std::size_t n = 0; n < decisions.size(); ++n) {
            const Decision& d = decisions[n];
            const InstanceBatch::Instance& instance = batches[d.batch]->instances[d.index];
            DrawInstance draw;
            draw.axisX = glm::vec4(rotationFloat * instance.axes[0], d.error);
            draw.axisY = glm::vec4(rotationFloat * instance.axes[1],
                                   float(instance.hash >> 8) / 16777216.0f);
            draw.axisZ = glm::vec4(rotationFloat * instance.axes[2], 0.0f);
            draw.origin = glm::vec4(d.originView + rotationFloat * instance.base, 1.0f);
            draw.tint = glm::vec4(instance.tint, 1.0f);
            out.instances[slots[chunk][2 * n]] = draw;
            if (slots[chunk][2 * n + 1] != 0xFFFFFFFFu) {
                out.instances[slots[chunk][2 * n + 1]] = draw;
            }
        }
    });
}

}  // namespace sylva
