#include "PlantSeasonChecker.h"

#include "sylva/core/seasons/PlantSeasons.h"

namespace sylva::dsl {

void checkPlantSeasons(const Block& block, std::vector<Diagnostic>& diagnostics) {
    if (block.keyword != "source" || block.kind != "plants") {
        return;
    }
    SourceLocation problem = block.location;
    Result<PlantSeasons> seasons =
        PlantSeasons::read(block, PlantSeasons::speciesOf(block), &problem);
    if (!seasons) {
        addError(diagnostics, "E0415", seasons.error().message, problem,
                 "in plants source '" + block.name + "'");
    }
}

}  // namespace sylva::dsl
