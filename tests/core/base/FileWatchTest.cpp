#include "sylva/core/base/FileWatch.h"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <thread>

#include <gdal.h>
#include <unistd.h>

#include "sylva/core/sources/GdalDatasetPool.h"
#include "sylva/core/sources/raster/RasterSource.h"

namespace sylva {
namespace {

// Writes a 16 x 16 Float32 GeoTIFF on WGS84 longitude/latitude with GDAL.
void writeGeoTiff(const std::filesystem::path& path, float value) {
    GdalDatasetPool::registerDrivers();
    GDALDatasetH dataset =
        GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), 16, 16, 1, GDT_Float32, nullptr);
    ASSERT_NE(dataset, nullptr);
    std::array<double, 6> transform{-35.0, 0.01, 0.0, -8.0, 0.0, -0.01};
    GDALSetGeoTransform(dataset, transform.data());
    GDALSetProjection(
        dataset,
        "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],"
        "PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433],AXIS[\"Latitude\",NORTH],"
        "AXIS[\"Longitude\",EAST],AUTHORITY[\"EPSG\",\"4326\"]]");
    std::vector<float> data(256, value);
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(dataset, 1), GF_Write, 0, 0, 16, 16, data.data(), 16,
                           16, GDT_Float32, 0, 0),
              CE_None);
    GDALClose(dataset);
}

TEST(FileWatch, ReportsARewrittenGeoTiffAndTheRasterHashChanges) {
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() / ("sylva_filewatch_" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    const std::filesystem::path file = folder / "dem.tif";
    const std::filesystem::path other = folder / "other.tif";
    writeGeoTiff(file, 10.0f);
    writeGeoTiff(other, 1.0f);

    RasterParameters parameters;
    parameters.file = file;
    const std::unique_ptr<RasterSource> before = RasterSource::open("dem", parameters);
    ASSERT_FALSE(before->openError()) << before->openError()->message;
    ASSERT_EQ(before->files().size(), 1u);
    EXPECT_EQ(before->files()[0], file);

    FileWatch watch;
    for (const std::filesystem::path& watched : before->files()) {
        watch.watch(watched);
    }
    watch.watch(other);
    watch.watch(folder / "appears.tif");
    EXPECT_EQ(watch.size(), 3u);
    EXPECT_TRUE(watch.poll().empty());

    // Same size, new content and modification time (nanosecond stamps; GDAL rewrites
    // the file in place).
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    writeGeoTiff(file, 20.0f);
    EXPECT_EQ(watch.poll(), std::vector<std::filesystem::path>{file});
    EXPECT_TRUE(watch.poll().empty());  // reported once
    const std::unique_ptr<RasterSource> after = RasterSource::open("dem", parameters);
    EXPECT_NE(after->contentHash(), before->contentHash());

    // Replaced by rename (new inode), created, deleted.
    const std::filesystem::path staged = folder / "staged.tif";
    writeGeoTiff(staged, 1.0f);
    std::filesystem::rename(staged, other);
    writeGeoTiff(folder / "appears.tif", 3.0f);
    EXPECT_EQ(watch.poll(), (std::vector<std::filesystem::path>{folder / "appears.tif", other}));
    std::filesystem::remove(file);
    EXPECT_EQ(watch.poll(), std::vector<std::filesystem::path>{file});
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace sylva
