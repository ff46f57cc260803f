#include "sylva/core/analysis/ZtvWriter.h"

#include <cmath>
#include <vector>

#include "sylva/core/analysis/GridGeoTiff.h"

namespace sylva {

Status writeZtvGeoTiff(const std::filesystem::path& path, const ViewshedResult& result,
                       const std::string& crsWkt) {
    std::vector<float> visible(result.cells()), count(result.cells());
    for (std::size_t i = 0; i < result.cells(); ++i) {
        const bool noData = std::isnan(result.fraction[i]);
        visible[i] = noData ? result.fraction[i] : float(result.visible[i]);
        count[i] = noData ? result.fraction[i] : float(result.count[i]);
    }
    const GridBand bands[] = {
        {"visible", &visible}, {"count", &count}, {"fraction", &result.fraction}};
    return writeGridGeoTiff(path, result.geometry, bands, crsWkt);
}

}  // namespace sylva
