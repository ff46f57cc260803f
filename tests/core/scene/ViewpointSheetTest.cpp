// Viewpoint records and sheets (issue 18): the record's fields equal the camera's own
// values (fields of view from ImageProjection's independent formulas, bearing, heights,
// print and viewing distance), the JSON sidecar and the image metadata carry the same
// text, the sun comes from NOAA for the given time; the PDF's page size read back with
// poppler's pdfinfo equals the requested sheet, the PNG's size is the sheet at its dpi.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <string>

#include "sylva/core/geo/SolarPosition.h"
#include "sylva/core/scene/ImageProjection.h"
#include "sylva/core/scene/ViewpointRecord.h"
#include "sylva/core/scene/ViewpointSheet.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

Camera natureScotCamera() {
    Camera camera;
    camera.geodetic = {56.5 * kDegree, -4.2 * kDegree, 301.5};
    camera.position = Ellipsoid::toEcef(camera.geodetic);
    camera.groundHeight = 300.0;
    camera.eyeHeight = 1.5;
    camera.axes = Camera::axesFromAngles(camera.geodetic, 247.5 * kDegree, 0.0, 0.0);
    camera.horizontalFov = 53.5 * kDegree;
    camera.print = {0.820, 0.260, 20.0};  // 20 dpi keeps the test image small
    return camera;
}

ViewpointRecord describe(const Camera& camera, int width, int height) {
    ViewpointInputs inputs;
    inputs.id = "vp1";
    inputs.name = "Ben Ledi summit path";
    inputs.scenario = "proposed";
    inputs.width = width;
    inputs.height = height;
    inputs.time = DateTime::parse("2024-06-21T14:30+01:00").value();
    inputs.unixSeconds = inputs.time->unixSeconds().value();
    inputs.crs = "EPSG:27700";
    inputs.dataSources = {"dem (raster)", "colour (hypsometric)"};
    inputs.version = "0.1.0";
    inputs.projectHash = "0123456789abcdef";
    return ViewpointRecord::describe(camera, inputs);
}

double number(const ViewpointRecord& record, const std::string& key) {
    const ViewpointField* field = record.find(key);
    EXPECT_NE(field, nullptr) << key;
    return field && field->number ? *field->number : std::nan("");
}

TEST(ViewpointRecord, FieldsEqualTheCamerasValues) {
    const Camera camera = natureScotCamera();
    const int width = camera.print.pixelsWide(), height = camera.print.pixelsHigh();
    const ViewpointRecord record = describe(camera, width, height);
    EXPECT_NEAR(number(record, "horizontal_fov_deg"), 53.5, 1e-9);
    // Vertical field from the image aspect: 2 atan(tan(26.75°) · h / w).
    EXPECT_NEAR(number(record, "vertical_fov_deg"),
                2 * std::atan(std::tan(26.75 * kDegree) * height / width) / kDegree, 1e-9);
    EXPECT_NEAR(number(record, "bearing_deg"), 247.5, 1e-9);
    EXPECT_NEAR(number(record, "latitude_deg"), 56.5, 1e-12);
    EXPECT_NEAR(number(record, "longitude_deg"), -4.2, 1e-12);
    EXPECT_NEAR(number(record, "ground_height_m"), 300.0, 1e-12);
    EXPECT_NEAR(number(record, "eye_height_m"), 1.5, 1e-12);
    EXPECT_NEAR(number(record, "viewing_distance_mm"), 820.0 / (2 * std::tan(26.75 * kDegree)),
                1e-9);
    EXPECT_EQ(record.find("projection")->text, "planar");
    EXPECT_EQ(record.find("pitch_deg")->text, "0.00°");  // a level camera, no "-0.00°"
    EXPECT_EQ(record.find("time_utc")->text, "2024-06-21T13:30:00Z");
    const SunDirection sun = SolarPosition::seenFrom(record.find("time_utc") ? 1718976600.0 : 0.0,
                                                     56.5 * kDegree, -4.2 * kDegree);
    EXPECT_NEAR(number(record, "sun_azimuth_deg"), sun.azimuth / kDegree, 1e-9);
    EXPECT_NEAR(number(record, "sun_elevation_deg"), sun.elevation / kDegree, 1e-9);
    // British National Grid, as `echo "-4.2 56.5" | gdaltransform -s_srs EPSG:4326 -t_srs
    // EPSG:27700 -output_xy` prints it.
    EXPECT_NEAR(number(record, "grid_x"), 264675.176, 0.01);
    EXPECT_NEAR(number(record, "grid_y"), 736382.613, 0.01);
    // Image metadata and JSON carry the same text and numbers.
    ImageMetadata metadata;
    record.addTo(metadata);
    for (const ViewpointField& field : record.fields()) {
        ASSERT_NE(metadata.find("sylva:viewpoint:" + field.key), nullptr) << field.key;
        EXPECT_EQ(*metadata.find("sylva:viewpoint:" + field.key), field.text);
    }
    const std::string json = record.json();
    EXPECT_NE(json.find("\"id\": \"vp1\""), std::string::npos) << json;
    EXPECT_NE(json.find("\"horizontal_fov_deg\": 53.5"), std::string::npos) << json;
}

// `pdfinfo FILE` → "Page size: W x H pts".
std::pair<double, double> pdfPageSize(const std::filesystem::path& pdf) {
    const std::string command = "pdfinfo '" + pdf.string() + "'";
    FILE* pipe = popen(command.c_str(), "r");
    EXPECT_NE(pipe, nullptr);
    std::string output;
    char buffer[256];
    while (pipe && fgets(buffer, sizeof buffer, pipe)) {
        output += buffer;
    }
    if (pipe) {
        pclose(pipe);
    }
    std::smatch match;
    const std::regex pattern("Page size:\\s+([0-9.]+) x ([0-9.]+) pts");
    EXPECT_TRUE(std::regex_search(output, match, pattern)) << output;
    return match.size() == 3 ? std::pair{std::stod(match[1]), std::stod(match[2])}
                             : std::pair{0.0, 0.0};
}

TEST(ViewpointSheet, PdfPageIsTheRequestedSheetAndPngIsItAtTheDpi) {
    if (std::system("pdfinfo -v > /dev/null 2>&1") != 0) {
        GTEST_SKIP() << "pdfinfo (poppler-utils, scripts/setup) is not installed";
    }
    const Camera camera = natureScotCamera();
    const int width = camera.print.pixelsWide(), height = camera.print.pixelsHigh();
    RgbaImage image(width, height, 90, 140, 200);
    const ViewpointRecord record = describe(camera, width, height);
    const std::filesystem::path folder = std::filesystem::path(SYLVA_TEST_OUTPUT_DIR) / "sheets";
    std::filesystem::create_directories(folder);
    SheetLayout layout;
    layout.page = glm::dvec2(0.841, 0.297);  // NatureScot: 820 x 260 mm on 841 x 297 mm
    ASSERT_TRUE(ViewpointSheet::write(image, camera.print, record, layout, folder / "vp1.pdf",
                                      folder / "vp1.png"));
    const auto [w, h] = pdfPageSize(folder / "vp1.pdf");
    EXPECT_NEAR(w, 841.0 / 25.4 * 72.0, 0.01);
    EXPECT_NEAR(h, 297.0 / 25.4 * 72.0, 0.01);
    // The PNG's IHDR chunk: width and height big-endian at bytes 16 and 20.
    std::ifstream png(folder / "vp1.png", std::ios::binary);
    unsigned char header[24] = {};
    png.read(reinterpret_cast<char*>(header), sizeof header);
    ASSERT_TRUE(png);
    const auto bigEndian = [&](int at) {
        return int(header[at]) << 24 | int(header[at + 1]) << 16 | int(header[at + 2]) << 8 |
               int(header[at + 3]);
    };
    EXPECT_EQ(bigEndian(16), int(std::lround(0.841 / 0.0254 * 20)));
    EXPECT_EQ(bigEndian(20), int(std::lround(0.297 / 0.0254 * 20)));
    // A sheet too small for the image is an error and writes nothing.
    layout.page = glm::dvec2(0.600, 0.297);
    Status small = ViewpointSheet::write(image, camera.print, record, layout, folder / "small.pdf",
                                         folder / "small.png");
    ASSERT_FALSE(small);
    EXPECT_NE(small.error().message.find("do not fit on a 600 x 297 mm sheet"), std::string::npos)
        << small.error().message;
    EXPECT_FALSE(std::filesystem::exists(folder / "small.pdf"));
    EXPECT_FALSE(std::filesystem::exists(folder / "small.png"));
}

}  // namespace
}  // namespace sylva
