#include "sylva/core/scene/RenderManifest.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace sylva {
namespace {

TEST(RenderManifestTest, RoundTripAndCurrentness) {
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() / "sylva-manifest-test";
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder / "today");
    RenderManifest manifest(folder / "manifest.json");
    ASSERT_TRUE(manifest.load().ok());  // missing = empty
    EXPECT_TRUE(manifest.entries().empty());
    ManifestEntry entry;
    entry.output = "today/beach.png";
    entry.kind = "image";
    entry.view = "photos";
    entry.camera = "beach";
    entry.scenario = "today";
    entry.time = "2024-06-21T09:00:00-03:00";
    entry.hash = 0xfedcba9876543210ull;
    entry.seconds = 2.5;
    entry.tilesGenerated = 42;
    manifest.record(entry);
    ASSERT_TRUE(manifest.save().ok());
    EXPECT_FALSE(std::filesystem::exists(folder / "manifest.json.tmp"));

    RenderManifest again(folder / "manifest.json");
    ASSERT_TRUE(again.load().ok());
    ASSERT_EQ(again.entries().size(), 1u);
    const ManifestEntry& loaded = again.entries().begin()->second;
    EXPECT_EQ(loaded.hash, entry.hash);
    EXPECT_EQ(loaded.time, entry.time);
    EXPECT_EQ(loaded.tilesGenerated, 42u);
    // Current only with the same hash and an existing image.
    EXPECT_FALSE(again.isCurrent("today/beach.png", entry.hash));
    std::ofstream(folder / "today/beach.png") << "png";
    EXPECT_TRUE(again.isCurrent("today/beach.png", entry.hash));
    EXPECT_FALSE(again.isCurrent("today/beach.png", entry.hash + 1));
    EXPECT_FALSE(again.isCurrent("today/hill.png", entry.hash));

    std::ofstream(folder / "manifest.json") << "{ not json";
    RenderManifest corrupt(folder / "manifest.json");
    EXPECT_EQ(corrupt.load().error().message,
              "manifest '" + (folder / "manifest.json").string() +
                  "' is corrupt (not a Sylva manifest): delete it to render everything");
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace sylva
