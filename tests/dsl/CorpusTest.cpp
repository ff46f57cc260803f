// The golden corpus: every tests/dsl/cases/X.sylva is loaded and its rendered diagnostics
// compared with X.expected; when it loads, its `dump --json` with X.json. Properties over
// the corpus and the sample projects: fmt is idempotent and parse(fmt(x)) == parse(x).
//
// A case may start with directive comments:
//   # args: -D name=value --set block.attr=value --lenient --max-imports N --test-schema
// SYLVA_UPDATE_DSL_GOLDENS=1 rewrites the .expected and .json files from the output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "sylva/dsl/Formatter.h"
#include "sylva/dsl/ModelJson.h"
#include "sylva/dsl/ProjectLoader.h"

namespace sylva::dsl {
namespace {

namespace fs = std::filesystem;

const fs::path kCases = fs::path(SYLVA_TEST_DATA_DIR) / "dsl" / "cases";

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeFile(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << text;
}

bool updating() {
    const char* value = std::getenv("SYLVA_UPDATE_DSL_GOLDENS");
    return value && std::string(value) == "1";
}

// The built-in schema plus a source kind that can form a well-typed cycle.
const SchemaRegistry& testSchema() {
    static const SchemaRegistry registry = [] {
        SchemaRegistry r = SchemaRegistry::builtin();
        AttributeSchema input;
        input.name = "input";
        input.type = ValueType::Reference;
        input.port = PortType::Elevation;
        input.target = "source";
        r.add({"source", "smooth", PortType::Elevation, "Test kind: smooths its input.", {input}});
        return r;
    }();
    return registry;
}

LoadOptions optionsFor(const std::string& text) {
    LoadOptions options;
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line) && line.rfind("#", 0) == 0) {
        if (line.rfind("# args:", 0) != 0) {
            continue;
        }
        std::istringstream words(line.substr(7));
        std::string word;
        while (words >> word) {
            auto split = [](const std::string& assignment) {
                std::size_t equals = assignment.find('=');
                return std::make_pair(assignment.substr(0, equals), assignment.substr(equals + 1));
            };
            if (word == "-D" && words >> word) {
                options.defines.push_back(split(word));
            } else if (word == "--set" && words >> word) {
                options.sets.push_back(split(word));
            } else if (word == "--lenient") {
                options.lenient = true;
            } else if (word == "--max-imports" && words >> word) {
                options.maxImports = static_cast<std::size_t>(std::stoul(word));
            } else if (word == "--test-schema") {
                options.schema = &testSchema();
            }
        }
    }
    return options;
}

std::vector<ProjectModel> modelsOf(const LoadResult& result) {
    if (!result.scenarios.empty()) {
        return result.scenarios;
    }
    return result.model ? std::vector<ProjectModel>{*result.model} : std::vector<ProjectModel>{};
}

std::vector<std::string> caseNames() {
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(kCases)) {
        if (entry.path().extension() == ".sylva") {
            names.push_back(entry.path().stem().string());
        }
    }
    std::sort(names.begin(), names.end());
    return names;
}

// Runs in the cases folder so diagnostics name files as "X.sylva" and imports resolve.
class CasesDirectory {
public:
    CasesDirectory() : saved_(fs::current_path()) { fs::current_path(kCases); }
    ~CasesDirectory() { fs::current_path(saved_); }

private:
    fs::path saved_;
};

class Corpus : public ::testing::TestWithParam<std::string> {};

TEST_P(Corpus, MatchesGoldens) {
    CasesDirectory inCases;
    const std::string name = GetParam();
    const std::string text = readFile(name + ".sylva");
    const LoadOptions options = optionsFor(text);
    LoadResult result = loadProject(name + ".sylva", options);
    const std::string rendered = result.render();
    const std::string json = result.model ? modelsToJson(modelsOf(result)) : "";
    if (updating()) {
        writeFile(name + ".expected", rendered);
        if (!json.empty()) {
            writeFile(name + ".json", json);
        } else {
            fs::remove(name + ".json");
        }
        return;
    }
    ASSERT_TRUE(fs::exists(name + ".expected")) << "run with SYLVA_UPDATE_DSL_GOLDENS=1";
    EXPECT_EQ(rendered, readFile(name + ".expected"));
    if (!json.empty()) {
        ASSERT_TRUE(fs::exists(name + ".json")) << "run with SYLVA_UPDATE_DSL_GOLDENS=1";
        EXPECT_EQ(json, readFile(name + ".json"));
    } else {
        EXPECT_FALSE(fs::exists(name + ".json")) << "stale golden: the case no longer loads";
    }
}

// fmt is idempotent, and the formatted text means the same: same diagnostics (codes and
// messages) and, when it loads, the same model.
void checkFormatProperties(const fs::path& file, const std::string& displayName,
                           const LoadOptions& options) {
    const std::string text = readFile(file);
    SourceFiles sources;
    std::vector<Diagnostic> diagnostics;
    std::optional<std::string> once = Formatter::format(text, displayName, sources, diagnostics);
    if (!once) {
        return;  // syntax errors: fmt refuses, which the diagnostics explain
    }
    std::optional<std::string> twice = Formatter::format(*once, displayName, sources, diagnostics);
    ASSERT_TRUE(twice.has_value());
    EXPECT_EQ(*twice, *once) << displayName << ": fmt is not idempotent";

    LoadResult original = loadProjectFromString(text, displayName, options);
    LoadResult formatted = loadProjectFromString(*once, displayName, options);
    auto summary = [](const LoadResult& result) {
        std::string out;
        for (const Diagnostic& diagnostic : result.diagnostics) {
            out += diagnostic.code + " " + diagnostic.message + "\n";
        }
        if (result.model) {
            out += modelsToJson(modelsOf(result));
        }
        return out;
    };
    EXPECT_EQ(summary(formatted), summary(original)) << displayName << ": fmt changed the meaning";
}

TEST_P(Corpus, FormatIsIdempotentAndKeepsMeaning) {
    CasesDirectory inCases;
    const std::string name = GetParam();
    checkFormatProperties(name + ".sylva", name + ".sylva", optionsFor(readFile(name + ".sylva")));
}

INSTANTIATE_TEST_SUITE_P(Cases, Corpus, ::testing::ValuesIn(caseNames()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                             return param.param;
                         });

TEST(CorpusSize, AtLeastSixtyCases) {
    EXPECT_GE(caseNames().size(), 60u);
}

// Every error and warning code the language reports has a case whose .expected shows it.
TEST(CorpusSize, EveryCodeHasACase) {
    std::string all;
    for (const std::string& name : caseNames()) {
        all += readFile(kCases / (name + ".expected"));
    }
    for (const char* code :
         {"E0001", "E0003", "E0004", "E0005", "E0006", "E0007", "E0008", "E0009", "E0011", "E0012",
          "E0101", "E0102", "E0103", "E0104", "E0201", "E0202", "E0203", "E0204", "E0205", "E0206",
          "E0207", "E0208", "E0209", "E0210", "E0211", "E0212", "E0213", "E0214", "E0301", "E0302",
          "E0303", "E0401", "E0402", "E0403", "E0404", "E0405", "E0406", "E0407", "E0408", "E0409",
          "E0410", "E0412", "E0413", "E0414", "W0101", "W0102", "W0201", "W0202"}) {
        EXPECT_NE(all.find(std::string("[") + code + "]"), std::string::npos)
            << "no corpus case shows " << code;
    }
}

TEST(SampleProjects, FormatPropertiesAndNoWarnings) {
    const fs::path projects = fs::path(SYLVA_SOURCE_DIR) / "projects";
    int count = 0;
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(projects)) {
        if (entry.path().extension() != ".sylva") {
            continue;
        }
        ++count;
        LoadResult result = loadProject(entry.path());
        EXPECT_EQ(result.render(), "") << entry.path();
        checkFormatProperties(entry.path(), entry.path().string(), {});
    }
    EXPECT_GT(count, 0);
}

}  // namespace
}  // namespace sylva::dsl
