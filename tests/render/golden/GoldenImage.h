// Golden-image comparison shared by the golden tests: RMSE and maximum channel error
// over RGB (llvmpipe is deterministic on one Mesa version; the tolerance absorbs small
// driver changes). SYLVA_UPDATE_GOLDENS=1 (`make goldens`) rewrites the golden instead;
// on failure the actual image and a difference image go to build/test-output/.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "sylva/core/image/ImageWriter.h"

namespace sylva::golden {

struct Comparison {
    double rmse = 0;
    int maxError = 0;
};

inline Comparison compareImages(const std::vector<std::uint8_t>& a,
                                const std::vector<std::uint8_t>& b,
                                std::vector<std::uint8_t>* difference) {
    Comparison result;
    double sum = 0;
    if (difference) {
        difference->assign(a.size(), 255);
    }
    for (std::size_t i = 0; i < a.size(); i += 4) {
        int pixelError = 0;
        for (int c = 0; c < 3; ++c) {
            const int d = std::abs(int(a[i + c]) - int(b[i + c]));
            sum += double(d) * d;
            pixelError = std::max(pixelError, d);
        }
        result.maxError = std::max(result.maxError, pixelError);
        if (difference) {
            const auto v = static_cast<std::uint8_t>(std::min(255, pixelError * 8));
            (*difference)[i] = v;
            (*difference)[i + 1] = v;
            (*difference)[i + 2] = v;
        }
    }
    result.rmse = std::sqrt(sum / (double(a.size()) / 4 * 3));
    return result;
}

inline std::filesystem::path goldenPath(const std::string& name) {
    return std::filesystem::path(SYLVA_TEST_DATA_DIR) / "render" / "goldens" / (name + ".png");
}

// Whether this run rewrites the goldens (SYLVA_UPDATE_GOLDENS=1, `make goldens`).
inline bool updatingGoldens() {
    const char* update = std::getenv("SYLVA_UPDATE_GOLDENS");
    return update != nullptr && std::string(update) == "1";
}

// Compares `pixels` (RGBA8, width × height) with tests/render/goldens/<name>.png and never
// rewrites it: for images that another test's render defines (e.g. the example program's
// output against the demo golden).
inline void expectMatchesGolden(const std::string& name, int width, int height,
                                const std::vector<std::uint8_t>& pixels, double rmseLimit = 2.0,
                                int maxLimit = 96) {
    ASSERT_EQ(pixels.size(), std::size_t(width) * height * 4);
    const std::filesystem::path golden = goldenPath(name);
    const std::filesystem::path outputs = std::filesystem::path(SYLVA_TEST_OUTPUT_DIR);
    int goldenWidth = 0, goldenHeight = 0;
    Result<std::vector<std::uint8_t>> expected =
        ImageWriter::readRgba8(golden, goldenWidth, goldenHeight);
    ASSERT_TRUE(expected) << expected.error().message << " (create it with `make goldens`)";
    ASSERT_EQ(goldenWidth, width);
    ASSERT_EQ(goldenHeight, height);
    std::vector<std::uint8_t> difference;
    const Comparison c = compareImages(pixels, expected.value(), &difference);
    const bool ok = c.rmse <= rmseLimit && c.maxError <= maxLimit;
    if (!ok) {
        std::filesystem::create_directories(outputs);
        (void)ImageWriter::writeRgba8(outputs / (name + ".actual.png"), width, height, pixels);
        (void)ImageWriter::writeRgba8(outputs / (name + ".diff.png"), width, height, difference);
    }
    EXPECT_TRUE(ok) << name << ": RMSE " << c.rmse << " (limit " << rmseLimit << "), max error "
                    << c.maxError << " (limit " << maxLimit << "); actual and diff written to "
                    << outputs;
}

// Compares `pixels` (RGBA8, width × height) with tests/render/goldens/<name>.png, or with
// SYLVA_UPDATE_GOLDENS=1 writes them as the new golden.
inline void checkGolden(const std::string& name, int width, int height,
                        const std::vector<std::uint8_t>& pixels, double rmseLimit = 2.0,
                        int maxLimit = 96) {
    ASSERT_EQ(pixels.size(), std::size_t(width) * height * 4);
    if (updatingGoldens()) {
        const std::filesystem::path golden = goldenPath(name);
        ASSERT_TRUE(ImageWriter::writeRgba8(golden, width, height, pixels));
        GTEST_SKIP() << "golden image updated: " << golden;
    }
    expectMatchesGolden(name, width, height, pixels, rmseLimit, maxLimit);
}

}  // namespace sylva::golden
