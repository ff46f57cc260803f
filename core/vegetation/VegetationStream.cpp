#include "sylva/core/vegetation/VegetationStream.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/sources/plants/InstanceTileCodec.h"

namespace sylva {

namespace {

constexpr double kPi = std::numbers::pi;

constexpr double kMetresPerRadian =
    6367000.0;                  // mean meridian radius: distances for selection only
constexpr int kRefinement = 2;  // levels finer than the coarse level near the camera
constexpr int kFinestLevel = 20;
constexpr std::uint64_t kKeepFrames = 8;  // frames an unused batch is kept

// Approximate ground distance (metres) from a point to a tile's bounds.
double distanceToTile(double latitude, double longitude, const TileKey& key) {
    const double nearestLatitude = std::clamp(latitude, key.south(), key.north());
    double dLongitude = 0.0;
    if (longitude < key.west()) {
        dLongitude = std::min(key.west() - longitude, longitude + 2 * kPi - key.east());
    } else if (longitude > key.east()) {
        dLongitude = std::min(longitude - key.east(), key.west() + 2 * kPi - longitude);
    }
    const double north = (latitude - nearestLatitude) * kMetresPerRadian;
    const double east = std::max(dLongitude, 0.0) * kMetresPerRadian * std::cos(nearestLatitude);
    return std::sqrt(north * north + east * east);
}

// The tile's priority by screen importance on the terrain's scale (FrameWantedSet): the
// clipmap ring level whose ring holds the tile's nearest point (ring i spans view
// distances pi R 2^-(i+1) .. pi R 2^-i), so instance tiles near the camera come before
// far terrain detail, and far ones after the terrain levels around them.
int screenPriority(double latitude, double longitude, double heightAboveGround,
                   const TileKey& key) {
    const double ground = distanceToTile(latitude, longitude, key);
    const double distance = std::max(std::hypot(ground, heightAboveGround), 1.0);
    return std::clamp(int(std::floor(std::log2(kPi * kMetresPerRadian / distance))), 0, 30);
}

void collect(const TileKey& key, double latitude, double longitude, double radius, int finest,
             std::vector<TileKey>& out) {
    const double distance = distanceToTile(latitude, longitude, key);
    if (distance > radius) {
        return;
    }
    const double size = (key.north() - key.south()) * kMetresPerRadian;
    if (key.level < finest && distance < size) {
        for (int dy = 0; dy < 2; ++dy) {
            for (int dx = 0; dx < 2; ++dx) {
                collect(TileKey{key.level + 1, 0, key.x * 2 + dx, key.y * 2 + dy}, latitude,
                        longitude, radius, finest, out);
            }
        }
        return;
    }
    out.push_back(key);
}

}  // namespace

std::vector<TileKey> VegetationStream::tilesAround(double latitude, double longitude, double radius,
                                                   int minimumLevel) {
    std::vector<TileKey> out;
    if (!(radius > 0.0)) {
        return out;
    }
    // The coarse level: tiles about half the radius high (at least the source's minimum).
    const double wanted = std::max(radius / 2.0, 50.0);
    int level = int(std::floor(std::log2(kPi * kMetresPerRadian / wanted)));
    level = std::clamp(level, std::max(minimumLevel, 0), kFinestLevel);
    const int finest = std::min(level + kRefinement, kFinestLevel);
    const double tileAngle = kPi / double(TileKey::rows(level));
    const double latitudeRadius = radius / kMetresPerRadian;
    const double longitudeRadius = std::min(
        kPi,
        radius / (kMetresPerRadian *
                  std::max(std::cos(std::min(std::abs(latitude) + latitudeRadius, kPi / 2 - 1e-6)),
                           1e-6)));
    const int rows = TileKey::rows(level), columns = TileKey::columns(level, 0);
    const int yFirst = std::clamp(
        int(std::floor((kPi / 2 - (latitude + latitudeRadius)) / tileAngle)), 0, rows - 1);
    const int yLast = std::clamp(
        int(std::floor((kPi / 2 - (latitude - latitudeRadius)) / tileAngle)), 0, rows - 1);
    const int span = std::min(columns, int(std::ceil(2 * longitudeRadius / tileAngle)) + 2);
    const int xCentre = int(std::floor((longitude + kPi) / tileAngle));
    for (int y = yFirst; y <= yLast; ++y) {
        for (int i = -span / 2 - 1; i <= span / 2 + 1 && i - (-span / 2 - 1) < columns; ++i) {
            const int x = ((xCentre + i) % columns + columns) % columns;
            collect(TileKey{level, 0, x, y}, latitude, longitude, radius, finest, out);
        }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

bool VegetationStream::grow(const PlantSeasons& seasons, const PlantDate& date, double modelHeight,
                            InstancePlacement& placement) {
    if (!seasons.planted()) {
        return true;
    }
    const std::optional<GrowthScale> scale = seasons.scaleAt(date, std::max(modelHeight, 1e-3));
    if (!scale || scale->crown < 1e-3 || scale->height < 1e-3) {
        return false;
    }
    placement.scale = float(placement.scale * scale->crown);
    placement.heightScale = float(scale->height / scale->crown);
    return true;
}

Result<std::vector<const InstanceBatch*>> VegetationStream::update(
    const std::vector<VegetationStreamLayer>& layers, TileProvider& provider, const Camera& camera,
    const std::vector<SpeciesLod>& species, const VegetationStreamSettings& settings) {
    ++frame_;
    statistics_ = {};
    if (const std::string date = settings.date ? settings.date->text() : std::string();
        date != dateOfBatches_) {
        batches_.clear();  // grown for another date
        dateOfBatches_ = date;
    }
    std::vector<const InstanceBatch*> out;
    // Streaming radius: where the largest plant still covers minimumPixels, at most the
    // maximum distance, and measured along the ground.
    double largest = 0.0;
    for (const SpeciesLod& lod : species) {
        largest = std::max(largest, double(lod.sphereRadius));
    }
    const double limit = settings.maximumDistance > 0 ? settings.maximumDistance
                                                      : VegetationStreamSettings::kDefaultDistance;
    const double visible =
        2.0 * largest * 1.3 / (std::max(settings.minimumPixels, 0.1) * settings.pixelAngle);
    const double distance = std::min(limit, visible);
    statistics_.distance = distance;
    for (const VegetationStreamLayer& layer : layers) {
        const double height = std::max(settings.heightAboveGround, 0.0);
        const double ground =
            height < distance ? std::sqrt(distance * distance - height * height) : 0.0;
        const std::vector<TileKey> keys =
            tilesAround(camera.geodetic.latitude, camera.geodetic.longitude, ground,
                        layer.source->minimumLevel());
        statistics_.wantedTiles += keys.size();
        for (const TileKey& key : keys) {
            const auto id = std::make_pair(layer.source, key);
            auto found = batches_.find(id);
            if (found == batches_.end()) {
                TilePointer tile;
                if (settings.wait) {
                    Result<TilePointer> produced = provider.tile(*layer.source, key);
                    if (!produced) {
                        return produced.error();
                    }
                    tile = produced.value();
                } else {
                    TileLookup lookup =
                        provider.tryGet(*layer.source, key,
                                        screenPriority(camera.geodetic.latitude,
                                                       camera.geodetic.longitude, height, key));
                    if (lookup.state == TileLookup::State::Failed) {
                        return lookup.error;
                    }
                    if (lookup.state != TileLookup::State::Ready) {
                        continue;
                    }
                    tile = lookup.tile;
                }
                Result<std::vector<PlantInstance>> instances = InstanceTileCodec::decode(*tile);
                if (!instances) {
                    return instances.error();
                }
                std::vector<InstancePlacement> placements;
                placements.reserve(instances.value().size());
                for (const PlantInstance& instance : instances.value()) {
                    if (instance.species >= layer.species.size() ||
                        layer.species[instance.species] < 0) {
                        continue;
                    }
                    InstancePlacement p;
                    p.latitude = instance.latitude;
                    p.longitude = instance.longitude;
                    // Sunk a little: the terrain drawn may sit a few decimetres off the
                    // sampled elevation, and a floating stem is worse than a buried one.
                    p.baseEcef = Ellipsoid::toEcef(
                        {instance.latitude, instance.longitude, instance.height - 0.3});
                    p.heading = instance.rotation;
                    p.scale = instance.scale;
                    p.tint = instance.tint;
                    p.species = std::uint32_t(layer.species[instance.species]);
                    if (settings.date && !grow(layer.source->seasons(), *settings.date,
                                               species[p.species].height, p)) {
                        continue;  // not planted yet
                    }
                    placements.push_back(p);
                }
                const double centreLatitude = 0.5 * (key.north() + key.south());
                const double centreLongitude = 0.5 * (key.west() + key.east());
                const double originHeight =
                    instances.value().empty() ? 0.0 : instances.value().front().height;
                auto batch = std::make_shared<InstanceBatch>(LodSelector::makeBatch(
                    Ellipsoid::toEcef({centreLatitude, centreLongitude, originHeight}), placements,
                    species));
                found = batches_.emplace(id, Entry{std::move(batch), 0}).first;
            }
            found->second.lastUsed = frame_;
            ++statistics_.readyTiles;
            statistics_.instances += found->second.batch->instances.size();
            out.push_back(found->second.batch.get());
        }
    }
    for (auto it = batches_.begin(); it != batches_.end();) {
        it = it->second.lastUsed + kKeepFrames < frame_ ? batches_.erase(it) : std::next(it);
    }
    return out;
}

}  // namespace sylva
