#include "sylva/core/plantlod/PlodFile.h"

#include "sylva/core/base/AtomicFile.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

#include <unistd.h>

namespace sylva {

namespace {

constexpr char kMagic[8] = {'S', 'Y', 'L', 'V', 'P', 'L', 'O', 'D'};
constexpr std::size_t kHeaderSize = 64;
constexpr std::size_t kEntrySize = 32;
constexpr std::size_t kAlignment = 64;
constexpr std::uint32_t kLevelStride = 32;
constexpr std::uint32_t kEllipsoidStride = 112;
constexpr std::uint32_t kLineStride = 64;
constexpr std::uint32_t kBillboardLevelStride = 32;
constexpr std::uint32_t kBillboardQuadStride = 96;

class Writer {
public:
    void u32(std::uint32_t v) {
        for (int i = 0; i < 4; ++i) {
            bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
        }
    }
    void u64(std::uint64_t v) {
        for (int i = 0; i < 8; ++i) {
            bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
        }
    }
    void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
    void vec3(const glm::vec3& v) {
        f32(v.x);
        f32(v.y);
        f32(v.z);
    }
    void vec2(const glm::vec2& v) {
        f32(v.x);
        f32(v.y);
    }
    void pad(std::size_t alignment) {
        while (bytes.size() % alignment != 0) {
            bytes.push_back(0);
        }
    }
    void putU64At(std::size_t at, std::uint64_t v) {
        for (int i = 0; i < 8; ++i) {
            bytes[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
        }
    }
    std::vector<std::uint8_t> bytes;
};

class Reader {
public:
    Reader(std::span<const std::uint8_t> bytes, std::size_t at) : bytes_(bytes), at_(at) {}
    std::uint32_t u32() {
        std::uint32_t v = 0;
        for (int i = 0; i < 4; ++i) {
            v |= static_cast<std::uint32_t>(bytes_[at_ + i]) << (8 * i);
        }
        at_ += 4;
        return v;
    }
    std::uint64_t u64() {
        std::uint64_t v = 0;
        for (int i = 0; i < 8; ++i) {
            v |= static_cast<std::uint64_t>(bytes_[at_ + i]) << (8 * i);
        }
        at_ += 8;
        return v;
    }
    float f32() { return std::bit_cast<float>(u32()); }
    glm::vec3 vec3() {
        const float x = f32(), y = f32();
        return {x, y, f32()};
    }
    glm::vec2 vec2() {
        const float x = f32();
        return {x, f32()};
    }

private:
    std::span<const std::uint8_t> bytes_;
    std::size_t at_;
};

std::uint64_t fnv1a(std::span<const std::uint8_t> bytes) {
    std::uint64_t hash = 0xcbf29ce484222325ull;
    for (std::uint8_t b : bytes) {
        hash = (hash ^ b) * 0x100000001b3ull;
    }
    return hash;
}

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string hex(std::uint64_t v) {
    char text[32];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
    return text;
}

}  // namespace

std::vector<std::uint8_t> encodePlod(const PlantLod& lod) {
    struct Section {
        char tag[4];
        std::uint32_t count;
        std::uint32_t stride;
        Writer data;
    };
    std::vector<Section> sections(4);
    std::memcpy(sections[0].tag, "NAME", 4);
    sections[0].count = static_cast<std::uint32_t>(lod.name.size());
    sections[0].stride = 1;
    sections[0].data.bytes.assign(lod.name.begin(), lod.name.end());

    std::memcpy(sections[1].tag, "LEVL", 4);
    sections[1].count = static_cast<std::uint32_t>(lod.levels.size());
    sections[1].stride = kLevelStride;
    for (const PlantLodLevel& level : lod.levels) {
        Writer& w = sections[1].data;
        w.f32(level.errorMinimum);
        w.f32(level.errorMaximum);
        w.u32(level.ellipsoidCount);
        w.u32(level.lineCount);
        w.f32(level.imageError);
        w.f32(level.alphaThreshold);
        w.f32(level.primitiveScale);
        w.u32(0);
    }

    std::memcpy(sections[2].tag, "ELLI", 4);
    sections[2].count = static_cast<std::uint32_t>(lod.ellipsoids.size());
    sections[2].stride = kEllipsoidStride;
    for (const LodEllipsoid& e : lod.ellipsoids) {
        Writer& w = sections[2].data;
        w.vec3(e.center);
        w.f32(e.weight);
        for (int i = 0; i < 3; ++i) {
            w.vec3(e.axes[i]);
            w.f32(e.radii[i]);
        }
        w.vec3(e.color);
        w.f32(e.ambientOcclusion);
        w.f32(e.noiseLevel);
        w.f32(e.alphaThreshold);
        w.f32(e.errorMinimum);
        w.f32(e.errorMaximum);
        w.u32(e.level);
        w.u32(0);
        w.u32(0);
        w.u32(0);
    }

    std::memcpy(sections[3].tag, "LINE", 4);
    sections[3].count = static_cast<std::uint32_t>(lod.lines.size());
    sections[3].stride = kLineStride;
    for (const LodLine& l : lod.lines) {
        Writer& w = sections[3].data;
        w.vec3(l.start);
        w.f32(l.startRadius);
        w.vec3(l.end);
        w.f32(l.endRadius);
        w.vec3(l.color);
        w.f32(l.ambientOcclusion);
        w.f32(l.weight);
        w.f32(l.errorMinimum);
        w.f32(l.errorMaximum);
        w.u32(0);
    }

    // Billboard clouds (optional): levels, quads, atlases (each atlas 64-byte aligned
    // inside BBCA).
    if (!lod.billboards.levels.empty()) {
        sections.resize(7);
        Section& levels = sections[4];
        Section& quads = sections[5];
        Section& atlases = sections[6];
        std::memcpy(levels.tag, "BBCL", 4);
        std::memcpy(quads.tag, "BBCQ", 4);
        std::memcpy(atlases.tag, "BBCA", 4);
        levels.stride = kBillboardLevelStride;
        quads.stride = kBillboardQuadStride;
        atlases.stride = 1;
        std::uint32_t firstQuad = 0;
        for (const BillboardLevel& level : lod.billboards.levels) {
            atlases.data.pad(kAlignment);
            Writer& w = levels.data;
            w.f32(level.epsilon);
            w.f32(level.imageError);
            w.u32(firstQuad);
            w.u32(static_cast<std::uint32_t>(level.quads.size()));
            w.u32(static_cast<std::uint32_t>(level.atlas.width));
            w.u32(static_cast<std::uint32_t>(level.atlas.height));
            w.u64(atlases.data.bytes.size());
            atlases.data.bytes.insert(atlases.data.bytes.end(), level.atlas.rgba.begin(),
                                      level.atlas.rgba.end());
            for (const BillboardQuad& q : level.quads) {
                Writer& qw = quads.data;
                for (const glm::vec3& c : q.corners) {
                    qw.vec3(c);
                }
                for (const glm::vec2& uv : q.atlasUvs) {
                    qw.vec2(uv);
                }
                qw.vec3(q.normal);
                qw.u32((q.part == PlantPart::Branch ? 1u : 0u) | (q.cardboard ? 2u : 0u));
            }
            firstQuad += static_cast<std::uint32_t>(level.quads.size());
        }
        levels.count = static_cast<std::uint32_t>(lod.billboards.levels.size());
        quads.count = firstQuad;
        atlases.count = static_cast<std::uint32_t>(atlases.data.bytes.size());
    }

    Writer out;
    out.bytes.insert(out.bytes.end(), kMagic, kMagic + 8);
    out.u32(kPlodVersion);
    out.u32(static_cast<std::uint32_t>(kHeaderSize));
    out.u32(static_cast<std::uint32_t>(sections.size()));
    out.u32(0);  // flags
    out.u64(0);  // file size, patched below
    out.vec3(lod.boundsMinimum);
    out.vec3(lod.boundsMaximum);
    out.u64(0);  // checksum, patched below
    std::uint64_t offset = kHeaderSize + kEntrySize * sections.size();
    for (Section& s : sections) {
        offset = (offset + kAlignment - 1) / kAlignment * kAlignment;
        out.bytes.insert(out.bytes.end(), s.tag, s.tag + 4);
        out.u32(1);  // section version
        out.u64(offset);
        out.u64(s.data.bytes.size());
        out.u32(s.count);
        out.u32(s.stride);
        offset += s.data.bytes.size();
    }
    for (Section& s : sections) {
        out.pad(kAlignment);
        out.bytes.insert(out.bytes.end(), s.data.bytes.begin(), s.data.bytes.end());
    }
    out.putU64At(24, out.bytes.size());
    out.putU64At(56, fnv1a(std::span(out.bytes).subspan(kHeaderSize)));
    return std::move(out.bytes);
}

Result<PlantLod> decodePlod(std::span<const std::uint8_t> bytes, const std::string& name,
                            PlodFileInfo* info) {
    const auto fail = [&](const std::string& message) { return Error{name + ": " + message}; };
    if (bytes.size() < kHeaderSize) {
        return fail("truncated header (" + std::to_string(bytes.size()) +
                    " bytes, a .plod header has 64)");
    }
    if (std::memcmp(bytes.data(), kMagic, 8) != 0) {
        return fail("not a .plod file (bad magic; expected \"SYLVPLOD\")");
    }
    Reader header(bytes, 8);
    const std::uint32_t version = header.u32();
    if (version != kPlodVersion) {
        return fail("unsupported .plod version " + std::to_string(version) +
                    " (this build reads version " + std::to_string(kPlodVersion) + ")");
    }
    const std::uint32_t headerSize = header.u32();
    if (headerSize != kHeaderSize) {
        return fail("header size " + std::to_string(headerSize) + " is not 64");
    }
    const std::uint32_t sectionCount = header.u32();
    header.u32();  // flags
    const std::uint64_t fileSize = header.u64();
    if (fileSize != bytes.size()) {
        return fail("truncated or padded: the header says " + std::to_string(fileSize) +
                    " bytes, the file has " + std::to_string(bytes.size()));
    }
    PlantLod lod;
    lod.boundsMinimum = header.vec3();
    lod.boundsMaximum = header.vec3();
    const std::uint64_t storedChecksum = header.u64();
    if (kHeaderSize + static_cast<std::uint64_t>(sectionCount) * kEntrySize > bytes.size()) {
        return fail("the section table (" + std::to_string(sectionCount) +
                    " entries) runs past the end of the file");
    }
    const std::uint64_t checksum = fnv1a(bytes.subspan(kHeaderSize));
    if (checksum != storedChecksum) {
        return fail("checksum mismatch (stored " + hex(storedChecksum) + ", computed " +
                    hex(checksum) + "): the file is corrupt");
    }
    PlodFileInfo parsed;
    parsed.version = version;
    parsed.fileSize = fileSize;
    Reader table(bytes, kHeaderSize);
    const PlodSectionInfo* level = nullptr;
    const PlodSectionInfo* ellipsoid = nullptr;
    const PlodSectionInfo* line = nullptr;
    const PlodSectionInfo* nameSection = nullptr;
    const PlodSectionInfo* billboardLevels = nullptr;
    const PlodSectionInfo* billboardQuads = nullptr;
    const PlodSectionInfo* billboardAtlases = nullptr;
    parsed.sections.reserve(sectionCount);
    for (std::uint32_t i = 0; i < sectionCount; ++i) {
        PlodSectionInfo s;
        const std::size_t at = kHeaderSize + i * kEntrySize;
        s.tag.assign(reinterpret_cast<const char*>(bytes.data() + at), 4);
        table.u32();
        table.u32();  // section version
        s.offset = table.u64();
        s.size = table.u64();
        s.count = table.u32();
        s.stride = table.u32();
        const std::string label = "section '" + s.tag + "'";
        if (s.offset % kAlignment != 0) {
            return fail(label + " offset " + std::to_string(s.offset) + " is not 64-byte aligned");
        }
        if (s.offset > bytes.size() || s.size > bytes.size() - s.offset) {
            return fail(label + " [" + std::to_string(s.offset) + ", " +
                        std::to_string(s.offset + s.size) + ") runs past the end of the file (" +
                        std::to_string(bytes.size()) + " bytes)");
        }
        if (static_cast<std::uint64_t>(s.count) * s.stride != s.size) {
            return fail(label + " holds " + std::to_string(s.size) + " bytes, but " +
                        std::to_string(s.count) + " elements of " + std::to_string(s.stride) +
                        " bytes need " +
                        std::to_string(static_cast<std::uint64_t>(s.count) * s.stride));
        }
        parsed.sections.push_back(s);
    }
    for (const PlodSectionInfo& s : parsed.sections) {
        const auto expect = [&](std::uint32_t stride) -> Status {
            if (s.stride != stride) {
                return fail("section '" + s.tag + "' element size " + std::to_string(s.stride) +
                            ", expected " + std::to_string(stride));
            }
            return Status::success();
        };
        Status status;
        if (s.tag == "LEVL") {
            level = &s;
            status = expect(kLevelStride);
        } else if (s.tag == "ELLI") {
            ellipsoid = &s;
            status = expect(kEllipsoidStride);
        } else if (s.tag == "LINE") {
            line = &s;
            status = expect(kLineStride);
        } else if (s.tag == "NAME") {
            nameSection = &s;
            status = expect(1);
        } else if (s.tag == "BBCL") {
            billboardLevels = &s;
            status = expect(kBillboardLevelStride);
        } else if (s.tag == "BBCQ") {
            billboardQuads = &s;
            status = expect(kBillboardQuadStride);
        } else if (s.tag == "BBCA") {
            billboardAtlases = &s;
            status = expect(1);
        }
        if (!status) {
            return status.error();
        }
    }
    for (const auto& [section, tag] :
         {std::pair{level, "LEVL"}, std::pair{ellipsoid, "ELLI"}, std::pair{line, "LINE"}}) {
        if (!section) {
            return fail(std::string("missing section '") + tag + "'");
        }
    }
    if (nameSection) {
        lod.name.assign(reinterpret_cast<const char*>(bytes.data() + nameSection->offset),
                        nameSection->size);
    }
    Reader r(bytes, level->offset);
    for (std::uint32_t i = 0; i < level->count; ++i) {
        PlantLodLevel l;
        l.errorMinimum = r.f32();
        l.errorMaximum = r.f32();
        l.ellipsoidCount = r.u32();
        l.lineCount = r.u32();
        l.imageError = r.f32();
        l.alphaThreshold = r.f32();
        l.primitiveScale = r.f32();
        r.u32();
        if (std::isnan(l.errorMinimum) || std::isnan(l.errorMaximum) ||
            l.errorMinimum > l.errorMaximum) {
            return fail("level " + std::to_string(i) + " has an invalid error interval");
        }
        lod.levels.push_back(l);
    }
    r = Reader(bytes, ellipsoid->offset);
    std::vector<std::uint32_t> perLevel(lod.levels.size(), 0);
    for (std::uint32_t i = 0; i < ellipsoid->count; ++i) {
        LodEllipsoid e;
        e.center = r.vec3();
        e.weight = r.f32();
        for (int k = 0; k < 3; ++k) {
            e.axes[k] = r.vec3();
            e.radii[k] = r.f32();
        }
        e.color = r.vec3();
        e.ambientOcclusion = r.f32();
        e.noiseLevel = r.f32();
        e.alphaThreshold = r.f32();
        e.errorMinimum = r.f32();
        e.errorMaximum = r.f32();
        e.level = r.u32();
        r.u32();
        r.u32();
        r.u32();
        if (!finite(e.center) || !finite(e.radii) || !finite(e.axes[0]) || !finite(e.axes[1]) ||
            !finite(e.axes[2])) {
            return fail("ellipsoid " + std::to_string(i) +
                        " has a non-finite centre, axis or radius");
        }
        if (e.level >= perLevel.size()) {
            return fail("ellipsoid " + std::to_string(i) + " names level " +
                        std::to_string(e.level) + ", the file has " +
                        std::to_string(perLevel.size()) + " levels");
        }
        ++perLevel[e.level];
        lod.ellipsoids.push_back(e);
    }
    for (std::size_t k = 0; k < perLevel.size(); ++k) {
        if (perLevel[k] != lod.levels[k].ellipsoidCount) {
            return fail("level " + std::to_string(k) + " lists " +
                        std::to_string(lod.levels[k].ellipsoidCount) +
                        " ellipsoids, the ellipsoid section has " + std::to_string(perLevel[k]));
        }
    }
    r = Reader(bytes, line->offset);
    for (std::uint32_t i = 0; i < line->count; ++i) {
        LodLine l;
        l.start = r.vec3();
        l.startRadius = r.f32();
        l.end = r.vec3();
        l.endRadius = r.f32();
        l.color = r.vec3();
        l.ambientOcclusion = r.f32();
        l.weight = r.f32();
        l.errorMinimum = r.f32();
        l.errorMaximum = r.f32();
        r.u32();
        if (!finite(l.start) || !finite(l.end) || !std::isfinite(l.startRadius) ||
            !std::isfinite(l.endRadius)) {
            return fail("line " + std::to_string(i) + " has a non-finite end point or radius");
        }
        lod.lines.push_back(l);
    }
    if (billboardLevels || billboardQuads || billboardAtlases) {
        if (!billboardLevels || !billboardQuads || !billboardAtlases) {
            return fail("billboard clouds need the sections 'BBCL', 'BBCQ' and 'BBCA' together");
        }
        std::vector<BillboardQuad> quads;
        r = Reader(bytes, billboardQuads->offset);
        for (std::uint32_t i = 0; i < billboardQuads->count; ++i) {
            BillboardQuad q;
            for (glm::vec3& c : q.corners) {
                c = r.vec3();
            }
            for (glm::vec2& uv : q.atlasUvs) {
                uv = r.vec2();
            }
            q.normal = r.vec3();
            const std::uint32_t flags = r.u32();
            q.part = (flags & 1u) != 0 ? PlantPart::Branch : PlantPart::Leaf;
            q.cardboard = (flags & 2u) != 0;
            if (!finite(q.corners[0]) || !finite(q.corners[1]) || !finite(q.corners[2]) ||
                !finite(q.corners[3]) || !finite(q.normal)) {
                return fail("billboard quad " + std::to_string(i) +
                            " has a non-finite corner or normal");
            }
            quads.push_back(q);
        }
        r = Reader(bytes, billboardLevels->offset);
        for (std::uint32_t i = 0; i < billboardLevels->count; ++i) {
            BillboardLevel billboard;
            billboard.epsilon = r.f32();
            billboard.imageError = r.f32();
            const std::uint64_t first = r.u32();
            const std::uint64_t count = r.u32();
            const std::uint32_t width = r.u32();
            const std::uint32_t height = r.u32();
            const std::uint64_t atlasOffset = r.u64();
            const std::string label = "billboard level " + std::to_string(i);
            if (first + count > quads.size()) {
                return fail(label + " names quads [" + std::to_string(first) + ", " +
                            std::to_string(first + count) + "), the file has " +
                            std::to_string(quads.size()));
            }
            const std::uint64_t atlasBytes = std::uint64_t{width} * height * 4u;
            if (width > 65536 || height > 65536 || atlasOffset > billboardAtlases->size ||
                atlasBytes > billboardAtlases->size - atlasOffset) {
                return fail(label + ": its " + std::to_string(width) + " x " +
                            std::to_string(height) + " atlas at byte " +
                            std::to_string(atlasOffset) + " runs past the section 'BBCA' (" +
                            std::to_string(billboardAtlases->size) + " bytes)");
            }
            billboard.quads.assign(quads.begin() + static_cast<std::ptrdiff_t>(first),
                                   quads.begin() + static_cast<std::ptrdiff_t>(first + count));
            billboard.atlas.width = static_cast<int>(width);
            billboard.atlas.height = static_cast<int>(height);
            const std::uint8_t* atlas = bytes.data() + billboardAtlases->offset + atlasOffset;
            billboard.atlas.rgba.assign(atlas, atlas + atlasBytes);
            lod.billboards.levels.push_back(std::move(billboard));
        }
    }
    if (info) {
        *info = std::move(parsed);
    }
    return lod;
}

Status writePlodFile(const PlantLod& lod, const std::string& path) {
    const std::vector<std::uint8_t> bytes = encodePlod(lod);
    const Status written = writeFileAtomically(
        path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    if (!written) {
        return Error{"cannot write " + path + ": " + written.error().message};
    }
    return Status::success();
}

Result<PlantLod> readPlodFile(const std::string& path, PlodFileInfo* info) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        return Error{"cannot open " + path + ": " + std::strerror(errno)};
    }
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                          std::istreambuf_iterator<char>());
    return decodePlod(bytes, path, info);
}

}  // namespace sylva
