// libFuzzer target: the plant model sidecar JSON (PlantSidecar::readFor), which names
// the leaf and branch meshes of an imported model.
#include "FuzzInput.h"
#include "sylva/core/plantlod/PlantSidecar.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace sylva;
    const std::filesystem::path model = fuzz::scratchFolder() / "plant.gltf";
    fuzz::writeInput(PlantSidecar::pathFor(model).filename().string(), fuzz::asText(data, size));
    Result<PlantSidecar> sidecar = PlantSidecar::readFor(model);
    fuzz::requireMessage(sidecar);
    if (sidecar) {
        (void)sidecar->partOf("leaves");
        (void)sidecar->partOf("");
    }
    return 0;
}
