// Always-on checks for programmer errors (broken invariants, misuse of an API).
// User and data errors never go through here: they travel as Result<T> or diagnostics.
#pragma once

namespace sylva::detail {
[[noreturn]] void checkFailed(const char* expression, const char* file, int line,
                              const char* message);
}  // namespace sylva::detail

// Aborts with the failed expression and its location. Active in every build type.
#define SYLVA_CHECK(expression)                                                     \
    do {                                                                            \
        if (!(expression)) {                                                        \
            ::sylva::detail::checkFailed(#expression, __FILE__, __LINE__, nullptr); \
        }                                                                           \
    } while (false)

#define SYLVA_CHECK_MESSAGE(expression, message)                                    \
    do {                                                                            \
        if (!(expression)) {                                                        \
            ::sylva::detail::checkFailed(#expression, __FILE__, __LINE__, message); \
        }                                                                           \
    } while (false)
