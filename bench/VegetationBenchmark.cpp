#include "sylva/bench/VegetationBenchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "BenchForest.h"
#include "FarFieldBenchmark.h"
#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/plantlod/BillboardCloudBuilder.h"
#include "sylva/core/plantlod/ImageErrorMetric.h"
#include "sylva/core/plantlod/PlantGenerator.h"
#include "sylva/core/plantlod/PlantLodBuilder.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::bench {

using namespace sylva::render;
// The rendered frame, not sylva::Image<Channel> (which the directive above would make
// ambiguous).
using render::Image;

namespace {

constexpr double kDegree = std::numbers::pi / 180;
double srgbToLinear(std::uint8_t value) {
    const double c = value / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// Linear luminance of an RGBA8 sRGB image, box-filtered by `scale` in each direction.
std::vector<float> luminance(const Image& image, int scale) {
    const int width = image.width / scale, height = image.height / scale;
    std::vector<float> out(std::size_t(width) * height, 0.0f);
    std::vector<double> table(256);
    for (int i = 0; i < 256; ++i) {
        table[i] = srgbToLinear(std::uint8_t(i));
    }
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            double sum = 0.0;
            for (int dy = 0; dy < scale; ++dy) {
                const std::uint8_t* row =
                    image.pixels.data() +
                    (std::size_t(y * scale + dy) * image.width + x * scale) * 4;
                for (int dx = 0; dx < scale; ++dx) {
                    const std::uint8_t* p = row + dx * 4;
                    sum += 0.2126 * table[p[0]] + 0.7152 * table[p[1]] + 0.0722 * table[p[2]];
                }
            }
            out[std::size_t(y) * width + x] = float(sum / (scale * scale));
        }
    }
    return out;
}

// The multi-scale RMSE of seed 001 §3.5 over a whole frame: the metric needs square
// power-of-two images, so the frame is covered by 256² blocks (the last row and column
// of blocks overlap their neighbours) and the block values are averaged.
double frameError(const std::vector<float>& a, const std::vector<float>& b, int width, int height) {
    constexpr int kBlock = 256;
    std::vector<int> xs, ys;
    for (int x = 0; x + kBlock <= width; x += kBlock) {
        xs.push_back(x);
    }
    if (width % kBlock != 0 && width > kBlock) {
        xs.push_back(width - kBlock);
    }
    for (int y = 0; y + kBlock <= height; y += kBlock) {
        ys.push_back(y);
    }
    if (height % kBlock != 0 && height > kBlock) {
        ys.push_back(height - kBlock);
    }
    if (xs.empty() || ys.empty()) {
        return 0.0;
    }
    std::vector<float> blockA(kBlock * kBlock), blockB(kBlock * kBlock);
    double sum = 0.0;
    for (int y0 : ys) {
        for (int x0 : xs) {
            for (int y = 0; y < kBlock; ++y) {
                std::copy_n(a.begin() + std::ptrdiff_t(y0 + y) * width + x0, kBlock,
                            blockA.begin() + y * kBlock);
                std::copy_n(b.begin() + std::ptrdiff_t(y0 + y) * width + x0, kBlock,
                            blockB.begin() + y * kBlock);
            }
            sum += multiScaleRmse(multiScaleSquaredErrors(blockA, blockB, kBlock));
        }
    }
    return sum / double(xs.size() * ys.size());
}

// One key of the path: offsets north/east of the forest centre (metres), height above
// the ground, heading and pitch (radians).
const char* methodName(VegetationMethod method) {
    switch (method) {
        case VegetationMethod::Lod:
            return "lod";
        case VegetationMethod::Billboard:
            return "bbc";
        case VegetationMethod::Mesh:
            return "mesh";
        case VegetationMethod::Points:
            return "points";
        case VegetationMethod::DisplacedBillboard:
            return "dmbbc";
        case VegetationMethod::Impostors:
            return "impostors";
    }
    return "?";
}

void logProgress(const char* text) {
    std::fprintf(stderr, "bench vegetation: %s\n", text);
}

constexpr double kSegmentSeconds = 5.0;  // path time per segment, for the 1/25 s step
constexpr double kNextFrame = 1.0 / (25.0 * kSegmentSeconds);

constexpr VegetationMethod kMethods[] = {
    VegetationMethod::Lod,    VegetationMethod::Billboard,          VegetationMethod::Mesh,
    VegetationMethod::Points, VegetationMethod::DisplacedBillboard, VegetationMethod::Impostors};

// The flat meadow, the renderer with the oak as its one species, and timed frames.
class ForestScene {
public:
    static Result<std::unique_ptr<ForestScene>> create(const ShaderLibrary& library,
                                                       std::shared_ptr<PlantAsset> asset,
                                                       const VegetationBenchmarkOptions& options) {
        auto scene = std::unique_ptr<ForestScene>(new ForestScene(options));
        Result<std::unique_ptr<SceneRenderer>> created =
            SceneRenderer::create(library, TerrainSettings{});
        if (!created) {
            return created.error();
        }
        scene->renderer_ = std::move(created.value());
        Result<std::uint32_t> species = scene->renderer_->vegetation().addSpecies(std::move(asset));
        if (!species) {
            return species.error();
        }
        scene->species_ = species.value();
        return scene;
    }

    SceneRenderer& renderer() { return *renderer_; }
    void setOcclusion(bool occlusion) { occlusion_ = occlusion; }
    std::uint32_t species() const { return species_; }
    const std::vector<SpeciesLod>& lods() { return renderer_->vegetation().speciesLods(); }

    // Renders `batches` with `method` at `scale` times the frame size; the wall seconds
    // of the render in `seconds`.
    Result<Image> render(const Camera& c, const std::vector<const InstanceBatch*>& batches,
                         VegetationMethod method, double& seconds, int scale = 1) {
        settings_.width = options_.width * scale;
        settings_.height = options_.height * scale;
        settings_.instanceBatches = batches;
        settings_.vegetation = VegetationSettings{};
        settings_.vegetation.method = method;
        // The methods are compared as themselves: no mesh handover for the LoD.
        settings_.vegetation.closeUpMesh = false;
        settings_.vegetation.occlusionCulling = occlusion_;
        const auto start = std::chrono::steady_clock::now();
        Result<Image> image = renderer_->render(layers_, evaluator_, c, settings_);
        seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return image;
    }

    // A warm-up frame without plants (fills the tile cache), then the seconds of the
    // same frame without plants.
    Result<double> bareSeconds(const Camera& c) {
        double seconds = 0.0;
        if (Result<Image> warm = render(c, {}, VegetationMethod::Lod, seconds); !warm) {
            return warm.error();
        }
        double bare = 0.0;
        if (Result<Image> empty = render(c, {}, VegetationMethod::Lod, bare); !empty) {
            return empty.error();
        }
        return bare;
    }

private:
    explicit ForestScene(const VegetationBenchmarkOptions& options)
        : options_(options),
          elevation_("flat", kForestGround),
          color_("meadow", glm::vec4(0.10f, 0.14f, 0.05f, 1.0f)),
          normals_("flat.normals", &elevation_, 1.0),
          layers_{&elevation_, &color_, &normals_, {}, {}},
          evaluator_(TileFormat{256, 2}),
          occlusion_(options.occlusion) {
        settings_.sunDirection =
            glm::normalize(Ellipsoid::surfaceNormal(kForestLatitude - 0.5, kForestLongitude - 0.6));
        settings_.atmosphere = true;
        settings_.ocean = false;
    }

    const VegetationBenchmarkOptions& options_;
    const ConstantSource elevation_;
    const ConstantSource color_;
    const NormalMapSource normals_;
    const TerrainLayers layers_;
    TileEvaluator evaluator_;
    RenderSettings settings_;
    std::unique_ptr<SceneRenderer> renderer_;
    std::uint32_t species_ = 0;
    bool occlusion_ = true;
};

// Per method: the plants' milliseconds per frame, the error against the reference and
// the temporal error on the sampled frames.
struct MethodSamples {
    std::map<VegetationMethod, std::vector<double>> plantMilliseconds;
    std::map<VegetationMethod, std::vector<double>> referenceError, temporalError;
};

bool methodRuns(VegetationMethod method, const VegetationBenchmarkOptions& options,
                bool haveBillboards) {
    switch (method) {
        case VegetationMethod::Lod:
            return options.lod;
        case VegetationMethod::Billboard:
            return haveBillboards && options.billboards;
        case VegetationMethod::Mesh:
            return options.mesh;
        case VegetationMethod::Points:
            return options.points;
        case VegetationMethod::DisplacedBillboard:
            return haveBillboards && options.dmbbc;
        case VegetationMethod::Impostors:
            return options.impostors;
    }
    return false;
}

void logMethodFrame(const VegetationStatistics& drawn, VegetationMethod method,
                    double plantMilliseconds, double bare) {
    char detail[256];
    std::snprintf(detail, sizeof detail,
                  "  %s: %.0f ms (frame without plants %.0f ms); %zu instances, %zu "
                  "ellipsoids, %zu lines, "
                  "%zu meshes, %zu billboard clouds, %zu points, select %.1f ms, %zu quad passes, "
                  "%zu occluded (%.1f ms)",
                  methodName(method), plantMilliseconds, bare * 1000.0, drawn.drawnInstances,
                  drawn.ellipsoids, drawn.lines, drawn.meshInstances, drawn.billboardInstances,
                  drawn.points, drawn.selectSeconds * 1000.0, drawn.quadPassRuns,
                  drawn.occludedInstances, drawn.occlusionSeconds * 1000.0);
    logProgress(detail);
}

void logImpostorFrame(const ImpostorStatistics& drawn) {
    char detail[256];
    std::snprintf(detail, sizeof detail,
                  "  impostors: %zu single, %zu groups of %zu instances, %zu group renders (%zu "
                  "for resolution), validity tests %zu: %zu in GVV, %zu valid by metric, %zu "
                  "regenerated",
                  drawn.impostorInstances, drawn.groups, drawn.groupInstances, drawn.groupsRendered,
                  drawn.resolutionRenders, drawn.validity.tests,
                  drawn.validity.insideGuaranteedVolume, drawn.validity.validByMetric,
                  drawn.validity.regenerated);
    logProgress(detail);
}

// Frame `frame` (path time `t`) with `method`: timed against `bare`, written to the
// frames folder, and on sampled frames (non-empty `reference`) compared with the
// reference and with the frame 1/25 s later.
Status measureMethod(ForestScene& scene, const std::vector<const InstanceBatch*>& forest,
                     VegetationMethod method, int frame, double t, double bare,
                     const std::vector<float>& reference, const VegetationBenchmarkOptions& options,
                     MethodSamples& samples) {
    double seconds = 0.0;
    Result<Image> image = scene.render(forestCamera(kForestPath, t), forest, method, seconds);
    if (!image) {
        return image.error();
    }
    samples.plantMilliseconds[method].push_back(std::max(0.0, seconds - bare) * 1000.0);
    logMethodFrame(scene.renderer().vegetation().statistics(), method,
                   samples.plantMilliseconds[method].back(), bare);
    if (method == VegetationMethod::Impostors) {
        logImpostorFrame(scene.renderer().vegetation().impostorStatistics());
    }
    if (!options.framesFolder.empty()) {
        char name[64];
        std::snprintf(name, sizeof name, "/frame%02d_%s.png", frame, methodName(method));
        (void)ImageWriter::writeRgba8(options.framesFolder + name, image.value().width,
                                      image.value().height, image.value().pixels);
    }
    if (reference.empty()) {
        return {};
    }
    const std::vector<float> current = luminance(image.value(), 1);
    samples.referenceError[method].push_back(
        frameError(current, reference, options.width, options.height));
    Result<Image> next =
        scene.render(forestCamera(kForestPath, t + kNextFrame), forest, method, seconds);
    if (!next) {
        return next.error();
    }
    samples.temporalError[method].push_back(
        frameError(current, luminance(next.value(), 1), options.width, options.height));
    return {};
}

// Every frame of the path with every method that runs.
Status measurePath(ForestScene& scene, const std::vector<InstanceBatch>& forest, int frames,
                   const VegetationBenchmarkOptions& options, MethodSamples& samples) {
    const bool haveBillboards = !scene.lods()[scene.species()].billboardError.empty();
    if (!options.framesFolder.empty()) {
        std::filesystem::create_directories(options.framesFolder);
    }
    for (int frame = 0; frame < frames; ++frame) {
        const double t = double(frame) / options.framesPerSegment;
        const Camera c = forestCamera(kForestPath, t);
        char line[96];
        std::snprintf(line, sizeof line, "frame %d/%d", frame + 1, frames);
        logProgress(line);
        Result<double> bare = scene.bareSeconds(c);
        if (!bare) {
            return bare.error();
        }
        // Every method's segment ends (but the start) are compared with the mesh
        // rendered at referenceScale times the resolution, box-filtered down.
        const bool sampled = frame % options.framesPerSegment == 0 && frame > 0 && options.mesh;
        std::vector<float> reference;
        if (sampled) {
            double seconds = 0.0;
            Result<Image> image = scene.render(c, pointers(forest), VegetationMethod::Mesh, seconds,
                                               options.referenceScale);
            if (!image) {
                return image.error();
            }
            reference = luminance(image.value(), options.referenceScale);
        }
        for (VegetationMethod method : kMethods) {
            if (!methodRuns(method, options, haveBillboards)) {
                continue;
            }
            if (Status measured = measureMethod(scene, pointers(forest), method, frame, t,
                                                bare.value(), reference, options, samples);
                !measured) {
                return measured;
            }
        }
    }
    return {};
}

// Metrics of the methods that ran (all of them unless the options leave some out).
void addMethodMetrics(MethodSamples& samples, std::map<std::string, double>& metrics) {
    const auto mean = [](const std::vector<double>& v) {
        double s = 0.0;
        for (double x : v) {
            s += x;
        }
        return v.empty() ? 0.0 : s / double(v.size());
    };
    const auto ran = [&](VegetationMethod method) {
        return !samples.plantMilliseconds[method].empty();
    };
    for (VegetationMethod method : kMethods) {
        if (!ran(method)) {
            continue;
        }
        const std::string name = methodName(method);
        metrics[name + "_ms_median"] = median(samples.plantMilliseconds[method]);
        if (!samples.referenceError[method].empty()) {
            metrics["rmse_ref_" + name] = mean(samples.referenceError[method]);
            metrics["temporal_" + name] = mean(samples.temporalError[method]);
        }
    }
    const auto ratio = [&](const char* key, VegetationMethod slower) {
        if (ran(VegetationMethod::Lod) && ran(slower)) {
            metrics[key] = metrics[std::string(methodName(slower)) + "_ms_median"] /
                           std::max(metrics["lod_ms_median"], 1e-6);
        }
    };
    ratio("lod_vs_mesh", VegetationMethod::Mesh);
    ratio("lod_vs_bbc", VegetationMethod::Billboard);
}

// The selection alone (CPU) of `batches`, from every segment's midpoint, three times:
// its median milliseconds and the visible instances of the last selection.
std::pair<double, double> selectionMilliseconds(const std::vector<InstanceBatch>& batches,
                                                const std::vector<SpeciesLod>& lods,
                                                const VegetationBenchmarkOptions& options) {
    const int segments = int(kForestPath.size()) - 1;
    LodSelectionSettings selection;
    selection.pixelAngle = 2.0 * std::tan(25.0 * kDegree) / options.height;
    LodSelector::setFrustum(selection, 50.0 * kDegree, double(options.width) / options.height);
    LodSelector selector;
    LodSelection out;
    std::vector<double> selectMilliseconds;
    for (int run = 0; run < 3; ++run) {
        for (int segment = 1; segment <= segments; ++segment) {
            const Camera c = forestCamera(kForestPath, double(segment) - 0.5);
            const auto start = std::chrono::steady_clock::now();
            selector.select(pointers(batches), lods, c, selection, out);
            selectMilliseconds.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count());
        }
    }
    return {median(selectMilliseconds), double(out.visibleInstances)};
}

// The LoD method with 100,000 and 1,000,000 instances, from every segment's midpoint,
// and the selection alone of the million.
Status measureScaling(ForestScene& scene, const VegetationBenchmarkOptions& options,
                      std::map<std::string, double>& metrics) {
    const int segments = int(kForestPath.size()) - 1;
    for (const int count : {100000, 1000000}) {
        char line[96];
        std::snprintf(line, sizeof line, "scaling: %d instances", count);
        logProgress(line);
        const std::vector<InstanceBatch> many =
            makeForest(count, scene.species(), scene.lods(), 11);
        std::vector<double> milliseconds;
        for (int segment = 1; segment <= segments; ++segment) {
            const Camera c = forestCamera(kForestPath, double(segment) - 0.5);
            double bare = 0.0, seconds = 0.0;
            (void)scene.render(c, {}, VegetationMethod::Lod, seconds);
            (void)scene.render(c, {}, VegetationMethod::Lod, bare);
            Result<Image> image = scene.render(c, pointers(many), VegetationMethod::Lod, seconds);
            if (!image) {
                return image.error();
            }
            milliseconds.push_back(std::max(0.0, seconds - bare) * 1000.0);
        }
        metrics[count == 100000 ? "lod_ms_100k" : "lod_ms_1m"] = median(milliseconds);
        if (count == 1000000) {
            const auto [select, visible] = selectionMilliseconds(many, scene.lods(), options);
            metrics["select_ms_1m"] = select;
            metrics["select_visible_1m"] = visible;
        }
    }
    return {};
}

// The fraction of the instances that pass the frustum, size and distance tests that
// occlusion culling drops, for the camera inside the forest (the path's fourth key) with
// the LoD method.
Result<double> culledFractionInsideForest(ForestScene& scene,
                                          const std::vector<InstanceBatch>& forest) {
    scene.setOcclusion(true);
    double seconds = 0.0;
    Result<Image> image = scene.render(forestCamera(kForestPath, 3.0), pointers(forest),
                                       VegetationMethod::Lod, seconds);
    if (!image) {
        return image.error();
    }
    const VegetationStatistics& drawn = scene.renderer().vegetation().statistics();
    const double candidates = double(drawn.visibleInstances + drawn.occludedInstances);
    return candidates > 0.0 ? double(drawn.occludedInstances) / candidates : 0.0;
}

}  // namespace

std::string VegetationBenchmarkResult::json() const {
    return metricsJson("vegetation", metrics, {NumberFormat::Notation::General, 6});
}

Result<VegetationBenchmarkResult> runVegetationBenchmark(
    const ShaderLibrary& library, const VegetationBenchmarkOptions& options) {
    VegetationBenchmarkResult farField;
    if (options.farField) {
        logProgress("far-field canopy (demo relief, ground camera, five headings)");
        Result<std::map<std::string, double>> metrics =
            runFarFieldBenchmark(library, options.width, options.height);
        if (!metrics) {
            return metrics.error();
        }
        farField.metrics = metrics.value();
    }
    if (!options.lod && !options.billboards && !options.mesh) {
        return farField;  // --methods farfield: nothing else asked for
    }
    // The plant: a generated oak, its LoD and billboard clouds (not timed).
    logProgress("building the plant (generator, LoD, billboard clouds)");
    Result<std::shared_ptr<PlantAsset>> asset = buildOak(options.leaves);
    if (!asset) {
        return asset.error();
    }
    Result<std::unique_ptr<ForestScene>> scene =
        ForestScene::create(library, asset.value(), options);
    if (!scene) {
        return scene.error();
    }
    const int frames = (int(kForestPath.size()) - 1) * options.framesPerSegment + 1;
    const std::vector<InstanceBatch> forest =
        makeForest(options.trees, scene.value()->species(), scene.value()->lods(), 7);
    MethodSamples samples;
    if (Status measured = measurePath(*scene.value(), forest, frames, options, samples);
        !measured) {
        return measured.error();
    }
    VegetationBenchmarkResult result;
    addMethodMetrics(samples, result.metrics);
    if (options.lod) {
        Result<double> culled = culledFractionInsideForest(*scene.value(), forest);
        if (!culled) {
            return culled.error();
        }
        result.metrics["culled_fraction_inside_forest"] = culled.value();
        scene.value()->setOcclusion(options.occlusion);
    }
    result.metrics["trees"] = options.trees;
    result.metrics["frames"] = frames;
    result.metrics["lod_ellipsoids"] = double(asset.value()->lod.ellipsoids.size());
    result.metrics["lod_lines"] = double(asset.value()->lod.lines.size());
    if (options.scaling && options.lod) {
        if (Status measured = measureScaling(*scene.value(), options, result.metrics); !measured) {
            return measured.error();
        }
    }
    result.metrics.insert(farField.metrics.begin(), farField.metrics.end());
    return result;
}

}  // namespace sylva::bench
