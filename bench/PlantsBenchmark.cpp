#include "sylva/bench/PlantsBenchmark.h"
#include "sylva/bench/BenchmarkMetrics.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <vector>

#include "sylva/core/plantlod/BillboardCloudBuilder.h"
#include "sylva/core/plantlod/PlantGenerator.h"
#include "sylva/core/plantlod/PlantGltfWriter.h"
#include "sylva/core/plantlod/PlantImporter.h"

namespace sylva::bench {

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The times of one run, milliseconds.
struct PlantsRun {
    double generate = 0, write = 0, import = 0, reconstruct = 0, billboards = 0;
    std::size_t triangles = 0;
};

Result<PlantsRun> runOnce(const std::filesystem::path& path) {
    PlantsRun run;
    PlantGeneratorOptions options;
    options.seed = 1;
    options.leafCount = 27000;
    auto start = Clock::now();
    Result<PlantModel> model =
        PlantGenerator::generate(PlantGenerator::preset("oak").value(), options);
    run.generate = millisecondsSince(start);
    if (!model) {
        return model.error();
    }
    run.triangles = model->triangleCount(PlantPart::Leaf) + model->triangleCount(PlantPart::Branch);
    start = Clock::now();
    if (Status written = PlantGltfWriter::write(*model, path); !written) {
        return written.error();
    }
    run.write = millisecondsSince(start);
    start = Clock::now();
    Result<PlantModel> imported = PlantImporter::import(path);
    run.import = millisecondsSince(start);
    PlantImportOptions noSkeleton;
    noSkeleton.useFileSkeleton = false;
    start = Clock::now();
    Result<PlantModel> rebuilt = PlantImporter::import(path, noSkeleton);
    run.reconstruct = millisecondsSince(start);
    if (!imported || !rebuilt) {
        return !imported ? imported.error() : rebuilt.error();
    }
    options.leafCount = 5000;
    Result<PlantModel> small =
        PlantGenerator::generate(PlantGenerator::preset("oak").value(), options);
    if (!small) {
        return small.error();
    }
    start = Clock::now();
    Result<BillboardCloud> cloud = BillboardCloudBuilder::build(*small);
    run.billboards = millisecondsSince(start);
    if (!cloud) {
        return cloud.error();
    }
    return run;
}

}  // namespace

std::string PlantsBenchmarkResult::json() const {
    return metricsJson("plants", metrics, {NumberFormat::Notation::Fixed, 3});
}

Result<PlantsBenchmarkResult> runPlantsBenchmark(const PlantsBenchmarkOptions& options) {
    const std::filesystem::path folder = std::filesystem::temp_directory_path() /
                                         ("sylva-bench-plants-" + std::to_string(::getpid()));
    std::vector<PlantsRun> runs;
    for (int run = 0; run < std::max(1, options.runs); ++run) {
        Result<PlantsRun> measured = runOnce(folder / "oak.glb");
        if (!measured) {
            std::error_code ignored;
            std::filesystem::remove_all(folder, ignored);
            return measured.error();
        }
        runs.push_back(measured.value());
    }
    std::error_code ignored;
    std::filesystem::remove_all(folder, ignored);
    const auto medianOf = [&](double PlantsRun::*field) {
        std::vector<double> times;
        for (const PlantsRun& run : runs) {
            times.push_back(run.*field);
        }
        return median(times);
    };
    PlantsBenchmarkResult result;
    result.metrics = {{"generate_oak_27k_ms", medianOf(&PlantsRun::generate)},
                      {"write_glb_ms", medianOf(&PlantsRun::write)},
                      {"import_glb_ms", medianOf(&PlantsRun::import)},
                      {"import_reconstruct_skeleton_ms", medianOf(&PlantsRun::reconstruct)},
                      {"billboard_cloud_oak_5k_ms", medianOf(&PlantsRun::billboards)},
                      {"triangles", double(runs.back().triangles)}};
    return result;
}

}  // namespace sylva::bench
