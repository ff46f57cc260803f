// Content hashing for sources and tiles: a deterministic 64-bit hash (FNV-1a over bytes,
// finished by a 64-bit mix). Equal inputs give equal hashes on every platform and run,
// which is what cache invalidation and scenario sharing rely on. Not cryptographic.
#pragma once

#include <cstdint>
#include <cstring>
#include <string_view>
#include <type_traits>

namespace sylva {

class ContentHash {
public:
    ContentHash& add(const void* bytes, std::size_t size) {
        const auto* p = static_cast<const unsigned char*>(bytes);
        for (std::size_t i = 0; i < size; ++i) {
            state_ ^= p[i];
            state_ *= 0x100000001b3ull;
        }
        return *this;
    }
    ContentHash& add(std::string_view text) {
        const std::uint64_t size = text.size();
        add(&size, sizeof size);
        return add(text.data(), text.size());
    }
    template <typename T>
    requires std::is_arithmetic_v<T> ContentHash& add(T value) { return add(&value, sizeof value); }
    std::uint64_t value() const {
        std::uint64_t x = state_;
        x ^= x >> 33;
        x *= 0xff51afd7ed558ccdull;
        x ^= x >> 33;
        x *= 0xc4ceb9fe1a85ec53ull;
        x ^= x >> 33;
        return x;
    }

private:
    std::uint64_t state_ = 0xcbf29ce484222325ull;
};

}  // namespace sylva
