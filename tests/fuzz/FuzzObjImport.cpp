// libFuzzer target: PlantImporter on Wavefront OBJ with its MTL. The input is the OBJ,
// then (after a line "%%MTL%%") the material library plant.mtl, which the OBJ may name
// with `mtllib plant.mtl`; textures it names do not exist (a located error).
#include "FuzzInput.h"
#include "sylva/core/plantlod/PlantImporter.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace sylva;
    const std::string_view bytes = fuzz::asText(data, size);
    constexpr std::string_view kSeparator = "\n%%MTL%%\n";
    const std::size_t split = bytes.find(kSeparator);
    fuzz::writeInput("plant.mtl", split == std::string_view::npos
                                      ? std::string_view()
                                      : bytes.substr(split + kSeparator.size()));
    const auto path = fuzz::writeInput("plant.obj", bytes.substr(0, split));
    PlantImportOptions lenient;
    lenient.requireLeavesAndBranches = false;
    fuzz::requireMessage(PlantImporter::import(path, lenient));
    return 0;
}
