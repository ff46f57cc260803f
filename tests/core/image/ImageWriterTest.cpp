#include "sylva/core/image/ImageWriter.h"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace sylva {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
    const fs::path folder =
        fs::temp_directory_path() / ("sylva-imagewriter-" + std::to_string(::getpid())) / name;
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder;
}

void roundTrip(const std::string& name, bool opaque) {
    const fs::path folder = scratch(name);
    const int width = 5, height = 3;
    std::vector<std::uint8_t> pixels(std::size_t(width) * height * 4);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        pixels[i] = static_cast<std::uint8_t>((i * 37 + 11) % 256);
        if (opaque && i % 4 == 3) {
            pixels[i] = 255;
        }
    }
    const fs::path path = folder / "sub" / "image.png";  // missing parent is created
    const Status written = ImageWriter::writeRgba8(path, width, height, pixels);
    ASSERT_TRUE(written) << written.error().message;
    ASSERT_TRUE(fs::is_regular_file(path));
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        EXPECT_NE(entry.path().filename().string().rfind(".sylva-", 0), 0u)
            << "temporary left: " << entry.path();
    }
    int w = 0, h = 0;
    Result<std::vector<std::uint8_t>> read = ImageWriter::readRgba8(path, w, h);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(w, width);
    EXPECT_EQ(h, height);
    EXPECT_EQ(read.value(), pixels);
    fs::remove_all(folder);
}

TEST(ImageWriter, WritesAtomicallyAndReadsBack) {
    roundTrip("opaque", true);
}

TEST(ImageWriter, TranslucentPixelsReadBackUnchanged) {
    roundTrip("translucent", false);
}

// A grey + alpha PNG written by another library (GDAL's PNG driver: two bands are grey and
// alpha) reads as grey in R, G, B and its own alpha in A (the second channel used to be
// overwritten by grey, so every such image read as opaque).
TEST(ImageWriter, GreyAlphaPngKeepsItsAlpha) {
    GDALAllRegister();
    const fs::path folder = scratch("grey-alpha");
    const fs::path path = folder / "grey-alpha.png";
    const int width = 4, height = 2;
    std::vector<std::uint8_t> grey(width * height), alpha(width * height);
    for (int i = 0; i < width * height; ++i) {
        grey[std::size_t(i)] = std::uint8_t(30 * i + 10);
        alpha[std::size_t(i)] = std::uint8_t(255 - 25 * i);
    }
    GDALDriver* memory = GetGDALDriverManager()->GetDriverByName("MEM");
    GDALDriver* png = GetGDALDriverManager()->GetDriverByName("PNG");
    ASSERT_NE(memory, nullptr);
    ASSERT_NE(png, nullptr);
    GDALDataset* source = memory->Create("", width, height, 2, GDT_Byte, nullptr);
    ASSERT_NE(source, nullptr);
    ASSERT_EQ(source->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, width, height, grey.data(), width,
                                                 height, GDT_Byte, 0, 0),
              CE_None);
    ASSERT_EQ(source->GetRasterBand(2)->RasterIO(GF_Write, 0, 0, width, height, alpha.data(), width,
                                                 height, GDT_Byte, 0, 0),
              CE_None);
    GDALDataset* written =
        png->CreateCopy(path.string().c_str(), source, FALSE, nullptr, nullptr, nullptr);
    ASSERT_NE(written, nullptr);
    GDALClose(written);
    GDALClose(source);
    int w = 0, h = 0;
    Result<std::vector<std::uint8_t>> read = ImageWriter::readRgba8(path, w, h);
    ASSERT_TRUE(read) << read.error().message;
    ASSERT_EQ(w, width);
    ASSERT_EQ(h, height);
    for (std::size_t i = 0; i < grey.size(); ++i) {
        EXPECT_EQ(read.value()[i * 4 + 0], grey[i]) << "pixel " << i;
        EXPECT_EQ(read.value()[i * 4 + 1], grey[i]) << "pixel " << i;
        EXPECT_EQ(read.value()[i * 4 + 2], grey[i]) << "pixel " << i;
        EXPECT_EQ(read.value()[i * 4 + 3], alpha[i]) << "pixel " << i;
    }
    fs::remove_all(folder);
}

TEST(ImageWriter, ParentIsARegularFile) {
    const fs::path folder = scratch("blocked");
    const fs::path file = folder / "not-a-folder";
    std::ofstream(file) << "x";
    const fs::path path = file / "image.png";
    const Status written = ImageWriter::writeRgba8(path, 1, 1, {0, 0, 0, 255});
    ASSERT_FALSE(written);
    EXPECT_NE(written.error().message.find(path.string()), std::string::npos)
        << written.error().message;
    EXPECT_EQ(fs::file_size(file), 1u);
    fs::remove_all(folder.parent_path());
}

TEST(ImageWriter, ReadingAMissingFileFailsWithThePath) {
    int w = 0, h = 0;
    const fs::path path = scratch("missing") / "none.png";
    Result<std::vector<std::uint8_t>> read = ImageWriter::readRgba8(path, w, h);
    ASSERT_FALSE(read);
    EXPECT_NE(read.error().message.find(path.string()), std::string::npos) << read.error().message;
    fs::remove_all(path.parent_path().parent_path());
}

TEST(ImageWriter, LinearExrKeepsValuesAndMetadataAndClampsToHalf) {
    const fs::path folder = scratch("exr");
    LinearImage image(3, 2, 0.25f, 1.5f, 7.0f, 1.0f);
    image.at(2, 1)[0] = 1.0e6f;  // beyond half: stored as the largest half, not infinity
    ImageMetadata metadata;
    metadata.set("sylva:scenario", "today");
    metadata.set("sylva:time", "2024-06-21T09:00:00-03:00");
    const fs::path path = folder / "radiance.EXR";
    EXPECT_TRUE(ImageWriter::isExr(path));
    EXPECT_FALSE(ImageWriter::isExr(folder / "radiance.png"));
    const Status written = ImageWriter::writeLinear(path, image, metadata);
    ASSERT_TRUE(written) << written.error().message;
    Result<LinearImage> read = ImageWriter::readLinear(path);
    ASSERT_TRUE(read) << read.error().message;
    ASSERT_EQ(read.value().width, 3);
    EXPECT_FLOAT_EQ(read.value().at(0, 0)[0], 0.25f);  // exact in half
    EXPECT_FLOAT_EQ(read.value().at(0, 0)[1], 1.5f);
    EXPECT_FLOAT_EQ(read.value().at(1, 1)[2], 7.0f);
    EXPECT_FLOAT_EQ(read.value().at(2, 1)[0], 65504.0f);
    Result<ImageMetadata> stored =
        ImageWriter::readMetadata(path, {"sylva:scenario", "sylva:time", "sylva:none"});
    ASSERT_TRUE(stored) << stored.error().message;
    ASSERT_EQ(stored.value().attributes.size(), 2u);
    EXPECT_EQ(*stored.value().find("sylva:scenario"), "today");
    EXPECT_EQ(*stored.value().find("sylva:time"), "2024-06-21T09:00:00-03:00");
    for (const auto& entry : fs::directory_iterator(folder)) {
        EXPECT_NE(entry.path().filename().string().rfind(".sylva-", 0), 0u) << entry.path();
    }
    fs::remove_all(folder.parent_path());
}

TEST(ImageWriter, PngCarriesMetadataAsText) {
    const fs::path folder = scratch("pngtext");
    ImageMetadata metadata;
    metadata.set("sylva:camera", "beach");
    const fs::path path = folder / "image.png";
    ASSERT_TRUE(ImageWriter::writeRgba8(path, 1, 1, {1, 2, 3, 255}, metadata));
    Result<ImageMetadata> stored = ImageWriter::readMetadata(path, {"sylva:camera"});
    ASSERT_TRUE(stored) << stored.error().message;
    ASSERT_NE(stored.value().find("sylva:camera"), nullptr);
    EXPECT_EQ(*stored.value().find("sylva:camera"), "beach");
    fs::remove_all(folder.parent_path());
}

}  // namespace
}  // namespace sylva
