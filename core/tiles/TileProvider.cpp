#include "sylva/core/tiles/TileProvider.h"

namespace sylva {

TileLookup TileProvider::tryGet(const Source& source, const TileKey& key, int priority) {
    (void)priority;
    Result<TilePointer> produced = tile(source, key);
    if (!produced) {
        return {TileLookup::State::Failed, nullptr, produced.error()};
    }
    return {TileLookup::State::Ready, produced.value(), {}};
}

}  // namespace sylva
