// BlendSource (`source x : blend`): lays `over` on `base`, per texel.
//
// Weight w = opacity x mask x coverage(over) x fade, where coverage(over) is the
// image's alpha, or for elevation the coverage mask of a raster (coverageOf()), and
// fade (feather > 0) = smoothstep(0.5, 1, C) with C the over-coverage at the coarser
// pyramid level whose texels are about twice `feather`, bilinearly interpolated at
// the texel centre. C is 0.5 on the coverage edge and reaches 1 about half a coarse
// texel inside, so the fade starts at the edge and is complete about `feather` metres
// inside it (an over-source narrower than a few coarse texels never reaches full
// weight: keep feather well below its size); being taken from one fixed level it is the same at
// every requested level and continuous across tiles (the coarse tile's border covers the bilinear
// footprint). This is a blurred-coverage feather in the spirit of alpha feathering in
// image compositing (Porter & Duff 1984 for the operators).
//
// Images (linear RGB, straight alpha): mixed(base, f(base, over), w) with f =
// over (normal), base*over (multiply), 1-(1-base)(1-over) (screen), base+over (add),
// min, max; alpha = w + base.a (1 - w). Elevation: replace/normal mix(base, over, w),
// add base + w over, min/max mix(base, min/max(base, over), w).
// Lazy: an input is read only where it has weight — `over` not at all when every texel's
// weight is 0, `base` not at all when every texel's weight is 1 in normal/replace mode (a
// DEM over a procedural relief then never synthesises the relief inside the DEM).
// Fails when an input it reads fails (the input's error).
#pragma once

#include <optional>
#include <vector>

#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"

namespace sylva {

enum class BlendMode { Normal, Multiply, Screen, Add, Min, Max };

struct BlendParameters {
    BlendMode mode = BlendMode::Normal;
    double opacity = 1.0;
    double feather = 0.0;  // metres
};

class BlendSource final : public Source {
public:
    // `base` and `over` of the same port type (elevation or image); `mask` optional.
    BlendSource(std::string name, const Source* base, const Source* over, const Source* mask,
                const BlendParameters& parameters);

    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

    // The Mask source giving the coverage of an elevation source, or nullptr when it
    // covers everything: a raster's coverage(); a blend passes on its base's, an
    // elevation_edit its input's.
    static const Source* coverageOf(const Source& elevation);

    // Pyramid level whose texel height is about twice `feather` metres (at most `level`).
    static int featherLevel(double featherMetres, int tileSize, int level);

private:
    struct Inputs;
    // Per texel (border included, row-major) weight in [0, 1], snapped to 1 within 1e-9,
    // with the lowest and highest. Without a mask and a coverage the opacity alone decides:
    // `texels` is then empty (no (size + 2 border)^2 vector per tile) and every texel has
    // the weight `lowest` (= `highest`).
    struct TexelWeights {
        std::vector<double> texels;
        double lowest = 0, highest = 0;
        double at(std::size_t texel) const { return texels.empty() ? lowest : texels[texel]; }
    };
    // Reads the mask, the over-source's coverage and the feather's coarse coverage.
    std::optional<Error> fetchWeightInputs(const TileKey& key, TileProvider& provider,
                                           Inputs& in) const;
    // The weights of the key's texels, from the opacity and the inputs fetchWeightInputs read.
    TexelWeights texelWeights(const Inputs& in, const TileKey& key, const TileFormat& format) const;
    // Blends `over` into `tile` (a copy of the base) by the weights.
    void blendTexels(const ImageTile& over, const TexelWeights& weights, ImageTile& tile) const;

    const Source* base_;
    const Source* over_;
    const Source* mask_;
    const Source* overCoverage_;  // elevation: coverageOf(over); image: over itself (alpha)
    BlendParameters parameters_;
};

}  // namespace sylva
