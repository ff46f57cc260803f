// libFuzzer target: the .plod reader (decodePlod: header, section table, records).
// A decoded file must encode again without failing.
#include <span>

#include "FuzzInput.h"
#include "sylva/core/plantlod/PlodFile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace sylva;
    PlodFileInfo info;
    Result<PlantLod> lod =
        decodePlod(std::span<const std::uint8_t>(data, size), "fuzz.plod", &info);
    fuzz::requireMessage(lod);
    if (lod) {
        (void)encodePlod(lod.value());
    }
    return 0;
}
