#include "sylva/bench/MarkerFixture.h"

#include <algorithm>
#include <cmath>

#include "sylva/core/base/Hash.h"
#include "sylva/core/image/ColorSpace.h"
#include "sylva/core/scene/ImageProjection.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/core/tiles/ImageTile.h"

namespace sylva::bench {
namespace {

constexpr float kGround = 0.04f;  // linear albedo of the ground
// Added at a marker's centre: low enough that the tone map does not clip the peak (a
// flat-topped blob's centroid would rest on its texel-stepped edges alone).
constexpr float kMarker = 0.12f;

// The markers as a colour source: ground grey plus kMarker·exp(−(θ/θR)²) near each marker
// (θ: angle between the texel's ground point and the marker seen from its viewpoint).
class MarkerColour final : public Source {
public:
    explicit MarkerColour(std::shared_ptr<const std::vector<Marker>> markers)
        : Source("markers", "test", PortType::Image, 4), markers_(std::move(markers)) {
        ContentHash hash;
        hash.add(std::string_view("markers-v1"));
        for (const Marker& marker : *markers_) {
            hash.add(marker.ground.latitude).add(marker.ground.longitude);
            hash.add(marker.viewpoint.x).add(marker.viewpoint.y).add(marker.viewpoint.z);
            hash.add(marker.angularRadius);
        }
        setParameterHash(hash.value());
    }

    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 4);
        for (int iy = -format.border; iy < format.size + format.border; ++iy) {
            const double latitude = tile->texelLatitude(iy);
            for (int ix = -format.border; ix < format.size + format.border; ++ix) {
                const double longitude = tile->texelLongitude(ix);
                const glm::dvec3 point =
                    Ellipsoid::toEcef({latitude, longitude, MarkerFixture::kGroundHeight});
                float value = kGround;
                for (const Marker& marker : *markers_) {
                    const glm::dvec3 toPoint = glm::normalize(point - marker.viewpoint);
                    const glm::dvec3 toMarker = glm::normalize(marker.ecef - marker.viewpoint);
                    const double d =
                        2.0 * std::asin(std::min(1.0, glm::length(toPoint - toMarker) / 2.0)) /
                        marker.angularRadius;
                    if (d < 3.0) {
                        value += kMarker * float(std::exp(-d * d));
                    }
                }
                for (int c = 0; c < 3; ++c) {
                    tile->at(ix, iy, c) = value;
                }
                tile->at(ix, iy, 3) = 1.0f;
            }
        }
        return TilePointer(tile);
    }

private:
    std::shared_ptr<const std::vector<Marker>> markers_;
};

}  // namespace

MarkerFixture::MarkerFixture()
    : markers_(std::make_shared<std::vector<Marker>>()),
      elevation_(std::make_unique<ConstantSource>("ground", kGroundHeight)) {
    normals_ = std::make_unique<NormalMapSource>("ground.normals", elevation_.get(), 1.0);
}

MarkerFixture::~MarkerFixture() = default;

std::optional<Marker> MarkerFixture::addAt(const Camera& camera, int width, int height,
                                           const glm::dvec2& pixel, double angularRadius) {
    const ImageProjection image(camera, width, height);
    const glm::dvec3 direction = image.ecefDirection(pixel);
    const auto above = [&](double t) {
        return Ellipsoid::toGeodetic(camera.position + direction * t).height - kGroundHeight;
    };
    if (above(0.0) <= 0.0 || above(50e3) > 0.0) {
        return std::nullopt;
    }
    double low = 0.0, high = 50e3;
    for (int i = 0; i < 200 && high - low > 1e-7; ++i) {
        const double middle = 0.5 * (low + high);
        (above(middle) > 0.0 ? low : high) = middle;
    }
    const double distance = 0.5 * (low + high);
    Marker marker;
    marker.ground = Ellipsoid::toGeodetic(camera.position + direction * distance);
    marker.ground.height = kGroundHeight;
    marker.ecef = Ellipsoid::toEcef(marker.ground);
    marker.viewpoint = camera.position;
    marker.angularRadius = angularRadius;
    markers_->push_back(marker);
    colour_.reset();
    return marker;
}

TerrainLayers MarkerFixture::layers() const {
    auto& colour = const_cast<std::unique_ptr<Source>&>(colour_);
    if (!colour) {
        colour = std::make_unique<MarkerColour>(markers_);
    }
    return TerrainLayers{elevation_.get(), colour.get(), normals_.get(), {}, {}};
}

std::optional<glm::dvec2> MarkerFixture::centroid(const RgbaImage& image,
                                                  const glm::dvec2& predicted, double window) {
    const int x0 = std::max(0, int(std::floor(predicted.x - window)));
    const int x1 = std::min(image.width - 1, int(std::floor(predicted.x + window)));
    const int y0 = std::max(0, int(std::floor(predicted.y - window)));
    const int y1 = std::min(image.height - 1, int(std::floor(predicted.y + window)));
    if (x0 > x1 || y0 > y1) {
        return std::nullopt;
    }
    // Background: the darkest luminance in the window (the uniform ground).
    const auto luminance = [&](int x, int y) {
        const std::uint8_t* p = image.at(x, y);
        return 0.2126 * srgbToLinear(p[0] / 255.0f) + 0.7152 * srgbToLinear(p[1] / 255.0f) +
               0.0722 * srgbToLinear(p[2] / 255.0f);
    };
    double background = 1e9, peak = 0.0;
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            background = std::min(background, luminance(x, y));
            peak = std::max(peak, luminance(x, y));
        }
    }
    // Weights above a tenth of the blob's height ignore the ground's shading noise.
    const double threshold = background + 0.1 * (peak - background);
    glm::dvec2 sum(0.0);
    double weight = 0.0;
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            const double w = luminance(x, y) - threshold;
            if (w > 0.0) {
                sum += w * glm::dvec2(x + 0.5, y + 0.5);
                weight += w;
            }
        }
    }
    if (!(weight > 0.0) || peak - background < 0.02) {
        return std::nullopt;
    }
    return sum / weight;
}

}  // namespace sylva::bench
