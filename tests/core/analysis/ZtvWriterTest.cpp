// The ZTV GeoTIFF read back with GDAL: georeferencing, CRS, band names and values,
// compression, overviews; a failed write leaves no file behind.
#include "sylva/core/analysis/ZtvWriter.h"

#include <gdal.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva {
namespace {

namespace fs = std::filesystem;

ViewshedResult sampleResult() {
    ViewshedResult r;
    r.geometry = {500000.0, 5500000.0, 25.0, 25.0, 70, 40};
    const std::size_t cells = 70 * 40;
    r.visible.assign(cells, 0);
    r.count.assign(cells, 0);
    r.fraction.assign(cells, 0.0f);
    for (std::size_t i = 0; i < cells; i += 3) {
        r.visible[i] = 1;
        r.count[i] = std::uint16_t(1 + i % 4);
        r.fraction[i] = 0.25f * float(i % 5);
    }
    r.fraction[5] = std::nanf("");  // a no-data cell
    return r;
}

const char* kUtm32 =
    "PROJCS[\"WGS 84 / UTM zone 32N\",GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS "
    "84\",6378137,298.257223563]],PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433]],"
    "PROJECTION[\"Transverse_Mercator\"],PARAMETER[\"latitude_of_origin\",0],PARAMETER["
    "\"central_meridian\",9],PARAMETER[\"scale_factor\",0.9996],PARAMETER[\"false_easting\","
    "500000],PARAMETER[\"false_northing\",0],UNIT[\"metre\",1],AUTHORITY[\"EPSG\",\"32632\"]]";

TEST(ZtvWriter, GeoTiffReadsBackWithGeoreferencingBandsAndOverviews) {
    const fs::path dir = fs::path(SYLVA_TEST_OUTPUT_DIR) / "ztv-writer";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path path = dir / "ztv.tif";
    const ViewshedResult result = sampleResult();
    ASSERT_TRUE(writeZtvGeoTiff(path, result, kUtm32).ok());
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
    ASSERT_NE(ds, nullptr);
    EXPECT_EQ(GDALGetRasterXSize(ds), 70);
    EXPECT_EQ(GDALGetRasterYSize(ds), 40);
    ASSERT_EQ(GDALGetRasterCount(ds), 3);
    double gt[6];
    ASSERT_EQ(GDALGetGeoTransform(ds, gt), CE_None);
    EXPECT_DOUBLE_EQ(gt[0], 500000.0);
    EXPECT_DOUBLE_EQ(gt[1], 25.0);
    EXPECT_DOUBLE_EQ(gt[3], 5500000.0);
    EXPECT_DOUBLE_EQ(gt[5], -25.0);
    EXPECT_NE(std::string(GDALGetProjectionRef(ds)).find("32632"), std::string::npos);
    const char* compression = GDALGetMetadataItem(ds, "COMPRESSION", "IMAGE_STRUCTURE");
    ASSERT_NE(compression, nullptr);
    EXPECT_STREQ(compression, "DEFLATE");
    const char* names[] = {"visible", "count", "fraction"};
    for (int b = 0; b < 3; ++b) {
        GDALRasterBandH band = GDALGetRasterBand(ds, b + 1);
        EXPECT_STREQ(GDALGetDescription(band), names[b]);
        EXPECT_EQ(GDALGetOverviewCount(band), 1);  // 35 x 20 (min side 40 / 2 >= 16)
        std::vector<float> values(70 * 40);
        ASSERT_EQ(
            GDALRasterIO(band, GF_Read, 0, 0, 70, 40, values.data(), 70, 40, GDT_Float32, 0, 0),
            CE_None);
        for (std::size_t i = 0; i < values.size(); ++i) {
            const float want = i == 5   ? std::nanf("")
                               : b == 0 ? float(result.visible[i])
                               : b == 1 ? float(result.count[i])
                                        : result.fraction[i];
            if (std::isnan(want)) {
                EXPECT_TRUE(std::isnan(values[i])) << "band " << b;
            } else {
                ASSERT_EQ(values[i], want) << "band " << b << " cell " << i;
            }
        }
    }
    GDALClose(ds);
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_EQ(entry.path().filename(), "ztv.tif") << "left behind: " << entry.path();
}

TEST(ZtvWriter, FailureLeavesNothing) {
    const fs::path dir = fs::path(SYLVA_TEST_OUTPUT_DIR) / "ztv-writer-missing";
    fs::remove_all(dir);
    const Status status = writeZtvGeoTiff(dir / "ztv.tif", sampleResult(), kUtm32);
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find("ztv.tif"), std::string::npos) << status.error().message;
    EXPECT_FALSE(fs::exists(dir));
}

}  // namespace
}  // namespace sylva
