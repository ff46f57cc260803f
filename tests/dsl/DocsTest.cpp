// docs/dsl.md carries the reference generated from the schema registry; this fails when
// the registry changed and the file was not regenerated (`sylva doc --update docs/dsl.md`).
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "sylva/dsl/SchemaReference.h"

namespace sylva::dsl {
namespace {

TEST(Docs, DslReferenceIsUpToDate) {
    std::ifstream in(std::string(SYLVA_SOURCE_DIR) + "/docs/dsl.md", std::ios::binary);
    ASSERT_TRUE(in.good()) << "docs/dsl.md is missing";
    std::string document((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string regenerated =
        SchemaReference::replaceGenerated(document, SchemaRegistry::builtin());
    ASSERT_FALSE(regenerated.empty()) << "docs/dsl.md lost its generated-reference markers";
    EXPECT_TRUE(regenerated == document)
        << "docs/dsl.md is stale: run `sylva doc --update docs/dsl.md`";
}

TEST(Docs, EveryKindHasADocString) {
    for (const KindSchema& kind : SchemaRegistry::builtin().all()) {
        EXPECT_FALSE(kind.doc.empty()) << kind.keyword << " " << kind.kind;
        for (const AttributeSchema& attribute : kind.attributes) {
            EXPECT_FALSE(attribute.doc.empty())
                << kind.keyword << " " << kind.kind << "." << attribute.name;
        }
    }
}

}  // namespace
}  // namespace sylva::dsl
