// The language beyond the golden corpus: resource limits, per-scenario models and their
// content hashes, and the replay of the fuzzer's corpus through the normal build.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "sylva/dsl/Parser.h"
#include "sylva/dsl/ProjectLoader.h"

namespace sylva::dsl {
namespace {

namespace fs = std::filesystem;

TEST(Language, FileTooLargeIsOneLineError) {
    std::string text(kMaxProjectFileBytes + 1, '#');
    LoadResult result = loadProjectFromString(text, "big.sylva");
    ASSERT_EQ(result.diagnostics.size(), 1u);
    EXPECT_EQ(result.diagnostics[0].code, "E0002");
    EXPECT_FALSE(result.model.has_value());
}

TEST(Language, ListTooLongIsLocated) {
    std::string text = "param p = [";
    for (std::size_t i = 0; i <= Parser::kMaxListLength; ++i) {
        text += "1,";
    }
    text += "]\n";
    LoadResult result = loadProjectFromString(text, "long.sylva");
    ASSERT_FALSE(result.diagnostics.empty());
    EXPECT_EQ(result.diagnostics[0].code, "E0105");
    EXPECT_TRUE(result.diagnostics[0].location.valid());
}

TEST(Language, DeepBracketsDoNotOverflow) {
    std::string text = "param p = " + std::string(200000, '[') + "\n";
    LoadResult result = loadProjectFromString(text, "deep.sylva");
    ASSERT_FALSE(result.diagnostics.empty());
    EXPECT_EQ(result.diagnostics[0].code, "E0103");
}

TEST(Language, OneModelPerScenarioWithSharedHashes) {
    const char* text =
        "source height : noise { seed = 7 }\n"
        "source other : noise { seed = 8 }\n"
        "scenario today { layers = [@height] }\n"
        "scenario later extends today { override @height { seed = 9 } }\n"
        "scenario same extends today { layers += [@other] }\n";
    LoadResult result = loadProjectFromString(text, "s.sylva");
    ASSERT_EQ(result.render(), "");
    ASSERT_EQ(result.scenarios.size(), 3u);
    EXPECT_EQ(result.model->scenario, "today");
    const ProjectModel* today = result.modelFor("today");
    const ProjectModel* later = result.modelFor("later");
    const ProjectModel* same = result.modelFor("same");
    ASSERT_TRUE(today && later && same);
    EXPECT_EQ(result.modelFor("nope"), nullptr);
    EXPECT_NE(today->findSource("height")->contentHash, 0u);
    EXPECT_NE(today->findSource("height")->contentHash, later->findSource("height")->contentHash);
    EXPECT_EQ(today->findSource("height")->contentHash, same->findSource("height")->contentHash);
    EXPECT_EQ(today->findSource("other")->contentHash, later->findSource("other")->contentHash);
    EXPECT_EQ(later->findSource("height")->find("seed")->value.get<Quantity>()->value, 9.0);
    EXPECT_EQ(same->findScenario("same")->find("layers")->value.get<ValueList>()->size(), 2u);
}

// `override render { ... }` gives a scenario its own render attributes (sun shadows on
// in one, off in another), inherited through `extends`; the other scenarios keep the
// project's render block.
TEST(Language, ScenarioOverridesRenderAttributes) {
    const char* text =
        "source height : noise { seed = 7 }\n"
        "render { shadow_distance = 3km }\n"
        "scenario today { layers = [@height] }\n"
        "scenario flat extends today { override render { shadows = false } }\n"
        "scenario flatter extends flat { override render { shadow_distance = 500m } }\n";
    LoadResult result = loadProjectFromString(text, "r.sylva");
    ASSERT_EQ(result.render(), "");
    const ProjectModel* today = result.modelFor("today");
    const ProjectModel* flat = result.modelFor("flat");
    const ProjectModel* flatter = result.modelFor("flatter");
    ASSERT_TRUE(today && flat && flatter);
    EXPECT_TRUE(*today->render.find("shadows")->value.get<bool>());
    EXPECT_FALSE(*flat->render.find("shadows")->value.get<bool>());
    EXPECT_EQ(flat->render.find("shadow_distance")->value.get<Quantity>()->value, 3000.0);
    EXPECT_FALSE(*flatter->render.find("shadows")->value.get<bool>());
    EXPECT_EQ(flatter->render.find("shadow_distance")->value.get<Quantity>()->value, 500.0);
    EXPECT_NE(today->render.contentHash, flat->render.contentHash);
    EXPECT_EQ(today->findSource("height")->contentHash, flat->findSource("height")->contentHash);
}

TEST(Language, DeviceImportIsRefused) {
    LoadResult result = loadProjectFromString("import \"/dev/zero\" as z\n", "dev.sylva");
    ASSERT_EQ(result.diagnostics.size(), 1u);
    EXPECT_EQ(result.diagnostics[0].code, "E0001");
}

// Every input the fuzzer kept loads or yields located diagnostics, without crashing.
TEST(FuzzCorpus, ReplaysCleanly) {
    const fs::path corpus = fs::path(SYLVA_TEST_DATA_DIR) / "dsl" / "fuzz-corpus";
    int count = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(corpus)) {
        std::ifstream in(entry.path(), std::ios::binary);
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        LoadOptions options;
        options.maxImports = 2;
        LoadResult result = loadProjectFromString(text, "fuzz.sylva", options);
        for (const Diagnostic& diagnostic : result.diagnostics) {
            bool fileLevel = diagnostic.code == "E0002" || diagnostic.code == "E0003";
            EXPECT_TRUE(diagnostic.location.valid() || fileLevel)
                << entry.path() << ": " << diagnostic.code << " " << diagnostic.message;
        }
        EXPECT_NE(result.hasErrors(), result.model.has_value()) << entry.path();
        (void)result.render();
        ++count;
    }
    EXPECT_GT(count, 0);
}

}  // namespace
}  // namespace sylva::dsl
