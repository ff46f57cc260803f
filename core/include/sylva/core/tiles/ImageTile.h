// ImageTile: the raster content of one TileKey for one source. Immutable once
// produced (shared as std::shared_ptr<const ImageTile>).
//
// A tile holds size x size interior texels plus a border of `border` texels on every
// side, so filters such as normal maps need no neighbour fetch. Texel (ix, iy) with
// ix, iy in [0, size) is centred at
//   longitude = west  + (ix + 0.5) * (east - west) / size
//   latitude  = north - (iy + 0.5) * (north - south) / size
// and border texels continue that grid (negative indices or >= size). Values are
// floats in the unit of the source's port type (metres for elevation, linear RGB
// for images, ECEF unit vectors for normals).
#pragma once

#include <cstddef>
#include <vector>

#include "sylva/core/base/Check.h"
#include "sylva/core/tiles/TileKey.h"

namespace sylva {

class ImageTile {
public:
    ImageTile(TileKey key, int size, int border, int channels);

    const TileKey& key() const { return key_; }
    int size() const { return size_; }
    int border() const { return border_; }
    int channels() const { return channels_; }
    int stride() const { return size_ + 2 * border_; }  // texels per stored row
    std::size_t bytes() const { return texels_.size() * sizeof(float); }

    // Pointer to texel (-border, iy); iy in [-border, size + border).
    float* row(int iy) {
        SYLVA_CHECK(iy >= -border_ && iy < size_ + border_);
        return texels_.data() + static_cast<std::size_t>(iy + border_) * stride() * channels_;
    }
    const float* row(int iy) const { return const_cast<ImageTile*>(this)->row(iy); }
    float& at(int ix, int iy, int channel) {
        SYLVA_CHECK(ix >= -border_ && ix < size_ + border_ && channel >= 0 && channel < channels_);
        return row(iy)[static_cast<std::size_t>(ix + border_) * channels_ + channel];
    }
    float at(int ix, int iy, int channel) const {
        return const_cast<ImageTile*>(this)->at(ix, iy, channel);
    }

    // Geographic position of texel centres, radians (see above).
    double texelLongitude(double ix) const;
    double texelLatitude(double iy) const;
    double texelWidth() const;   // radians of longitude per texel
    double texelHeight() const;  // radians of latitude per texel

    std::vector<float>& texels() { return texels_; }
    const std::vector<float>& texels() const { return texels_; }

private:
    TileKey key_;
    int size_;
    int border_;
    int channels_;
    std::vector<float> texels_;
};

}  // namespace sylva
