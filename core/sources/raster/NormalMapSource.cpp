#include "sylva/core/sources/raster/NormalMapSource.h"

#include <algorithm>
#include <cmath>

#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {

NormalMapSource::NormalMapSource(std::string name, const Source* height, double exaggeration)
    : Source(std::move(name), "normal_map", PortType::Normals, 3),
      height_(height),
      exaggeration_(exaggeration) {
    SYLVA_CHECK(height != nullptr && height->output() == PortType::Elevation);
    addInput(height);
    setParameterHash(ContentHash().add(exaggeration).value());
}

glm::dvec3 NormalMapSource::normalAt(const ImageTile& height, int ix, int iy, double exaggeration) {
    const int low = -height.border();
    const int high = height.size() + height.border() - 1;
    const int x0 = std::max(ix - 1, low), x1 = std::min(ix + 1, high);
    const int y0 = std::max(iy - 1, low), y1 = std::min(iy + 1, high);
    const double latitude = height.texelLatitude(iy);
    const double longitude = height.texelLongitude(ix);
    const double eastMetres = Ellipsoid::primeVerticalRadius(latitude) *
                              std::max(std::cos(latitude), 1e-9) * height.texelWidth() * (x1 - x0);
    const double northMetres =
        Ellipsoid::meridionalRadius(latitude) * height.texelHeight() * (y1 - y0);
    // Rows grow southwards, so north is y0 - y1.
    const double slopeEast = (height.at(x1, iy, 0) - height.at(x0, iy, 0)) / eastMetres;
    const double slopeNorth = (height.at(ix, y0, 0) - height.at(ix, y1, 0)) / northMetres;
    const glm::dvec3 local =
        glm::normalize(glm::dvec3(-slopeEast * exaggeration, -slopeNorth * exaggeration, 1.0));
    const glm::dmat3 frame = Ellipsoid::localFrame(latitude, longitude);
    return glm::normalize(frame * local);
}

Result<TilePointer> NormalMapSource::produce(const TileKey& key, TileProvider& provider) const {
    Result<TilePointer> height = provider.tile(*height_, key);
    if (!height) {
        return height.error();
    }
    const ImageTile& h = *height.value();
    const TileFormat& format = provider.format();
    auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 3);
    for (int iy = -format.border; iy < format.size + format.border; ++iy) {
        for (int ix = -format.border; ix < format.size + format.border; ++ix) {
            const glm::dvec3 n = normalAt(h, ix, iy, exaggeration_);
            tile->at(ix, iy, 0) = static_cast<float>(n.x);
            tile->at(ix, iy, 1) = static_cast<float>(n.y);
            tile->at(ix, iy, 2) = static_cast<float>(n.z);
        }
    }
    return TilePointer(std::move(tile));
}

Result<std::unique_ptr<Source>> NormalMapSource::create(const SourceBuildContext& context) {
    const Block& block = context.block;
    const BlockReader& reader = context.reader;
    Result<const Source*> height = context.input("height", true);
    if (!height) {
        return height.error();
    }
    Result<double> exaggeration = reader.number("exaggeration");
    if (!exaggeration) {
        return exaggeration.error();
    }
    return std::unique_ptr<Source>(
        std::make_unique<NormalMapSource>(block.name, height.value(), exaggeration.value()));
}

}  // namespace sylva
