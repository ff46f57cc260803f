// The `.plod` codec: sections assembled from the record field lists of PlodRecords.h
// (one list per record, run by the writer and the reader alike) and the checks of
// docs/formats.md ("Validation"), first failure reported.
#include "sylva/core/plantlod/PlodFile.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include "PlodRecords.h"
#include "sylva/core/base/AtomicFile.h"

namespace sylva {

namespace {

using plod::strideOf;

constexpr char kMagic[8] = {'S', 'Y', 'L', 'V', 'P', 'L', 'O', 'D'};
constexpr std::size_t kHeaderSize = strideOf<plod::Header>();
constexpr std::size_t kEntrySize = strideOf<plod::SectionEntry>();
constexpr std::size_t kAlignment = 64;
constexpr std::uint32_t kSectionVersion = 1;

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

// ---------------------------------------------------------------------------- writing

struct Section {
    char tag[4] = {};
    std::uint32_t count = 0;
    std::uint32_t stride = 0;
    plod::PlodWriter data;
};

Section emptySection(const char (&tag)[5], std::uint32_t stride) {
    Section section;
    std::memcpy(section.tag, tag, 4);
    section.stride = stride;
    return section;
}

template <typename Record>
Section recordSection(const char (&tag)[5], const std::vector<Record>& records) {
    Section section = emptySection(tag, strideOf<Record>());
    section.count = static_cast<std::uint32_t>(records.size());
    for (const Record& record : records) {
        plod::write(section.data, record);
    }
    return section;
}

Section nameSection(const std::string& name) {
    Section section = emptySection("NAME", 1);
    section.count = static_cast<std::uint32_t>(name.size());
    section.data.bytes.assign(name.begin(), name.end());
    return section;
}

// `BBCL`, `BBCQ`, `BBCA`: the levels, all their quads, their atlases (each atlas 64-byte
// aligned inside `BBCA`).
void appendBillboardSections(const BillboardCloud& cloud, std::vector<Section>& sections) {
    Section levels = emptySection("BBCL", strideOf<plod::BillboardLevelEntry>());
    Section quads = emptySection("BBCQ", strideOf<BillboardQuad>());
    Section atlases = emptySection("BBCA", 1);
    std::uint32_t firstQuad = 0;
    for (const BillboardLevel& level : cloud.levels) {
        atlases.data.pad(kAlignment);
        plod::BillboardLevelEntry entry;
        entry.epsilon = level.epsilon;
        entry.imageError = level.imageError;
        entry.firstQuad = firstQuad;
        entry.quadCount = static_cast<std::uint32_t>(level.quads.size());
        entry.atlasWidth = static_cast<std::uint32_t>(level.atlas.width);
        entry.atlasHeight = static_cast<std::uint32_t>(level.atlas.height);
        entry.atlasOffset = atlases.data.bytes.size();
        plod::write(levels.data, entry);
        atlases.data.bytes.insert(atlases.data.bytes.end(), level.atlas.rgba.begin(),
                                  level.atlas.rgba.end());
        for (const BillboardQuad& quad : level.quads) {
            plod::write(quads.data, quad);
        }
        firstQuad += entry.quadCount;
    }
    levels.count = static_cast<std::uint32_t>(cloud.levels.size());
    quads.count = firstQuad;
    atlases.count = static_cast<std::uint32_t>(atlases.data.bytes.size());
    sections.push_back(std::move(levels));
    sections.push_back(std::move(quads));
    sections.push_back(std::move(atlases));
}

}  // namespace

std::vector<std::uint8_t> encodePlod(const PlantLod& lod) {
    std::vector<Section> sections;
    sections.push_back(nameSection(lod.name));
    sections.push_back(recordSection("LEVL", lod.levels));
    sections.push_back(recordSection("ELLI", lod.ellipsoids));
    sections.push_back(recordSection("LINE", lod.lines));
    if (!lod.billboards.levels.empty()) {
        appendBillboardSections(lod.billboards, sections);
    }
    // Everything after the header: the table, then the sections at aligned offsets.
    plod::PlodWriter body;
    std::uint64_t offset = kHeaderSize + kEntrySize * sections.size();
    for (const Section& section : sections) {
        offset = (offset + kAlignment - 1) / kAlignment * kAlignment;
        plod::SectionEntry entry;
        std::memcpy(entry.tag, section.tag, 4);
        entry.version = kSectionVersion;
        entry.offset = offset;
        entry.size = section.data.bytes.size();
        entry.count = section.count;
        entry.stride = section.stride;
        plod::write(body, entry);
        offset += entry.size;
    }
    for (const Section& section : sections) {
        // Padding relative to the body is padding relative to the file: 64 | kHeaderSize.
        body.pad(kAlignment);
        body.bytes.insert(body.bytes.end(), section.data.bytes.begin(), section.data.bytes.end());
    }
    plod::Header header;
    std::memcpy(header.magic, kMagic, sizeof kMagic);
    header.version = kPlodVersion;
    header.headerSize = static_cast<std::uint32_t>(kHeaderSize);
    header.sectionCount = static_cast<std::uint32_t>(sections.size());
    header.fileSize = kHeaderSize + body.bytes.size();
    header.boundsMinimum = lod.boundsMinimum;
    header.boundsMaximum = lod.boundsMaximum;
    header.checksum = fnv1a(body.bytes);
    plod::PlodWriter out;
    plod::write(out, header);
    out.bytes.insert(out.bytes.end(), body.bytes.begin(), body.bytes.end());
    return std::move(out.bytes);
}

namespace {

// ---------------------------------------------------------------------------- reading

static_assert(kHeaderSize % kAlignment == 0);

// Messages that start with the file name.
struct Failure {
    const std::string& name;
    Error operator()(const std::string& message) const { return Error{name + ": " + message}; }
};

// Magic, version, sizes, the table's extent and the checksum.
Result<plod::Header> readHeader(std::span<const std::uint8_t> bytes, const Failure& fail) {
    if (bytes.size() < kHeaderSize) {
        return fail("truncated header (" + std::to_string(bytes.size()) +
                    " bytes, a .plod header has 64)");
    }
    const plod::Header header = plod::read<plod::Header>(bytes, 0);
    if (std::memcmp(header.magic, kMagic, sizeof kMagic) != 0) {
        return fail("not a .plod file (bad magic; expected \"SYLVPLOD\")");
    }
    if (header.version != kPlodVersion) {
        return fail("unsupported .plod version " + std::to_string(header.version) +
                    " (this build reads version " + std::to_string(kPlodVersion) + ")");
    }
    if (header.headerSize != kHeaderSize) {
        return fail("header size " + std::to_string(header.headerSize) + " is not 64");
    }
    if (header.fileSize != bytes.size()) {
        return fail("truncated or padded: the header says " + std::to_string(header.fileSize) +
                    " bytes, the file has " + std::to_string(bytes.size()));
    }
    if (kHeaderSize + static_cast<std::uint64_t>(header.sectionCount) * kEntrySize > bytes.size()) {
        return fail("the section table (" + std::to_string(header.sectionCount) +
                    " entries) runs past the end of the file");
    }
    const std::uint64_t checksum = fnv1a(bytes.subspan(kHeaderSize));
    if (checksum != header.checksum) {
        return fail("checksum mismatch (stored " + hex(header.checksum) + ", computed " +
                    hex(checksum) + "): the file is corrupt");
    }
    return header;
}

// The table entries, each inside the file, aligned, and count × stride = size.
Result<std::vector<PlodSectionInfo>> readSectionTable(std::span<const std::uint8_t> bytes,
                                                      std::uint32_t sectionCount,
                                                      const Failure& fail) {
    std::vector<PlodSectionInfo> sections;
    sections.reserve(sectionCount);
    for (std::uint32_t i = 0; i < sectionCount; ++i) {
        const auto entry = plod::read<plod::SectionEntry>(bytes, kHeaderSize + i * kEntrySize);
        PlodSectionInfo s;
        s.tag.assign(entry.tag, 4);
        s.offset = entry.offset;
        s.size = entry.size;
        s.count = entry.count;
        s.stride = entry.stride;
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
        sections.push_back(s);
    }
    return sections;
}

// The sections this reader knows (others are skipped), with their element sizes checked.
struct KnownSections {
    const PlodSectionInfo* name = nullptr;
    const PlodSectionInfo* levels = nullptr;
    const PlodSectionInfo* ellipsoids = nullptr;
    const PlodSectionInfo* lines = nullptr;
    const PlodSectionInfo* billboardLevels = nullptr;
    const PlodSectionInfo* billboardQuads = nullptr;
    const PlodSectionInfo* billboardAtlases = nullptr;
};

Result<KnownSections> findSections(const std::vector<PlodSectionInfo>& sections,
                                   const Failure& fail) {
    KnownSections known;
    const struct {
        const char* tag;
        std::uint32_t stride;
        const PlodSectionInfo* KnownSections::*slot;
    } kinds[] = {
        {"LEVL", strideOf<PlantLodLevel>(), &KnownSections::levels},
        {"ELLI", strideOf<LodEllipsoid>(), &KnownSections::ellipsoids},
        {"LINE", strideOf<LodLine>(), &KnownSections::lines},
        {"NAME", 1, &KnownSections::name},
        {"BBCL", strideOf<plod::BillboardLevelEntry>(), &KnownSections::billboardLevels},
        {"BBCQ", strideOf<BillboardQuad>(), &KnownSections::billboardQuads},
        {"BBCA", 1, &KnownSections::billboardAtlases},
    };
    for (const PlodSectionInfo& s : sections) {
        for (const auto& kind : kinds) {
            if (s.tag != kind.tag) {
                continue;
            }
            known.*kind.slot = &s;
            if (s.stride != kind.stride) {
                return fail("section '" + s.tag + "' element size " + std::to_string(s.stride) +
                            ", expected " + std::to_string(kind.stride));
            }
        }
    }
    for (const auto& [section, tag] :
         {std::pair{known.levels, "LEVL"}, std::pair{known.ellipsoids, "ELLI"},
          std::pair{known.lines, "LINE"}}) {
        if (!section) {
            return fail(std::string("missing section '") + tag + "'");
        }
    }
    return known;
}

template <typename Record>
std::vector<Record> readRecords(std::span<const std::uint8_t> bytes,
                                const PlodSectionInfo& section) {
    std::vector<Record> records;
    records.reserve(section.count);
    for (std::uint32_t i = 0; i < section.count; ++i) {
        records.push_back(
            plod::read<Record>(bytes, section.offset + std::uint64_t{i} * section.stride));
    }
    return records;
}

Status checkLevels(const std::vector<PlantLodLevel>& levels, const Failure& fail) {
    for (std::size_t i = 0; i < levels.size(); ++i) {
        const PlantLodLevel& l = levels[i];
        if (std::isnan(l.errorMinimum) || std::isnan(l.errorMaximum) ||
            l.errorMinimum > l.errorMaximum) {
            return fail("level " + std::to_string(i) + " has an invalid error interval");
        }
    }
    return Status::success();
}

// Finite geometry, existing levels, and as many ellipsoids per level as the level lists.
Status checkEllipsoids(const std::vector<LodEllipsoid>& ellipsoids,
                       const std::vector<PlantLodLevel>& levels, const Failure& fail) {
    std::vector<std::uint32_t> perLevel(levels.size(), 0);
    for (std::size_t i = 0; i < ellipsoids.size(); ++i) {
        const LodEllipsoid& e = ellipsoids[i];
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
    }
    for (std::size_t k = 0; k < perLevel.size(); ++k) {
        if (perLevel[k] != levels[k].ellipsoidCount) {
            return fail("level " + std::to_string(k) + " lists " +
                        std::to_string(levels[k].ellipsoidCount) +
                        " ellipsoids, the ellipsoid section has " + std::to_string(perLevel[k]));
        }
    }
    return Status::success();
}

Status checkLines(const std::vector<LodLine>& lines, const Failure& fail) {
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const LodLine& l = lines[i];
        if (!finite(l.start) || !finite(l.end) || !std::isfinite(l.startRadius) ||
            !std::isfinite(l.endRadius)) {
            return fail("line " + std::to_string(i) + " has a non-finite end point or radius");
        }
    }
    return Status::success();
}

// The billboard levels with their quads and atlases.
Result<BillboardCloud> readBillboards(std::span<const std::uint8_t> bytes,
                                      const KnownSections& known, const Failure& fail) {
    const std::vector<BillboardQuad> quads =
        readRecords<BillboardQuad>(bytes, *known.billboardQuads);
    for (std::size_t i = 0; i < quads.size(); ++i) {
        const BillboardQuad& q = quads[i];
        if (!finite(q.corners[0]) || !finite(q.corners[1]) || !finite(q.corners[2]) ||
            !finite(q.corners[3]) || !finite(q.normal)) {
            return fail("billboard quad " + std::to_string(i) +
                        " has a non-finite corner or normal");
        }
    }
    const PlodSectionInfo& atlases = *known.billboardAtlases;
    if (known.billboardLevels->count > kMaxBillboardLevels) {
        return fail(std::to_string(known.billboardLevels->count) +
                    " billboard levels in section 'BBCL', at most " +
                    std::to_string(kMaxBillboardLevels) + " are supported");
    }
    const std::vector<plod::BillboardLevelEntry> entries =
        readRecords<plod::BillboardLevelEntry>(bytes, *known.billboardLevels);
    BillboardCloud cloud;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const plod::BillboardLevelEntry& entry = entries[i];
        const std::uint64_t first = entry.firstQuad;
        const std::uint64_t count = entry.quadCount;
        const std::uint32_t width = entry.atlasWidth;
        const std::uint32_t height = entry.atlasHeight;
        const std::string label = "billboard level " + std::to_string(i);
        if (first + count > quads.size()) {
            return fail(label + " names quads [" + std::to_string(first) + ", " +
                        std::to_string(first + count) + "), the file has " +
                        std::to_string(quads.size()));
        }
        const std::uint64_t atlasBytes = std::uint64_t{width} * height * 4u;
        if (width > 65536 || height > 65536 || entry.atlasOffset > atlases.size ||
            atlasBytes > atlases.size - entry.atlasOffset) {
            return fail(label + ": its " + std::to_string(width) + " x " + std::to_string(height) +
                        " atlas at byte " + std::to_string(entry.atlasOffset) +
                        " runs past the section 'BBCA' (" + std::to_string(atlases.size) +
                        " bytes)");
        }
        BillboardLevel level;
        level.epsilon = entry.epsilon;
        level.imageError = entry.imageError;
        level.quads.assign(quads.begin() + static_cast<std::ptrdiff_t>(first),
                           quads.begin() + static_cast<std::ptrdiff_t>(first + count));
        level.atlas.width = static_cast<int>(width);
        level.atlas.height = static_cast<int>(height);
        const std::uint8_t* atlas = bytes.data() + atlases.offset + entry.atlasOffset;
        level.atlas.rgba.assign(atlas, atlas + atlasBytes);
        cloud.levels.push_back(std::move(level));
    }
    return cloud;
}

}  // namespace

Result<PlantLod> decodePlod(std::span<const std::uint8_t> bytes, const std::string& name,
                            PlodFileInfo* info) {
    const Failure fail{name};
    Result<plod::Header> header = readHeader(bytes, fail);
    if (!header) {
        return header.error();
    }
    PlodFileInfo parsed;
    parsed.version = header->version;
    parsed.fileSize = header->fileSize;
    Result<std::vector<PlodSectionInfo>> table =
        readSectionTable(bytes, header->sectionCount, fail);
    if (!table) {
        return table.error();
    }
    parsed.sections = std::move(*table);
    Result<KnownSections> known = findSections(parsed.sections, fail);
    if (!known) {
        return known.error();
    }
    PlantLod lod;
    lod.boundsMinimum = header->boundsMinimum;
    lod.boundsMaximum = header->boundsMaximum;
    if (known->name) {
        lod.name.assign(reinterpret_cast<const char*>(bytes.data() + known->name->offset),
                        known->name->size);
    }
    lod.levels = readRecords<PlantLodLevel>(bytes, *known->levels);
    lod.ellipsoids = readRecords<LodEllipsoid>(bytes, *known->ellipsoids);
    lod.lines = readRecords<LodLine>(bytes, *known->lines);
    if (Status levels = checkLevels(lod.levels, fail); !levels) {
        return levels.error();
    }
    if (Status ellipsoids = checkEllipsoids(lod.ellipsoids, lod.levels, fail); !ellipsoids) {
        return ellipsoids.error();
    }
    if (Status lines = checkLines(lod.lines, fail); !lines) {
        return lines.error();
    }
    if (known->billboardLevels || known->billboardQuads || known->billboardAtlases) {
        if (!known->billboardLevels || !known->billboardQuads || !known->billboardAtlases) {
            return fail("billboard clouds need the sections 'BBCL', 'BBCQ' and 'BBCA' together");
        }
        Result<BillboardCloud> billboards = readBillboards(bytes, *known, fail);
        if (!billboards) {
            return billboards.error();
        }
        lod.billboards = std::move(*billboards);
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
