// plant_model sources: parameters and errors, the asset built once and cached on disk
// (a corrupt cache is rebuilt with a warning), .plod-only models, and the plants
// source's `models` through SourceGraph.
#include "sylva/core/sources/plants/PlantModelSource.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "sylva/core/plantlod/PlodFile.h"
#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/core/sources/plants/PlantsSource.h"

namespace sylva {
namespace {

namespace fs = std::filesystem;

// A private cache folder per test, set through SYLVA_CACHE_DIR.
class PlantModelSourceTest : public ::testing::Test {
protected:
    void SetUp() override {
        folder_ = fs::temp_directory_path() /
                  ("sylva_plant_model_test_" + std::to_string(::getpid()) + "_" +
                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(folder_);
        fs::create_directories(folder_);
        ::setenv("SYLVA_CACHE_DIR", (folder_ / "cache").c_str(), 1);
    }
    void TearDown() override {
        ::unsetenv("SYLVA_CACHE_DIR");
        fs::remove_all(folder_);
    }
    static PlantModelParameters smallBush() {
        PlantModelParameters p;
        p.preset = "bush";
        p.leaves = 40;
        p.seed = 3;
        return p;
    }
    fs::path folder_;
};

TEST_F(PlantModelSourceTest, BuildsOnceAndCachesOnDisk) {
    auto source = PlantModelSource::make("shrub", smallBush());
    ASSERT_TRUE(source) << source.error().message;
    EXPECT_EQ((*source)->output(), PortType::PlantModel);
    EXPECT_EQ(PlantModelSource::from(source->get()), source->get());
    const fs::path cache = (*source)->cacheFile();
    EXPECT_EQ(cache.parent_path(), folder_ / "cache" / "plants");
    EXPECT_FALSE(fs::exists(cache));

    // Concurrent first calls build once and share the result.
    std::vector<std::shared_ptr<const PlantAsset>> seen(4);
    std::vector<std::thread> threads;
    for (int i = 0; i < 4; ++i) {
        threads.emplace_back([&, i] {
            auto asset = (*source)->asset();
            ASSERT_TRUE(asset) << asset.error().message;
            seen[i] = asset.value();
        });
    }
    for (std::thread& t : threads) {
        t.join();
    }
    for (const auto& asset : seen) {
        EXPECT_EQ(asset, seen[0]);
    }
    const PlantAsset& built = *seen[0];
    EXPECT_EQ(built.name, "shrub");
    EXPECT_EQ(built.model.triangleCount(PlantPart::Leaf), 80u);  // 40 quads
    ASSERT_FALSE(built.lod.levels.empty());
    EXPECT_EQ(built.lod.levels[0].ellipsoidCount, 40u);
    ASSERT_TRUE(fs::exists(cache));
    const auto written = fs::last_write_time(cache);

    // A second source with the same parameters (the next process) reads the cache.
    auto again = PlantModelSource::make("shrub", smallBush());
    ASSERT_TRUE(again);
    EXPECT_EQ((*again)->contentHash(), (*source)->contentHash());
    auto reread = (*again)->asset();
    ASSERT_TRUE(reread) << reread.error().message;
    EXPECT_EQ(fs::last_write_time(cache), written);
    EXPECT_EQ(encodePlod(reread.value()->lod), encodePlod(built.lod));

    // Other parameters, other hash.
    PlantModelParameters other = smallBush();
    other.seed = 4;
    EXPECT_NE(PlantModelSource::make("shrub", other).value()->contentHash(),
              (*source)->contentHash());
}

TEST_F(PlantModelSourceTest, CorruptCacheIsRebuiltWithAWarning) {
    auto source = PlantModelSource::make("shrub", smallBush());
    ASSERT_TRUE(source);
    const fs::path cache = (*source)->cacheFile();
    fs::create_directories(cache.parent_path());
    std::ofstream(cache, std::ios::binary) << "SYLVPLOD but not really";
    ::testing::internal::CaptureStderr();
    auto asset = (*source)->asset();
    const std::string warning = ::testing::internal::GetCapturedStderr();
    ASSERT_TRUE(asset) << asset.error().message;
    EXPECT_NE(warning.find("warning: plant_model 'shrub': ignoring the cached LoD (" +
                           cache.string() + ": "),
              std::string::npos)
        << warning;
    EXPECT_NE(warning.find("rebuilding"), std::string::npos);
    Result<PlantLod> fixed = readPlodFile(cache.string());
    ASSERT_TRUE(fixed) << fixed.error().message;
    EXPECT_EQ(encodePlod(fixed.value()), encodePlod(asset.value()->lod));
}

TEST_F(PlantModelSourceTest, PlodOnlyModelHasNoMesh) {
    auto built = PlantModelSource::make("shrub", smallBush());
    ASSERT_TRUE(built);
    auto asset = (*built)->asset();
    ASSERT_TRUE(asset);
    const fs::path plod = folder_ / "shrub.plod";
    ASSERT_TRUE(writePlodFile(asset.value()->lod, plod.string()));

    PlantModelParameters p;
    p.file = plod;
    auto lodOnly = PlantModelSource::make("shrub2", p);
    ASSERT_TRUE(lodOnly) << lodOnly.error().message;
    EXPECT_EQ((*lodOnly)->files(), std::vector<fs::path>{plod});
    auto read = (*lodOnly)->asset();
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_TRUE(read.value()->model.meshes.empty());
    EXPECT_EQ(read.value()->lod.ellipsoids.size(), asset.value()->lod.ellipsoids.size());
    EXPECT_EQ(read.value()->name, "shrub2");
}

TEST_F(PlantModelSourceTest, BadParametersAndFilesGiveClearErrors) {
    const auto error = [](PlantModelParameters p) {
        auto made = PlantModelSource::make("tree", std::move(p), "here.sylva:3:5: ");
        return made ? std::string("(no error)") : made.error().message;
    };
    EXPECT_EQ(
        error({}),
        "here.sylva:3:5: give either `preset` (a generated tree) or `file` (a model or .plod), "
        "not neither");
    PlantModelParameters p;
    p.preset = "baobab";
    EXPECT_NE(error(p).find("here.sylva:3:5: "), std::string::npos);
    EXPECT_NE(error(p).find("baobab"), std::string::npos);
    p.preset = "oak";
    p.file = folder_ / "oak.glb";
    EXPECT_EQ(error(p),
              "here.sylva:3:5: give either `preset` (a generated tree) or `file` (a "
              "model or .plod), not both");
    p.preset.clear();
    EXPECT_EQ(error(p), "here.sylva:3:5: " + (folder_ / "oak.glb").string() + ": file not found");
    p.file = folder_ / "oak.fbx";
    EXPECT_EQ(error(p), "here.sylva:3:5: " + (folder_ / "oak.fbx").string() +
                            ": unsupported plant model type '.fbx' (.gltf, .glb, .obj or .plod)");
    p.file = folder_ / "oak.glb";
    std::ofstream(p.file, std::ios::binary) << "not a glb";
    p.leaves = 100;
    EXPECT_EQ(error(p), "here.sylva:3:5: `leaves` applies to generated trees (`preset`) only");
    p.leaves.reset();

    // A corrupt model file is found when the asset is built: the error names the file.
    auto corrupt = PlantModelSource::make("tree", p, "here.sylva:3:5: ");
    ASSERT_TRUE(corrupt) << corrupt.error().message;
    auto asset = (*corrupt)->asset();
    ASSERT_FALSE(asset);
    EXPECT_EQ(asset.error().message.rfind("here.sylva:3:5: " + p.file.string() + ": ", 0), 0u)
        << asset.error().message;
    EXPECT_EQ((*corrupt)->asset().error().message, asset.error().message);  // remembered
}

// --- the plants source's `models`, through SourceGraph ---------------------------------

const auto kFile = std::make_shared<const std::string>("forest.sylva");

Block sourceBlock(std::string name, std::string kind, std::uint32_t line) {
    Block block;
    block.keyword = "source";
    block.name = std::move(name);
    block.kind = std::move(kind);
    block.location = {kFile, line, 8, 1};
    return block;
}

void set(Block& block, std::string attribute, Value value, std::uint32_t line) {
    value.location = {kFile, line, 5, 1};
    block.attributes.push_back({std::move(attribute), value, value.location});
}

Value referenceTo(std::string name) {
    Value v;
    v.data = Reference{"source", std::move(name)};
    return v;
}

ProjectModel forest(std::vector<std::string> models) {
    ProjectModel m;
    m.file = "forest.sylva";
    m.sources.push_back(sourceBlock("hills", "noise", 1));
    for (const char* species : {"oak", "birch"}) {
        Block model = sourceBlock(species, "plant_model", 2);
        Value preset;
        preset.data = Word{species};
        set(model, "preset", preset, 2);
        m.sources.push_back(model);
    }
    Block trees = sourceBlock("trees", "plants", 3);
    set(trees, "elevation", referenceTo("hills"), 4);
    Value species;
    species.data = ValueObject{{"oak", Value{Quantity{0.6, Dimension::Ratio}, {}}},
                               {"birch", Value{Quantity{0.4, Dimension::Ratio}, {}}}};
    set(trees, "species", species, 6);
    if (!models.empty()) {
        ValueList list;
        for (const std::string& name : models) {
            list.push_back(referenceTo(name));
        }
        Value value;
        value.data = list;
        set(trees, "models", value, 7);
    }
    m.sources.push_back(trees);
    return m;
}

TEST(PlantsModels, SpeciesGetTheirModelsByName) {
    Result<SourceGraph> graph = SourceGraph::build(forest({"birch", "oak"}));
    ASSERT_TRUE(graph) << graph.error().message;
    const PlantsSource* trees = PlantsSource::from(graph->find("trees"));
    ASSERT_NE(trees, nullptr);
    ASSERT_EQ(trees->speciesNames(), (std::vector<std::string>{"oak", "birch"}));
    ASSERT_EQ(trees->models().size(), 2u);
    EXPECT_EQ(trees->models()[0], PlantModelSource::from(graph->find("oak")));
    EXPECT_EQ(trees->models()[1], PlantModelSource::from(graph->find("birch")));
    EXPECT_NE(trees->models()[0], nullptr);

    // Without `models`: markers only, no model per species.
    Result<SourceGraph> markers = SourceGraph::build(forest({}));
    ASSERT_TRUE(markers) << markers.error().message;
    EXPECT_EQ(PlantsSource::from(markers->find("trees"))->models(),
              (std::vector<const PlantModelSource*>{nullptr, nullptr}));
}

TEST(PlantsModels, SpeciesWithoutModelIsALocatedError) {
    Result<SourceGraph> graph = SourceGraph::build(forest({"oak"}));
    ASSERT_FALSE(graph);
    EXPECT_EQ(graph.error().message,
              "forest.sylva:7:5: source 'trees': species 'birch' has no plant model: `models` "
              "lists oak (a plant_model source named like the species draws it)");

    Result<SourceGraph> wrongKind = SourceGraph::build(forest({"oak", "birch", "hills"}));
    ASSERT_FALSE(wrongKind);
    EXPECT_EQ(wrongKind.error().message,
              "forest.sylva:7:5: source 'trees': 'models' expects plant_model, but source 'hills' "
              "gives elevation");
}

}  // namespace
}  // namespace sylva
