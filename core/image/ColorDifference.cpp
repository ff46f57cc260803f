#include "sylva/core/image/ColorDifference.h"

#include <cmath>
#include <numbers>

#include "sylva/core/image/ColorSpace.h"

namespace sylva {
namespace {

double labCurve(double t) {
    constexpr double kEpsilon = 216.0 / 24389.0;
    constexpr double kKappa = 24389.0 / 27.0;
    return t > kEpsilon ? std::cbrt(t) : (kKappa * t + 16.0) / 116.0;
}

double degrees(double radians) {
    return radians * 180.0 / std::numbers::pi;
}
double radians(double degreesValue) {
    return degreesValue * std::numbers::pi / 180.0;
}

}  // namespace

Lab ColorDifference::labFromSrgb8(std::uint8_t red, std::uint8_t green, std::uint8_t blue) {
    const double r = srgbToLinear(red / 255.0f);
    const double g = srgbToLinear(green / 255.0f);
    const double b = srgbToLinear(blue / 255.0f);
    // IEC 61966-2-1 primaries, D65 white.
    const double x = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
    const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    const double z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
    const double fx = labCurve(x / 0.95047);
    const double fy = labCurve(y / 1.0);
    const double fz = labCurve(z / 1.08883);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double ColorDifference::deltaE2000(const Lab& first, const Lab& second) {
    const double c1 = std::hypot(first.a, first.b);
    const double c2 = std::hypot(second.a, second.b);
    const double meanC = 0.5 * (c1 + c2);
    const double meanC7 = std::pow(meanC, 7.0);
    const double g = 0.5 * (1.0 - std::sqrt(meanC7 / (meanC7 + std::pow(25.0, 7.0))));
    const double a1 = (1.0 + g) * first.a;
    const double a2 = (1.0 + g) * second.a;
    const double c1p = std::hypot(a1, first.b);
    const double c2p = std::hypot(a2, second.b);
    auto hue = [](double b, double a) {
        if (a == 0.0 && b == 0.0) {
            return 0.0;
        }
        double h = degrees(std::atan2(b, a));
        return h < 0 ? h + 360.0 : h;
    };
    const double h1p = hue(first.b, a1);
    const double h2p = hue(second.b, a2);

    const double deltaL = second.lightness - first.lightness;
    const double deltaC = c2p - c1p;
    double deltaHue = 0.0;
    if (c1p * c2p != 0.0) {
        deltaHue = h2p - h1p;
        if (deltaHue > 180.0) {
            deltaHue -= 360.0;
        } else if (deltaHue < -180.0) {
            deltaHue += 360.0;
        }
    }
    const double deltaH = 2.0 * std::sqrt(c1p * c2p) * std::sin(radians(deltaHue / 2.0));

    const double meanL = 0.5 * (first.lightness + second.lightness);
    const double meanCp = 0.5 * (c1p + c2p);
    double meanH = h1p + h2p;
    if (c1p * c2p != 0.0) {
        if (std::abs(h1p - h2p) > 180.0) {
            meanH += meanH < 360.0 ? 360.0 : -360.0;
        }
        meanH *= 0.5;
    }
    const double t =
        1.0 - 0.17 * std::cos(radians(meanH - 30.0)) + 0.24 * std::cos(radians(2.0 * meanH)) +
        0.32 * std::cos(radians(3.0 * meanH + 6.0)) - 0.20 * std::cos(radians(4.0 * meanH - 63.0));
    const double deltaTheta = 30.0 * std::exp(-std::pow((meanH - 275.0) / 25.0, 2.0));
    const double meanCp7 = std::pow(meanCp, 7.0);
    const double rc = 2.0 * std::sqrt(meanCp7 / (meanCp7 + std::pow(25.0, 7.0)));
    const double sl =
        1.0 + 0.015 * std::pow(meanL - 50.0, 2.0) / std::sqrt(20.0 + std::pow(meanL - 50.0, 2.0));
    const double sc = 1.0 + 0.045 * meanCp;
    const double sh = 1.0 + 0.015 * meanCp * t;
    const double rt = -std::sin(radians(2.0 * deltaTheta)) * rc;
    const double l = deltaL / sl;
    const double c = deltaC / sc;
    const double h = deltaH / sh;
    return std::sqrt(l * l + c * c + h * h + rt * c * h);
}

}  // namespace sylva
