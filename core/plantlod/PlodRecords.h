// PlodRecords: the byte layout of every `.plod` record (docs/formats.md), written down
// once. Each record has one field list, `fields(io, record)`, that a PlodWriter (encode:
// the record is const) and a PlodReader (decode: the record is filled) both run, so a
// field cannot be added to, dropped from or moved on one side only; a PlodByteCounter
// runs the same list at compile time to give the record's stride, which the static
// assertions below hold to the documented sizes (a changed list is a new format version).
//
// Encodings: integers unsigned little-endian, reals IEEE-754 binary32 little-endian,
// reserved bytes zero on write and ignored on read.
#pragma once

#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Check.h"
#include "sylva/core/plantlod/PlantLod.h"

namespace sylva::plod {

// `Record` or `const Record`: a field list serves the writer and the reader alike.
template <typename T, typename Record>
concept RecordOf = std::same_as<std::remove_const_t<T>, Record>;

// Appends a record's fields to a byte vector.
class PlodWriter {
public:
    void field(std::uint32_t value) { little(value, 4); }
    void field(std::uint64_t value) { little(value, 8); }
    void field(float value) { field(std::bit_cast<std::uint32_t>(value)); }
    void field(const glm::vec2& value) {
        field(value.x);
        field(value.y);
    }
    void field(const glm::vec3& value) {
        field(value.x);
        field(value.y);
        field(value.z);
    }
    template <std::size_t N>
    void field(const char (&text)[N]) {
        bytes.insert(bytes.end(), text, text + N);
    }
    // A value stored in another form: Packing::encode(record) gives the u32 written.
    template <typename Packing, typename Record>
    void packed(const Record& record) {
        field(Packing::encode(record));
    }
    void reserved(std::size_t count) { bytes.insert(bytes.end(), count, 0); }

    // Zero bytes up to the next multiple of `alignment`.
    void pad(std::size_t alignment) {
        while (bytes.size() % alignment != 0) {
            bytes.push_back(0);
        }
    }

    std::vector<std::uint8_t> bytes;

private:
    void little(std::uint64_t value, int size) {
        for (int i = 0; i < size; ++i) {
            bytes.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
        }
    }
};

// Reads a record's fields from `bytes` starting at `at`. The caller has checked that the
// records lie inside the bytes (section bounds, count × stride = size); reading past the
// end is a programmer error.
class PlodReader {
public:
    PlodReader(std::span<const std::uint8_t> bytes, std::size_t at) : bytes_(bytes), at_(at) {}

    void field(std::uint32_t& value) { value = static_cast<std::uint32_t>(little(4)); }
    void field(std::uint64_t& value) { value = little(8); }
    void field(float& value) {
        std::uint32_t bits = 0;
        field(bits);
        value = std::bit_cast<float>(bits);
    }
    void field(glm::vec2& value) {
        field(value.x);
        field(value.y);
    }
    void field(glm::vec3& value) {
        field(value.x);
        field(value.y);
        field(value.z);
    }
    template <std::size_t N>
    void field(char (&text)[N]) {
        take(N);
        for (std::size_t i = 0; i < N; ++i) {
            text[i] = static_cast<char>(bytes_[at_ - N + i]);
        }
    }
    // The stored u32 given back to Packing::decode(value, record).
    template <typename Packing, typename Record>
    void packed(Record& record) {
        std::uint32_t value = 0;
        field(value);
        Packing::decode(value, record);
    }
    void reserved(std::size_t count) { take(count); }

private:
    void take(std::size_t count) {
        SYLVA_CHECK(at_ + count <= bytes_.size());
        at_ += count;
    }
    std::uint64_t little(int size) {
        take(std::size_t(size));
        std::uint64_t value = 0;
        for (int i = 0; i < size; ++i) {
            value |= static_cast<std::uint64_t>(bytes_[at_ - std::size_t(size) + std::size_t(i)])
                     << (8 * i);
        }
        return value;
    }

    std::span<const std::uint8_t> bytes_;
    std::size_t at_;
};

// Counts the bytes of a field list (constant evaluation: the record strides).
class PlodByteCounter {
public:
    constexpr void field(std::uint32_t) { bytes += 4; }
    constexpr void field(std::uint64_t) { bytes += 8; }
    constexpr void field(float) { bytes += 4; }
    constexpr void field(const glm::vec2&) { bytes += 8; }
    constexpr void field(const glm::vec3&) { bytes += 12; }
    template <std::size_t N>
    constexpr void field(const char (&)[N]) {
        bytes += N;
    }
    template <typename Packing, typename Record>
    constexpr void packed(const Record&) {
        bytes += 4;
    }
    constexpr void reserved(std::size_t count) { bytes += count; }

    std::size_t bytes = 0;
};

// ---------------------------------------------------------------------------- records

// The 64-byte file header.
struct Header {
    char magic[8] = {};
    std::uint32_t version = 0;
    std::uint32_t headerSize = 0;
    std::uint32_t sectionCount = 0;
    std::uint32_t flags = 0;
    std::uint64_t fileSize = 0;
    glm::vec3 boundsMinimum{0.0f};
    glm::vec3 boundsMaximum{0.0f};
    std::uint64_t checksum = 0;
};

template <typename Io, RecordOf<Header> R>
constexpr void fields(Io& io, R& header) {
    io.field(header.magic);
    io.field(header.version);
    io.field(header.headerSize);
    io.field(header.sectionCount);
    io.field(header.flags);
    io.field(header.fileSize);
    io.field(header.boundsMinimum);
    io.field(header.boundsMaximum);
    io.field(header.checksum);
}

// One 32-byte entry of the section table.
struct SectionEntry {
    char tag[4] = {};
    std::uint32_t version = 0;
    std::uint64_t offset = 0;  // from the file start, a multiple of 64
    std::uint64_t size = 0;    // bytes, count × stride
    std::uint32_t count = 0;
    std::uint32_t stride = 0;
};

template <typename Io, RecordOf<SectionEntry> R>
constexpr void fields(Io& io, R& entry) {
    io.field(entry.tag);
    io.field(entry.version);
    io.field(entry.offset);
    io.field(entry.size);
    io.field(entry.count);
    io.field(entry.stride);
}

// `LEVL`.
template <typename Io, RecordOf<PlantLodLevel> R>
constexpr void fields(Io& io, R& level) {
    io.field(level.errorMinimum);
    io.field(level.errorMaximum);
    io.field(level.ellipsoidCount);
    io.field(level.lineCount);
    io.field(level.imageError);
    io.field(level.alphaThreshold);
    io.field(level.primitiveScale);
    io.reserved(4);
}

// `ELLI`: each axis is followed by its radius.
template <typename Io, RecordOf<LodEllipsoid> R>
constexpr void fields(Io& io, R& ellipsoid) {
    io.field(ellipsoid.center);
    io.field(ellipsoid.weight);
    for (int i = 0; i < 3; ++i) {
        io.field(ellipsoid.axes[i]);
        io.field(ellipsoid.radii[i]);
    }
    io.field(ellipsoid.color);
    io.field(ellipsoid.ambientOcclusion);
    io.field(ellipsoid.noiseLevel);
    io.field(ellipsoid.alphaThreshold);
    io.field(ellipsoid.errorMinimum);
    io.field(ellipsoid.errorMaximum);
    io.field(ellipsoid.level);
    io.reserved(12);
}

// `LINE`.
template <typename Io, RecordOf<LodLine> R>
constexpr void fields(Io& io, R& line) {
    io.field(line.start);
    io.field(line.startRadius);
    io.field(line.end);
    io.field(line.endRadius);
    io.field(line.color);
    io.field(line.ambientOcclusion);
    io.field(line.weight);
    io.field(line.errorMinimum);
    io.field(line.errorMaximum);
    io.reserved(4);
}

// `BBCL`: a billboard level as stored; its quads and atlas live in `BBCQ` and `BBCA`.
struct BillboardLevelEntry {
    float epsilon = 0.0f;
    float imageError = 0.0f;
    std::uint32_t firstQuad = 0;
    std::uint32_t quadCount = 0;
    std::uint32_t atlasWidth = 0;
    std::uint32_t atlasHeight = 0;
    std::uint64_t atlasOffset = 0;  // inside `BBCA`, a multiple of 64
};

template <typename Io, RecordOf<BillboardLevelEntry> R>
constexpr void fields(Io& io, R& level) {
    io.field(level.epsilon);
    io.field(level.imageError);
    io.field(level.firstQuad);
    io.field(level.quadCount);
    io.field(level.atlasWidth);
    io.field(level.atlasHeight);
    io.field(level.atlasOffset);
}

// The flags word of a billboard quad: bit 0 = branch part (else leaves), bit 1 = cardboard.
struct BillboardQuadFlags {
    static std::uint32_t encode(const BillboardQuad& quad) {
        return (quad.part == PlantPart::Branch ? 1u : 0u) | (quad.cardboard ? 2u : 0u);
    }
    static void decode(std::uint32_t flags, BillboardQuad& quad) {
        quad.part = (flags & 1u) != 0 ? PlantPart::Branch : PlantPart::Leaf;
        quad.cardboard = (flags & 2u) != 0;
    }
};

// `BBCQ`.
template <typename Io, RecordOf<BillboardQuad> R>
constexpr void fields(Io& io, R& quad) {
    for (auto& corner : quad.corners) {
        io.field(corner);
    }
    for (auto& uv : quad.atlasUvs) {
        io.field(uv);
    }
    io.field(quad.normal);
    io.template packed<BillboardQuadFlags>(quad);
}

// The stride of a record: the bytes its field list writes.
template <typename Record>
constexpr std::uint32_t strideOf() {
    PlodByteCounter counter;
    const Record record{};
    fields(counter, record);
    return static_cast<std::uint32_t>(counter.bytes);
}

// The sizes docs/formats.md gives; a field list that no longer matches them fails here.
static_assert(strideOf<Header>() == 64);
static_assert(strideOf<SectionEntry>() == 32);
static_assert(strideOf<PlantLodLevel>() == 32);
static_assert(strideOf<LodEllipsoid>() == 112);
static_assert(strideOf<LodLine>() == 64);
static_assert(strideOf<BillboardLevelEntry>() == 32);
static_assert(strideOf<BillboardQuad>() == 96);

template <typename Record>
void write(PlodWriter& writer, const Record& record) {
    fields(writer, record);
}

template <typename Record>
Record read(std::span<const std::uint8_t> bytes, std::size_t at) {
    PlodReader reader(bytes, at);
    Record record;
    fields(reader, record);
    return record;
}

}  // namespace sylva::plod
