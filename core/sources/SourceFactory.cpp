#include "sylva/core/sources/SourceFactory.h"

#include "sylva/core/sources/HypsometricSource.h"
#include "sylva/core/sources/NoiseSource.h"
#include "sylva/core/sources/NormalMapSource.h"

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
    };
    for (const Entry& entry : kTable) {
        if (entry.kind == kind) {
            return entry.create;
        }
    }
    return nullptr;
}

}  // namespace sylva
