#include "sylva/dsl/Ast.h"

namespace sylva::dsl {

SourceLocation spanLocations(const SourceLocation& first, const SourceLocation& last) {
    SourceLocation result = first;
    if (first.file == last.file && first.line == last.line && last.column >= first.column) {
        result.length = last.column + last.length - first.column;
    }
    return result;
}

}  // namespace sylva::dsl
