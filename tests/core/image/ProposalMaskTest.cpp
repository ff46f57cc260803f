// The masks and lines of a photomontage (core/image ProposalMask, Photomontage) on depth
// buffers whose geometry is known by construction: a ground plane, a proposal box in
// front of it, an existing occluder in front of part of the box, and a sky band. Each
// expected pixel set is written out independently of the code under test.
#include <gtest/gtest.h>

#include "sylva/core/image/Photomontage.h"
#include "sylva/core/image/ProposalMask.h"

namespace sylva {
namespace {

constexpr int kWidth = 40, kHeight = 30;
constexpr float kNear = 0.5f;

float depthAt(double distance) {
    return static_cast<float>(kNear / distance);  // reversed-Z: near / distance
}

// Sky above row 8, ground at 1000 m below; the occluder (existing, in both) covers
// columns 10..14 of rows 15..29 at 300 m.
std::vector<float> baseline() {
    std::vector<float> depth(kWidth * kHeight, 0.0f);
    for (int y = 8; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            depth[y * kWidth + x] = depthAt(1000.0);
            if (x >= 10 && x <= 14 && y >= 15) {
                depth[y * kWidth + x] = depthAt(300.0);
            }
        }
    }
    return depth;
}

// The proposal: a box at 500 m covering columns 8..29, rows 4..20 (it rises into the sky).
bool inBox(int x, int y) {
    return x >= 8 && x <= 29 && y >= 4 && y <= 20;
}

std::vector<float> proposed() {
    std::vector<float> depth = baseline();
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (inBox(x, y) && depth[y * kWidth + x] < depthAt(500.0)) {
                depth[y * kWidth + x] = depthAt(500.0);
            }
        }
    }
    return depth;
}

bool occluded(int x, int y) {
    return x >= 10 && x <= 14 && y >= 15;
}

TEST(ProposalMask, IsTheProposalMinusWhatTheBaselineHides) {
    const PixelMask mask = ProposalMask::fromDepths(baseline(), proposed(), kWidth, kHeight);
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            EXPECT_EQ(mask[y * kWidth + x] != 0, inBox(x, y) && !occluded(x, y))
                << "pixel " << x << ", " << y;
        }
    }
}

TEST(ProposalMask, IgnoresDepthsWithinTheTolerance) {
    std::vector<float> same = baseline();
    std::vector<float> jittered = same;
    for (float& d : jittered) {
        d *= 1.0005f;  // 0.05 % nearer: float noise, not a proposal
    }
    EXPECT_EQ(ProposalMask::count(ProposalMask::fromDepths(same, jittered, kWidth, kHeight)), 0u);
}

TEST(ProposalMask, OutlineIsTheMasksBoundary) {
    const PixelMask mask = ProposalMask::fromDepths(baseline(), proposed(), kWidth, kHeight);
    const PixelMask lines = ProposalMask::outline(mask, kWidth, kHeight);
    auto visible = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < kWidth && y < kHeight && inBox(x, y) && !occluded(x, y);
    };
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const bool edge = visible(x, y) && (!visible(x - 1, y) || !visible(x + 1, y) ||
                                                !visible(x, y - 1) || !visible(x, y + 1));
            EXPECT_EQ(lines[y * kWidth + x] != 0, edge) << "pixel " << x << ", " << y;
        }
    }
}

TEST(ProposalMask, SkylineIsTheFirstGroundRowUnderTheSky) {
    const PixelMask skyline = ProposalMask::skyline(baseline(), kWidth, kHeight);
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            EXPECT_EQ(skyline[y * kWidth + x] != 0, y == 8) << "pixel " << x << ", " << y;
        }
    }
    // The proposal rising into the sky moves the skyline of the proposed render up.
    const PixelMask raised = ProposalMask::skyline(proposed(), kWidth, kHeight);
    EXPECT_NE(raised[4 * kWidth + 20], 0);
    EXPECT_EQ(raised[8 * kWidth + 20], 0);
}

TEST(Photomontage, CompositeTakesTheRenderOnlyInsideTheMask) {
    const RgbaImage photo(4, 2, 10, 20, 30);
    const RgbaImage render(4, 2, 200, 100, 50);
    const PixelMask mask = {0, 1, 0, 0, 0, 0, 1, 1};
    const RgbaImage out = Photomontage::composite(photo, render, mask);
    for (int i = 0; i < 8; ++i) {
        const std::uint8_t expected = mask[i] ? 200 : 10;
        EXPECT_EQ(out.pixels[i * 4], expected) << i;
    }
}

TEST(Photomontage, LinesHaveTheirWidth) {
    RgbaImage image(21, 21, 0, 0, 0);
    PixelMask lines(21 * 21, 0);
    lines[10 * 21 + 10] = 1;
    Photomontage::drawLines(image, lines, {255, 0, 0, 255}, 5.0);
    int painted = 0;
    for (int y = 0; y < 21; ++y) {
        for (int x = 0; x < 21; ++x) {
            painted += image.at(x, y)[0] == 255 ? 1 : 0;
        }
    }
    EXPECT_EQ(image.at(10, 10)[0], 255);
    EXPECT_EQ(image.at(12, 10)[0], 255);  // radius 2.5
    EXPECT_EQ(image.at(13, 10)[0], 0);
    EXPECT_EQ(painted, 21);  // the lattice points within 2.75 of the centre
}

}  // namespace
}  // namespace sylva
