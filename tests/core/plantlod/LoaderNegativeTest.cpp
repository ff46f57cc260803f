// Negative tests of every file loader Sylva parses itself, in the manner of GDAL's
// autotest: a missing file, a truncated file, a file of the wrong type and a file
// claiming huge dimensions each fail with a message that names the file, and never
// crash or allocate what the file claims.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sylva/core/plantlod/PlantImporter.h"
#include "sylva/core/plantlod/PlantSidecar.h"
#include "sylva/core/plantlod/PlodFile.h"
#include "sylva/core/scene/RenderManifest.h"

namespace sylva {
namespace {

std::filesystem::path scratch(const std::string& name) {
    const auto folder =
        std::filesystem::temp_directory_path() / ("sylva_loader_neg_" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    return folder / name;
}

std::filesystem::path write(const std::string& name, const std::string& bytes) {
    const auto path = scratch(name);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    return path;
}

// A PNG signature and IHDR: the wrong type for every loader here.
// (The literal's own size, less its terminator: a hand-counted 33 read past its end, found
// by AddressSanitizer.)
constexpr char kPngBytes[] = "\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\0\x01\0\0\0\x01\x08\x06\0\0\0";
const std::string kPng(kPngBytes, sizeof kPngBytes - 1);

template <typename ResultType>
void expectNamedFailure(const ResultType& result, const std::filesystem::path& path) {
    ASSERT_FALSE(result.ok()) << path;
    EXPECT_NE(result.error().message.find(path.filename().string()), std::string::npos)
        << result.error().message;
}

TEST(LoaderNegative, GltfMissingTruncatedWrongTypeHuge) {
    expectNamedFailure(PlantImporter::import(scratch("absent.gltf")), scratch("absent.gltf"));
    const auto truncated =
        write("truncated.gltf", R"({"asset":{"version":"2.0"},"meshes":[{"prim)");
    expectNamedFailure(PlantImporter::import(truncated), truncated);
    const auto glb = write("truncated.glb", std::string("glTF\x02\0\0\0\x40\0\0\0", 12));
    expectNamedFailure(PlantImporter::import(glb), glb);
    const auto png = write("picture.gltf", kPng);
    expectNamedFailure(PlantImporter::import(png), png);
    // An accessor of 357 million VEC3 in a 4 GiB buffer that is not there.
    const auto huge = write(
        "huge.gltf",
        R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4294967295}],)"
        R"("bufferViews":[{"buffer":0,"byteLength":4294967295}],"accessors":[{"bufferView":0,)"
        R"("componentType":5126,"count":357913941,"type":"VEC3"}],)"
        R"("meshes":[{"name":"leaves","primitives":[{"attributes":{"POSITION":0}}]}],)"
        R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})");
    expectNamedFailure(PlantImporter::import(huge), huge);
}

TEST(LoaderNegative, ObjMissingTruncatedWrongTypeHuge) {
    expectNamedFailure(PlantImporter::import(scratch("absent.obj")), scratch("absent.obj"));
    const auto truncated = write("truncated.obj", "o leaves\nv 0 0 0\nv 1 0 0\nv 0 1");
    expectNamedFailure(PlantImporter::import(truncated), truncated);
    const auto png = write("picture.obj", kPng);
    expectNamedFailure(PlantImporter::import(png), png);
    // A face index far beyond the vertices: an error, not an allocation of that size.
    const auto huge = write("huge.obj", "o leaves\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2000000000\n");
    expectNamedFailure(PlantImporter::import(huge), huge);
}

TEST(LoaderNegative, PlodMissingTruncatedWrongTypeHuge) {
    expectNamedFailure(readPlodFile(scratch("absent.plod").string()), scratch("absent.plod"));
    const auto png = write("picture.plod", kPng);
    expectNamedFailure(readPlodFile(png.string()), png);
    for (std::size_t size : {0u, 4u, 8u, 16u, 40u}) {
        const auto truncated =
            write("truncated.plod", std::string("PLOD\x01\0\0\0", 8) + std::string(64, '\xff'));
        std::filesystem::resize_file(truncated, size);
        expectNamedFailure(readPlodFile(truncated.string()), truncated);
    }
    // A header whose counts and sizes are all 0xFF...: huge claims, a small file.
    const auto huge = write("huge.plod", std::string("PLOD", 4) + std::string(252, '\xff'));
    expectNamedFailure(readPlodFile(huge.string()), huge);
}

TEST(LoaderNegative, ManifestTruncatedWrongTypeHuge) {
    const auto missing = scratch("absent-manifest.json");
    RenderManifest absent(missing);
    EXPECT_TRUE(absent.load()) << "a missing manifest is an empty one";
    EXPECT_TRUE(absent.entries().empty());
    for (const auto& [name, bytes] : std::vector<std::pair<std::string, std::string>>{
             {"truncated.json", R"({"format": "sylva-render-manifest", "images": [{"out)"},
             {"picture.json", kPng},
             {"array.json", "[1, 2, 3]"},
             {"wrongfield.json",
              R"({"format": "sylva-render-manifest", "version": 1, "images": [{"output": 7}]})"},
             {"deep.json", std::string(100000, '[') + std::string(100000, ']')}}) {
        const auto path = write(name, bytes);
        RenderManifest manifest(path);
        const Status loaded = manifest.load();
        ASSERT_FALSE(loaded) << name;
        EXPECT_NE(loaded.error().message.find(name), std::string::npos) << loaded.error().message;
    }
}

TEST(LoaderNegative, SidecarTruncatedWrongType) {
    const auto model = scratch("sidecar_model.gltf");
    EXPECT_TRUE(PlantSidecar::readFor(model)) << "no sidecar is no parts";
    for (const std::string& bytes :
         {std::string(R"({"parts": {"a": "le)"), kPng, std::string(R"({"parts": ["leaf"]})"),
          std::string(R"({"parts": {"a": "trunk"}})")}) {
        write(PlantSidecar::pathFor(model).filename().string(), bytes);
        Result<PlantSidecar> sidecar = PlantSidecar::readFor(model);
        ASSERT_FALSE(sidecar) << bytes;
        EXPECT_NE(sidecar.error().message.find(PlantSidecar::pathFor(model).filename().string()),
                  std::string::npos)
            << sidecar.error().message;
    }
}

}  // namespace
}  // namespace sylva
