// Result<T>: the channel for user and data errors (a missing file, a bad value).
// Holds either a value or an Error with a human-readable message that already names
// what failed (path, source name, reason). Accessing the wrong alternative is a
// programmer error and aborts through SYLVA_CHECK.
#pragma once

#include <string>
#include <utility>
#include <variant>

#include "sylva/core/base/Check.h"

namespace sylva {

struct Error {
    std::string message;
};

template <typename T>
class [[nodiscard]] Result {
public:
    Result(T value) : storage_(std::move(value)) {}
    Result(Error error) : storage_(std::move(error)) {}

    bool ok() const { return storage_.index() == 0; }
    explicit operator bool() const { return ok(); }

    T& value() & {
        SYLVA_CHECK(ok());
        return std::get<0>(storage_);
    }
    const T& value() const& {
        SYLVA_CHECK(ok());
        return std::get<0>(storage_);
    }
    T&& value() && {
        SYLVA_CHECK(ok());
        return std::get<0>(std::move(storage_));
    }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }

    const Error& error() const {
        SYLVA_CHECK(!ok());
        return std::get<1>(storage_);
    }

private:
    std::variant<T, Error> storage_;
};

// Result for operations that produce nothing but can fail.
class [[nodiscard]] Status {
public:
    Status() = default;
    Status(Error error) : error_(std::move(error)), failed_(true) {}
    static Status success() { return {}; }

    bool ok() const { return !failed_; }
    explicit operator bool() const { return ok(); }
    const Error& error() const {
        SYLVA_CHECK(failed_);
        return error_;
    }

private:
    Error error_;
    bool failed_ = false;
};

}  // namespace sylva
