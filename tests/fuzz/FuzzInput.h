// Helpers of the loader fuzz targets: a scratch folder per process (the loaders read
// files), and the rule every target checks: a loader either succeeds or fails with a
// message; it never crashes, hangs or fails silently.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace sylva::fuzz {

inline const std::filesystem::path& scratchFolder() {
    static const std::filesystem::path folder = [] {
        const auto path =
            std::filesystem::temp_directory_path() / ("sylva-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(path);
        return path;
    }();
    return folder;
}

inline std::filesystem::path writeInput(const std::string& name, std::string_view bytes) {
    const std::filesystem::path path = scratchFolder() / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return path;
}

inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

// A failure must say what failed.
template <typename ResultType>
void requireMessage(const ResultType& result) {
    if (!result.ok() && result.error().message.empty()) {
        std::abort();
    }
}

}  // namespace sylva::fuzz
