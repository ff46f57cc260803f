// The language reference generated from the schema registry: `sylva doc [KIND]` prints
// it as text, `sylva doc --markdown` as the generated part of docs/dsl.md (a test fails
// when the committed file differs from what the registry says).
#pragma once

#include <string>

#include "sylva/core/model/Schema.h"

namespace sylva::dsl {

class SchemaReference {
public:
    // Markers around the generated part of docs/dsl.md.
    static constexpr const char* kBeginMarker =
        "<!-- BEGIN GENERATED REFERENCE (sylva doc --markdown) -->";
    static constexpr const char* kEndMarker = "<!-- END GENERATED REFERENCE -->";

    // Every block keyword and source kind, in registration order, as Markdown.
    static std::string markdown(const SchemaRegistry& registry);
    // One block keyword or source kind ("camera", "noise") as plain text; empty if unknown.
    static std::string text(const SchemaRegistry& registry, const std::string& kind);
    // The names `text` accepts, for usage messages and did-you-mean.
    static std::vector<std::string> names(const SchemaRegistry& registry);
    // `document` with the part between the markers replaced by markdown(registry);
    // nullopt-like empty string if the markers are missing.
    static std::string replaceGenerated(const std::string& document,
                                        const SchemaRegistry& registry);
};

}  // namespace sylva::dsl
