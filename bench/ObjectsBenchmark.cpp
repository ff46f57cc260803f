#include "sylva/bench/ObjectsBenchmark.h"
#include "sylva/bench/BenchmarkMetrics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

#include <unistd.h>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scene/CameraNavigation.h"
#include "sylva/core/scheduler/Scheduler.h"
#include "sylva/core/sources/objects/BuildingsSource.h"
#include "sylva/core/sources/objects/ObjectsSource.h"
#include "sylva/core/sources/objects/WalkerCollision.h"
#include "sylva/core/sources/raster/HypsometricSource.h"
#include "sylva/core/sources/raster/NoiseSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::bench {

using namespace sylva::render;
using render::Image;

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kCentreLatitude = 46.0 * kDegree;
constexpr double kCentreLongitude = 8.0 * kDegree;
constexpr double kAltitudes[] = {800e3, 100e3, 10e3, 1e3, 50.0};  // as bench terrain

NoiseParameters relief() {  // the terrain benchmark's DEM
    NoiseParameters parameters;
    parameters.seed = 7;
    parameters.amplitude = 3000;
    parameters.baseWavelength = 3.0e6;
    parameters.ridges = 0.6;
    parameters.ridgeWavelength = 3.0e5;
    parameters.roughness = 0.7;
    return parameters;
}

std::vector<Camera> flight(const NoiseSource& noise, int framesPerSegment) {
    std::vector<Camera> frames;
    const int segments = int(std::size(kAltitudes)) - 1;
    const int total = segments * framesPerSegment + 1;
    for (int frame = 0; frame < total; ++frame) {
        const double progress = double(frame) / (total - 1);
        const int segment = std::min(frame / framesPerSegment, segments - 1);
        const double local = double(frame - segment * framesPerSegment) / framesPerSegment;
        const double altitude = std::exp(std::log(kAltitudes[segment]) * (1 - local) +
                                         std::log(kAltitudes[segment + 1]) * local);
        const double latitude = kCentreLatitude - 0.6 * kDegree * (1 - progress);
        const double longitude = kCentreLongitude + 0.2 * kDegree * (1 - progress);
        const double pitch = (-85.0 + 75.0 * std::pow(progress, 0.7)) * kDegree;
        const double ground = noise.height(Ellipsoid::surfaceNormal(latitude, longitude), 1.0);
        Camera camera;
        camera.geodetic = {latitude, longitude, std::max(ground, 0.0) + altitude};
        camera.position = Ellipsoid::toEcef(camera.geodetic);
        camera.axes = Camera::axesFromAngles(camera.geodetic, 10 * kDegree, pitch, 0.0);
        camera.verticalFov = 60 * kDegree;
        frames.push_back(camera);
    }
    return frames;
}

// A generated city: `count` rectangles of 8–20 m on a jittered 30 m grid south of the
// flight's end (where the last frames look), heights 4–40 m, every third with a hip roof.
std::filesystem::path writeCity(const std::filesystem::path& folder, int count) {
    const auto path = folder / "city.geojson";
    std::ofstream out(path);
    out << R"({"type":"FeatureCollection","features":[)";
    const int side = int(std::ceil(std::sqrt(double(count))));
    const double east =
        Ellipsoid::primeVerticalRadius(kCentreLatitude) * std::cos(kCentreLatitude) * kDegree;
    const double north = Ellipsoid::meridionalRadius(kCentreLatitude) * kDegree;
    std::mt19937 random(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    char text[160];
    for (int i = 0; i < count; ++i) {
        const double x = (i % side - side / 2) * 30.0 + 4 * unit(random);
        const double y = (i / side - side / 2) * 30.0 + 4 * unit(random);
        const double w = 8 + 12 * unit(random), d = 8 + 12 * unit(random);
        std::string ring;
        for (int k = 0; k <= 4; ++k) {
            const double cx = (k == 1 || k == 2) ? w / 2 : -w / 2;
            const double cy = (k == 2 || k == 3) ? d / 2 : -d / 2;
            std::snprintf(text, sizeof text, "%s[%.8f,%.8f]", k ? "," : "", 8.0 + (x + cx) / east,
                          46.0 + (y + cy) / north);
            ring += text;
        }
        std::snprintf(text, sizeof text, R"(%s{"type":"Feature","id":%d,"properties":{"h":%.1f,)",
                      i ? "," : "", i + 1, 4 + 36 * unit(random) * unit(random));
        out << text << R"("roof":")" << (i % 3 == 0 ? "hip" : "flat")
            << R"("},"geometry":{"type":"Polygon","coordinates":[[)" << ring << "]]}}";
    }
    out << "]}";
    return path;
}

// Turbine sites on a 250 m grid around the flight's end.
std::filesystem::path writeTurbineSites(const std::filesystem::path& folder, int count) {
    const auto path = folder / "turbines.geojson";
    std::ofstream out(path);
    out << R"({"type":"FeatureCollection","features":[)";
    const int side = int(std::ceil(std::sqrt(double(count))));
    const double east =
        Ellipsoid::primeVerticalRadius(kCentreLatitude) * std::cos(kCentreLatitude) * kDegree;
    const double north = Ellipsoid::meridionalRadius(kCentreLatitude) * kDegree;
    char text[200];
    for (int i = 0; i < count; ++i) {
        const double x = (i % side - side / 2) * 250.0, y = (i / side - side / 2) * 250.0 - 3000;
        std::snprintf(text, sizeof text,
                      R"(%s{"type":"Feature","id":%d,"properties":{"angle":%d},"geometry":)"
                      R"({"type":"Point","coordinates":[%.8f,%.8f]}})",
                      i ? "," : "", i + 1, (i * 37) % 120, 8.0 + x / east, 46.0 + y / north);
        out << text;
    }
    out << "]}";
    return path;
}

// A turbine as OBJ: tower, nacelle and a box standing for the rotor's disc (OBJ groups
// turn about +Z, so the rotor box turns horizontally here: only the drawing cost counts).
std::filesystem::path writeTurbineModel(const std::filesystem::path& folder) {
    const auto path = folder / "turbine.obj";
    std::ofstream out(path);
    int base = 1;
    const auto box = [&](const char* name, double x0, double x1, double y0, double y1, double z0,
                         double z1) {
        out << "o " << name << "\n";
        for (int i = 0; i < 8; ++i) {
            out << "v " << (i & 1 ? x1 : x0) << " " << (i & 2 ? y1 : y0) << " " << (i & 4 ? z1 : z0)
                << "\n";
        }
        const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                 {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto& f : faces) {
            out << "f " << base + f[0] << " " << base + f[1] << " " << base + f[2] << " "
                << base + f[3] << "\n";
        }
        base += 8;
    };
    box("tower", -2, 2, -2, 2, 0, 78.5);
    box("nacelle", -1.5, 1.5, -6, 2, 78.5, 81.5);
    box("rotor", -40, 40, 2.5, 3.5, 79, 81);
    return path;
}

// One timed frame of one scene: its wall time and what it cost the tile caches.
struct FrameSample {
    double seconds = 0;
    std::size_t meshTilesBuilt = 0;  // MeshRenderer tiles built (not resident before)
    std::size_t tilesProduced = 0;   // Scheduler misses during the frame
    std::size_t tilesEvicted = 0;    // Scheduler evictions during the frame
};

// Frame samples per scene (terrain alone, with the city, with the farm). Every scene
// flies the whole flight once untimed (tiles, meshes, shader variants, shadow caches),
// then the timed frames interleave the scenes camera by camera, the first scene of each
// camera rotating: the scene drawn first at a camera pays the clipmap's move to it, and
// a change in the machine's load during the run falls on all three alike. (Timing the
// scenes one after another made the terrain alone, flown first, the slowest: ratios
// below 1.)
Result<std::vector<std::vector<FrameSample>>> fly(SceneRenderer& renderer,
                                                  const std::vector<TerrainLayers>& scenes,
                                                  Scheduler& scheduler,
                                                  const std::vector<Camera>& frames,
                                                  const RenderSettings& settings) {
    for (const TerrainLayers& layers : scenes) {
        for (const Camera& camera : frames) {
            if (Result<Image> image = renderer.render(layers, scheduler, camera, settings);
                !image) {
                return image.error();
            }
        }
    }
    std::vector<std::vector<FrameSample>> samples(scenes.size());
    for (std::size_t frame = 0; frame < frames.size(); ++frame) {
        for (std::size_t k = 0; k < scenes.size(); ++k) {
            const std::size_t scene = (frame + k) % scenes.size();
            const SchedulerStatistics before = scheduler.totals();
            const auto start = std::chrono::steady_clock::now();
            Result<Image> image =
                renderer.render(scenes[scene], scheduler, frames[frame], settings);
            if (!image) {
                return image.error();
            }
            FrameSample sample;
            sample.seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const SchedulerStatistics after = scheduler.totals();
            sample.meshTilesBuilt = renderer.statistics().meshes.tilesBuilt;
            sample.tilesProduced = after.misses - before.misses;
            sample.tilesEvicted = after.evictions - before.evictions;
            samples[scene].push_back(sample);
            // As it happens, so a long run shows where it is.
            std::fprintf(stderr, "objects: timed frame %zu scene %zu: %.0f ms\n", frame, scene,
                         sample.seconds * 1e3);
        }
    }
    return samples;
}

// The viewer's walker in the city (issue 20; core/sources/objects/WalkerCollision): MeshCollision
// over every city tile, each tile's grid built by a first vertical probe through its
// origin (timed per tile), then walker moves — a 1.5 m step (three wall probes, a slide
// when blocked) and the standing height after it — from random points of random tiles,
// standing on whatever is there (ground or roof).
struct WalkerTiming {
    double indexMillisecondsPerTile = 0;
    double stepMilliseconds = 0;
    double blockedFraction = 0;  // moves a wall shortened
};

WalkerTiming timeWalker(const std::vector<std::shared_ptr<const MeshTile>>& tiles,
                        const NoiseSource& terrain) {
    using Clock = std::chrono::steady_clock;
    WalkerTiming timing;
    if (tiles.empty()) {
        return timing;
    }
    MeshCollision collision;
    collision.setTiles(tiles);
    const auto indexStart = Clock::now();
    for (const std::shared_ptr<const MeshTile>& tile : tiles) {
        const glm::dvec3 up = glm::normalize(tile->boundsCenter);
        (void)collision.firstHit(tile->boundsCenter + up * tile->boundsRadius,
                                 tile->boundsCenter - up * tile->boundsRadius);
    }
    timing.indexMillisecondsPerTile =
        std::chrono::duration<double, std::milli>(Clock::now() - indexStart).count() /
        double(tiles.size());
    const WalkerBody body;
    std::mt19937 random(3);
    std::uniform_real_distribution<double> offset(-500.0, 500.0),
        heading(-std::numbers::pi, std::numbers::pi);
    constexpr int kMoves = 4000;
    double seconds = 0;
    int blocked = 0;
    for (int move = 0; move < kMoves; ++move) {
        const MeshTile& tile = *tiles[random() % tiles.size()];
        const Geodetic centre = Ellipsoid::toGeodetic(tile.boundsCenter);
        const glm::dmat3 frame = Ellipsoid::localFrame(centre.latitude, centre.longitude);
        Geodetic at = Ellipsoid::toGeodetic(tile.boundsCenter +
                                            frame * glm::dvec3(offset(random), offset(random), 0));
        // The relief's analytic height (as the flight's), not the drawn levels'.
        const double ground =
            terrain.height(Ellipsoid::surfaceNormal(at.latitude, at.longitude), 1.0);
        at.height = WalkerCollision::standingHeight(collision, at.latitude, at.longitude,
                                                    ground + 300.0, ground - 50.0, body) +
                    body.eyeHeight;
        Camera from;
        from.geodetic = at;
        from.position = Ellipsoid::toEcef(at);
        from.axes = Camera::axesFromAngles(at, heading(random), 0.0, 0.0);
        const Camera to = CameraNavigation::walk(from, 1.5, 0.0);
        const auto start = Clock::now();
        const Camera reached = WalkerCollision::step(collision, from, to, body);
        (void)WalkerCollision::standingHeight(collision, reached.geodetic.latitude,
                                              reached.geodetic.longitude,
                                              at.height - body.eyeHeight, ground - 50.0, body);
        seconds += std::chrono::duration<double>(Clock::now() - start).count();
        blocked += glm::length(reached.position - to.position) > 1e-3 ? 1 : 0;
    }
    timing.stepMilliseconds = seconds * 1e3 / kMoves;
    timing.blockedFraction = double(blocked) / kMoves;
    return timing;
}

}  // namespace

std::string ObjectsBenchmarkResult::json() const {
    return metricsJson("objects", metrics, NumberFormat{NumberFormat::Notation::General, 6});
}

Result<ObjectsBenchmarkResult> runObjectsBenchmark(const ShaderLibrary& library,
                                                   const ObjectsBenchmarkOptions& options) {
    const auto folder = std::filesystem::temp_directory_path() /
                        ("sylva-bench-objects-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    const NoiseSource elevation("dem", relief());
    const NormalMapSource normals("dem.normals", &elevation, 1.0);
    const HypsometricSource colour("dem.colour", &elevation, &normals, HypsometricParameters{});
    SchedulerOptions schedulerOptions;
    schedulerOptions.format = TileFormat{256, 2};
    schedulerOptions.budgetBytes = options.cacheMegabytes << 20;
    Scheduler scheduler(schedulerOptions);

    FeatureSource footprints("city", writeCity(folder, options.buildings), {});
    BuildingsParameters city;
    city.heightAttribute = "h";
    city.roofAttribute = "roof";
    const BuildingsSource buildings("city", &footprints, &elevation, city);
    const auto buildStart = std::chrono::steady_clock::now();
    Result<std::vector<TileKey>> keys = buildings.tileKeys();
    if (!keys) {
        return keys.error();
    }
    double triangles = 0;
    std::vector<std::shared_ptr<const MeshTile>> cityTiles;
    for (const TileKey& key : keys.value()) {
        Result<std::shared_ptr<const MeshTile>> tile = buildings.tile(key, scheduler);
        if (!tile) {
            return tile.error();
        }
        triangles += double(tile.value()->geometry.indices.size() / 3);
        cityTiles.push_back(tile.value());
    }
    const double buildSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - buildStart).count();
    const WalkerTiming walker = timeWalker(cityTiles, elevation);
    std::fprintf(stderr, "objects: walker in %zu city tiles: %.2f%% of moves blocked\n",
                 cityTiles.size(), walker.blockedFraction * 100.0);

    FeatureSource sites("sites", writeTurbineSites(folder, options.turbines), {});
    ObjectsParameters farm;
    farm.model = writeTurbineModel(folder);
    farm.partAttributes = {{"rotor", "angle"}};
    const ObjectsSource turbines("farm", &sites, &elevation, farm);

    Result<std::unique_ptr<SceneRenderer>> renderer = SceneRenderer::create(library, {});
    if (!renderer) {
        return renderer.error();
    }
    RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.ocean = false;
    settings.sunDirection = Ellipsoid::surfaceNormal(5 * kDegree, -40 * kDegree);
    settings.exposure = 0.45;
    const std::vector<Camera> frames = flight(elevation, options.framesPerSegment);
    const std::vector<TerrainLayers> scenes = {
        {&elevation, &colour, &normals, {}, {}},
        {&elevation, &colour, &normals, {}, {&buildings}},
        {&elevation, &colour, &normals, {}, {&turbines}},
    };
    Result<std::vector<std::vector<FrameSample>>> flown =
        fly(*renderer.value(), scenes, scheduler, frames, settings);
    if (!flown) {
        return flown.error();
    }
    const std::vector<std::vector<FrameSample>>& samples = flown.value();
    static constexpr const char* kScenes[] = {"terrain", "city", "farm"};
    for (std::size_t frame = 0; frame < frames.size(); ++frame) {
        // The frames behind the medians, for reading a surprising ratio: per scene its
        // time, mesh tiles built, tiles produced and evicted by the Scheduler.
        std::string line = "objects: frame " + std::to_string(frame) + ":";
        for (std::size_t scene = 0; scene < samples.size(); ++scene) {
            const FrameSample& s = samples[scene][frame];
            char text[160];
            std::snprintf(text, sizeof text, "%s %s %.0f ms (meshes %zu, tiles +%zu -%zu)",
                          scene == 0 ? "" : ",", kScenes[scene], s.seconds * 1e3, s.meshTilesBuilt,
                          s.tilesProduced, s.tilesEvicted);
            line += text;
        }
        std::fprintf(stderr, "%s\n", line.c_str());
    }
    const SchedulerStatistics totals = scheduler.totals();
    std::fprintf(stderr,
                 "objects: cache budget %zu MiB, peak %.0f MiB, now %.0f MiB in %zu tiles; "
                 "%zu produced, %zu evicted\n",
                 options.cacheMegabytes, double(scheduler.peakCachedBytes()) / (1 << 20),
                 double(totals.bytes) / (1 << 20), totals.tiles, totals.misses, totals.evictions);
    std::vector<double> medians;
    for (const std::vector<FrameSample>& scene : samples) {
        std::vector<double> seconds;
        for (const FrameSample& sample : scene) {
            seconds.push_back(sample.seconds);
        }
        medians.push_back(median(seconds));
    }
    std::filesystem::remove_all(folder);
    ObjectsBenchmarkResult result;
    result.metrics = {
        {"buildings_frame_ratio", medians[1] / medians[0]},
        {"turbines_frame_ratio", medians[2] / medians[0]},
        {"buildings_build_s_100k", buildSeconds * 100000.0 / std::max(options.buildings, 1)},
        {"buildings", double(options.buildings)},
        {"buildings_triangles", triangles},
        {"turbines", double(options.turbines)},
        {"terrain_frame_ms", medians[0] * 1e3},
        {"buildings_frame_ms", medians[1] * 1e3},
        {"turbines_frame_ms", medians[2] * 1e3},
        {"walker_index_ms_per_tile", walker.indexMillisecondsPerTile},
        {"walker_move_ms", walker.stepMilliseconds},
    };
    return result;
}

}  // namespace sylva::bench
