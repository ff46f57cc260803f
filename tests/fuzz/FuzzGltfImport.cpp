// libFuzzer target: PlantImporter on glTF (JSON) and GLB (binary) plant models. Inputs
// starting with "glTF" are written as .glb, the rest as .gltf.
#include "FuzzInput.h"
#include "sylva/core/plantlod/PlantImporter.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace sylva;
    const std::string_view bytes = fuzz::asText(data, size);
    const bool binary = bytes.substr(0, 4) == "glTF";
    const auto path = fuzz::writeInput(binary ? "plant.glb" : "plant.gltf", bytes);
    fuzz::requireMessage(PlantImporter::import(path));
    PlantImportOptions lenient;
    lenient.useFileSkeleton = false;
    lenient.requireLeavesAndBranches = false;
    fuzz::requireMessage(PlantImporter::import(path, lenient));
    return 0;
}
