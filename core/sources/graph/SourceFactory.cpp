#include "sylva/core/sources/graph/SourceFactory.h"

#include "sylva/core/sources/compose/BlendSource.h"
#include "sylva/core/sources/compose/RasterizeSource.h"
#include "sylva/core/sources/objects/BuildingsSource.h"
#include "sylva/core/sources/objects/ObjectsSource.h"
#include "sylva/core/sources/plants/PlantModelSource.h"
#include "sylva/core/sources/plants/PlantsSource.h"
#include "sylva/core/sources/raster/AdjustSource.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/HypsometricSource.h"
#include "sylva/core/sources/raster/MaskSource.h"
#include "sylva/core/sources/raster/NoiseSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/core/sources/raster/RasterSource.h"
#include "sylva/core/sources/vector/ElevationEditSource.h"
#include "sylva/core/sources/vector/FeatureSource.h"

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
        {"buildings", &BuildingsSource::create},
        {"objects", &ObjectsSource::create},
    };
    for (const Entry& entry : kTable) {
        if (entry.kind == kind) {
            return entry.create;
        }
    }
    return nullptr;
}

}  // namespace sylva
