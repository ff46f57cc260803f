#include "sylva/core/base/Check.h"

#include <cstdio>
#include <cstdlib>

namespace sylva::detail {

void checkFailed(const char* expression, const char* file, int line, const char* message) {
    std::fprintf(stderr, "sylva: internal check failed: %s at %s:%d%s%s\n", expression, file, line,
                 message ? ": " : "", message ? message : "");
    std::fflush(stderr);
    std::abort();
}

}  // namespace sylva::detail
