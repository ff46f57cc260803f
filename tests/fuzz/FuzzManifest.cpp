// libFuzzer target: the render manifest reader (RenderManifest::load), and a loaded
// manifest saved and loaded again gives the same entries.
#include "FuzzInput.h"
#include "sylva/core/scene/RenderManifest.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace sylva;
    const auto path = fuzz::writeInput("manifest.json", fuzz::asText(data, size));
    RenderManifest manifest(path);
    const Status loaded = manifest.load();
    fuzz::requireMessage(loaded);
    if (loaded && manifest.save()) {
        RenderManifest again(path);
        if (!again.load() || again.entries().size() != manifest.entries().size()) {
            std::abort();
        }
    }
    return 0;
}
