#include "sylva/core/sources/SourceFactory.h"

#include "sylva/core/sources/AdjustSource.h"
#include "sylva/core/sources/BlendSource.h"
#include "sylva/core/sources/ConstantSource.h"
#include "sylva/core/sources/ElevationEditSource.h"
#include "sylva/core/sources/FeatureSource.h"
#include "sylva/core/sources/HypsometricSource.h"
#include "sylva/core/sources/MaskSource.h"
#include "sylva/core/sources/NoiseSource.h"
#include "sylva/core/sources/NormalMapSource.h"
#include "sylva/core/sources/PlantModelSource.h"
#include "sylva/core/sources/PlantsSource.h"
#include "sylva/core/sources/RasterSource.h"
#include "sylva/core/sources/RasterizeSource.h"

namespace sylva {

SourceCreator findSourceCreator(std::string_view kind) {
    struct Entry {
        std::string_view kind;
        SourceCreator create;
    };
    static constexpr Entry kTable[] = {
        {"noise", &NoiseSource::create},
        {"normal_map", &NormalMapSource::create},
        {"hypsometric", &HypsometricSource::create},
        {"raster", &RasterSource::create},
        {"constant", &ConstantSource::create},
        {"adjust", &AdjustSource::create},
        {"blend", &BlendSource::create},
        {"mask", &MaskSource::create},
        {"features", &FeatureSource::create},
        {"rasterize", &RasterizeSource::create},
        {"elevation_edit", &ElevationEditSource::create},
        {"plants", &PlantsSource::create},
        {"plant_model", &PlantModelSource::create},
    };
    for (const Entry& entry : kTable) {
        if (entry.kind == kind) {
            return entry.create;
        }
    }
    return nullptr;
}

}  // namespace sylva
