// PlodFile: the `.plod` binary of a PlantLod (layout byte by byte in docs/formats.md).
// Little-endian, versioned, a table of sections at 64-byte aligned offsets so the arrays
// can be memory-mapped and uploaded as they are; unknown sections are skipped, which
// leaves room for the billboard-cloud levels of the plant importer.
//
// Reading validates magic, version, sizes, section bounds, alignment, element sizes,
// the checksum and the level/primitive counts; every failure is an Error naming the
// file and the problem. Writing goes to a temporary file in the target folder that is
// renamed into place, so no partial file ever carries the final name.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantLod.h"

namespace sylva {

inline constexpr std::uint32_t kPlodVersion = 1;

struct PlodSectionInfo {
    std::string tag;  // four ASCII characters
    std::uint64_t offset = 0;
    std::uint64_t size = 0;
    std::uint32_t count = 0;
    std::uint32_t stride = 0;
};

struct PlodFileInfo {
    std::uint32_t version = 0;
    std::uint64_t fileSize = 0;
    std::vector<PlodSectionInfo> sections;
};

std::vector<std::uint8_t> encodePlod(const PlantLod& lod);
// `name` is the file name used in error messages.
Result<PlantLod> decodePlod(std::span<const std::uint8_t> bytes, const std::string& name,
                            PlodFileInfo* info = nullptr);

Status writePlodFile(const PlantLod& lod, const std::string& path);
Result<PlantLod> readPlodFile(const std::string& path, PlodFileInfo* info = nullptr);

}  // namespace sylva
