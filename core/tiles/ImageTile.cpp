#include "sylva/core/tiles/ImageTile.h"

namespace sylva {

ImageTile::ImageTile(TileKey key, int size, int border, int channels)
    : key_(key), size_(size), border_(border), channels_(channels) {
    SYLVA_CHECK(size > 0 && border >= 0 && channels > 0 && channels <= 4);
    texels_.assign(static_cast<std::size_t>(stride()) * stride() * channels, 0.0f);
}

double ImageTile::texelWidth() const {
    return (key_.east() - key_.west()) / size_;
}
double ImageTile::texelHeight() const {
    return (key_.north() - key_.south()) / size_;
}
double ImageTile::texelLongitude(double ix) const {
    return key_.west() + (ix + 0.5) * texelWidth();
}
double ImageTile::texelLatitude(double iy) const {
    return key_.north() - (iy + 0.5) * texelHeight();
}

}  // namespace sylva
