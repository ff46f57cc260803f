#include "sylva/core/plantlod/PlodFile.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

namespace sylva {
namespace {

PlantLod sampleLod() {
    PlantLod lod;
    lod.name = "oak";
    lod.boundsMinimum = {-1.5f, -2.0f, 0.0f};
    lod.boundsMaximum = {1.5f, 2.0f, 7.25f};
    for (int k = 0; k < 3; ++k) {
        PlantLodLevel level;
        level.errorMinimum = k == 0 ? 0.0f : 0.01f * k;
        level.errorMaximum = k == 2 ? std::numeric_limits<float>::infinity() : 0.01f * (k + 1);
        level.ellipsoidCount = 3 - k;
        level.lineCount = 5 - k;
        level.imageError = 0.001f * (k + 1);
        level.alphaThreshold = 0.1f * k;
        level.primitiveScale = 1.0f + k;
        lod.levels.push_back(level);
    }
    for (std::uint32_t level : {2u, 1u, 1u, 0u, 0u, 0u}) {
        LodEllipsoid e;
        e.center = {0.1f * level, 1.0f / 3.0f, -0.0f};
        e.axes[0] = glm::normalize(glm::vec3(1, 1, 0));
        e.axes[1] = glm::normalize(glm::vec3(-1, 1, 0));
        e.axes[2] = {0, 0, 1};
        e.radii = {0.3f, 0.2f, 1e-7f};
        e.color = {0.1f, 0.6f, 0.05f};
        e.weight = 0.02f;
        e.noiseLevel = 2.25f;
        e.alphaThreshold = 0.5f;
        e.ambientOcclusion = 0.7f;
        e.errorMinimum = lod.levels[level].errorMinimum;
        e.errorMaximum = lod.levels[level].errorMaximum;
        e.level = level;
        lod.ellipsoids.push_back(e);
    }
    for (int i = 0; i < 5; ++i) {
        LodLine l;
        l.start = {0, 0, float(i)};
        l.end = {0.5f, 0, float(i) + 1.0f};
        l.startRadius = 0.05f;
        l.endRadius = 0.04f;
        l.color = {0.3f, 0.2f, 0.1f};
        l.weight = 1e-3f;
        l.ambientOcclusion = 0.4f;
        l.errorMinimum = 0.0f;
        l.errorMaximum = i == 0 ? std::numeric_limits<float>::infinity() : 0.02f;
        lod.lines.push_back(l);
    }
    return lod;
}

std::filesystem::path temporaryPath(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("sylva_plod_test_" + name + ".plod");
}

TEST(PlodFile, RoundTripsBitExactly) {
    const PlantLod lod = sampleLod();
    const std::vector<std::uint8_t> bytes = encodePlod(lod);
    Result<PlantLod> decoded = decodePlod(bytes, "memory.plod");
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_EQ(encodePlod(*decoded), bytes);
    EXPECT_EQ(decoded->name, "oak");
    ASSERT_EQ(decoded->ellipsoids.size(), 6u);
    EXPECT_EQ(
        std::memcmp(&decoded->ellipsoids[3].center, &lod.ellipsoids[3].center, sizeof(glm::vec3)),
        0);
    EXPECT_TRUE(std::signbit(decoded->ellipsoids[0].center.z));  // −0 survives
    EXPECT_TRUE(std::isinf(decoded->lines[0].errorMaximum));

    const std::filesystem::path path = temporaryPath("roundtrip");
    ASSERT_TRUE(writePlodFile(lod, path.string()).ok());
    PlodFileInfo info;
    Result<PlantLod> read = readPlodFile(path.string(), &info);
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(encodePlod(*read), bytes);
    EXPECT_EQ(info.fileSize, bytes.size());
    for (const PlodSectionInfo& s : info.sections) {
        EXPECT_EQ(s.offset % 64, 0u) << s.tag;
    }
    // No temporary file left behind.
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(path.parent_path())) {
        files += entry.path().filename().string().rfind(path.filename().string() + ".tmp", 0) == 0
                     ? 1
                     : 0;
    }
    EXPECT_EQ(files, 0);
    std::filesystem::remove(path);
}

PlantLod sampleLodWithBillboards() {
    PlantLod lod = sampleLod();
    for (int k = 0; k < 2; ++k) {
        BillboardLevel level;
        level.epsilon = 0.25f * (k + 1);
        level.imageError = 0.004f + 0.001f * k;
        level.atlas.width = 5 - k;
        level.atlas.height = 3;
        for (int i = 0; i < level.atlas.width * level.atlas.height * 4; ++i) {
            level.atlas.rgba.push_back(static_cast<std::uint8_t>(37 * i + k));
        }
        for (int q = 0; q < 3 - k; ++q) {
            BillboardQuad quad;
            for (int c = 0; c < 4; ++c) {
                quad.corners[c] = {0.1f * c, -0.0f, 1.0f / (q + 3)};
                quad.atlasUvs[c] = {0.25f * c, 1.0f / 3.0f};
            }
            quad.normal = {0, 1, 0};
            quad.part = q == 1 ? PlantPart::Branch : PlantPart::Leaf;
            quad.cardboard = q == 2;
            level.quads.push_back(quad);
        }
        lod.billboards.levels.push_back(level);
    }
    return lod;
}

TEST(PlodFile, BillboardCloudsRoundTripBitExactly) {
    const PlantLod lod = sampleLodWithBillboards();
    const std::vector<std::uint8_t> bytes = encodePlod(lod);
    PlodFileInfo info;
    Result<PlantLod> decoded = decodePlod(bytes, "memory.plod", &info);
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_EQ(encodePlod(*decoded), bytes);
    ASSERT_EQ(info.sections.size(), 7u);
    EXPECT_EQ(info.sections[4].tag, "BBCL");
    EXPECT_EQ(info.sections[5].tag, "BBCQ");
    EXPECT_EQ(info.sections[6].tag, "BBCA");
    ASSERT_EQ(decoded->billboards.levels.size(), 2u);
    for (int k = 0; k < 2; ++k) {
        const BillboardLevel& a = lod.billboards.levels[k];
        const BillboardLevel& b = decoded->billboards.levels[k];
        EXPECT_EQ(b.epsilon, a.epsilon);
        EXPECT_EQ(b.imageError, a.imageError);
        EXPECT_EQ(b.atlas.width, a.atlas.width);
        EXPECT_EQ(b.atlas.rgba, a.atlas.rgba);
        EXPECT_EQ(b.byteSize(), a.byteSize());
        ASSERT_EQ(b.quads.size(), a.quads.size());
        for (std::size_t q = 0; q < a.quads.size(); ++q) {
            EXPECT_EQ(
                std::memcmp(b.quads[q].corners, a.quads[q].corners, sizeof a.quads[q].corners), 0);
            EXPECT_EQ(b.quads[q].part, a.quads[q].part);
            EXPECT_EQ(b.quads[q].cardboard, a.quads[q].cardboard);
        }
    }
    // 3 quads × 80 bytes + 5 × 3 × 4 atlas bytes.
    EXPECT_EQ(lod.billboards.levels[0].byteSize(), 3u * 80u + 60u);
    // A file without billboard sections (every file before them) reads with none.
    Result<PlantLod> plain = decodePlod(encodePlod(sampleLod()), "plain.plod");
    ASSERT_TRUE(plain.ok());
    EXPECT_TRUE(plain->billboards.levels.empty());
}

// The vegetation renderer's run keys hold kMaxBillboardLevels levels per species: a file
// with that many reads, one with more fails naming the file and the limit (instead of
// reaching the renderer and overflowing its keys).
TEST(PlodFile, BillboardLevelsAreLimited) {
    ASSERT_EQ(kMaxBillboardLevels, 16u);
    PlantLod lod = sampleLodWithBillboards();
    while (lod.billboards.levels.size() < kMaxBillboardLevels) {
        lod.billboards.levels.push_back(lod.billboards.levels.back());
    }
    const std::filesystem::path path = temporaryPath("sixteen");
    ASSERT_TRUE(writePlodFile(lod, path.string()).ok());
    Result<PlantLod> read = readPlodFile(path.string());
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(read->billboards.levels.size(), 16u);

    lod.billboards.levels.push_back(lod.billboards.levels.back());
    ASSERT_TRUE(writePlodFile(lod, path.string()).ok());
    Result<PlantLod> tooMany = readPlodFile(path.string());
    ASSERT_FALSE(tooMany.ok());
    EXPECT_EQ(tooMany.error().message,
              path.string() + ": 17 billboard levels in section 'BBCL', at most 16 are supported");
    std::filesystem::remove(path);
}

// Re-seals a modified file so the checksum passes and the intended check fires.
void reseal(std::vector<std::uint8_t>& bytes) {
    std::uint64_t hash = 0xcbf29ce484222325ull;
    for (std::size_t i = 64; i < bytes.size(); ++i) {
        hash = (hash ^ bytes[i]) * 0x100000001b3ull;
    }
    for (int i = 0; i < 8; ++i) {
        bytes[56 + i] = static_cast<std::uint8_t>(hash >> (8 * i));
    }
}

std::string decodeError(const std::vector<std::uint8_t>& bytes) {
    Result<PlantLod> result = decodePlod(bytes, "tree.plod");
    return result.ok() ? "(no error)" : result.error().message;
}

TEST(PlodFile, CorruptFilesGiveExactErrors) {
    const std::vector<std::uint8_t> good = encodePlod(sampleLod());

    EXPECT_EQ(decodeError(std::vector<std::uint8_t>(good.begin(), good.begin() + 20)),
              "tree.plod: truncated header (20 bytes, a .plod header has 64)");

    std::vector<std::uint8_t> bytes = good;
    bytes[0] = 'X';
    EXPECT_EQ(decodeError(bytes), "tree.plod: not a .plod file (bad magic; expected \"SYLVPLOD\")");

    bytes = good;
    bytes[8] = 9;
    EXPECT_EQ(decodeError(bytes),
              "tree.plod: unsupported .plod version 9 (this build reads version 1)");

    bytes.assign(good.begin(), good.end() - 10);
    EXPECT_EQ(decodeError(bytes), "tree.plod: truncated or padded: the header says " +
                                      std::to_string(good.size()) + " bytes, the file has " +
                                      std::to_string(good.size() - 10));

    bytes = good;
    bytes[good.size() - 3] ^= 0x40;
    EXPECT_NE(decodeError(bytes).find("tree.plod: checksum mismatch (stored "), std::string::npos);
    EXPECT_NE(decodeError(bytes).find("): the file is corrupt"), std::string::npos);

    // Section table entry 2 (ELLI): element size 100 instead of 112.
    bytes = good;
    const std::size_t elli = 64 + 2 * 32;
    ASSERT_EQ(std::string(bytes.begin() + elli, bytes.begin() + elli + 4), "ELLI");
    bytes[elli + 28] = 100;
    reseal(bytes);
    EXPECT_EQ(decodeError(bytes),
              "tree.plod: section 'ELLI' holds 672 bytes, but 6 elements of 100 bytes need 600");

    // Section past the end.
    bytes = good;
    bytes[elli + 8 + 2] = 0x7f;  // offset += 0x7f0000
    reseal(bytes);
    EXPECT_NE(decodeError(bytes).find("tree.plod: section 'ELLI' ["), std::string::npos);
    EXPECT_NE(decodeError(bytes).find(") runs past the end of the file (" +
                                      std::to_string(good.size()) + " bytes)"),
              std::string::npos);

    // Misaligned section.
    bytes = good;
    bytes[elli + 8] += 4;
    reseal(bytes);
    EXPECT_NE(decodeError(bytes).find("tree.plod: section 'ELLI' offset "), std::string::npos);
    EXPECT_NE(decodeError(bytes).find(" is not 64-byte aligned"), std::string::npos);

    // A level whose ellipsoid count disagrees with the ellipsoid section.
    bytes = good;
    const std::size_t levl = 64 + 1 * 32;
    std::uint64_t levelOffset = 0;
    for (int i = 0; i < 8; ++i) {
        levelOffset |= static_cast<std::uint64_t>(bytes[levl + 8 + i]) << (8 * i);
    }
    bytes[levelOffset + 8] = 4;  // level 0 ellipsoidCount: 3 → 4
    reseal(bytes);
    EXPECT_EQ(decodeError(bytes),
              "tree.plod: level 0 lists 4 ellipsoids, the ellipsoid section has 3");

    // A missing required section (its tag renamed: unknown sections are skipped).
    bytes = good;
    std::memcpy(&bytes[64 + 3 * 32], "XTRA", 4);
    reseal(bytes);
    EXPECT_EQ(decodeError(bytes), "tree.plod: missing section 'LINE'");

    // A billboard level whose atlas runs past BBCA.
    bytes = encodePlod(sampleLodWithBillboards());
    const std::size_t bbcl = 64 + 4 * 32;
    ASSERT_EQ(std::string(bytes.begin() + bbcl, bytes.begin() + bbcl + 4), "BBCL");
    std::uint64_t bbclOffset = 0;
    for (int i = 0; i < 8; ++i) {
        bbclOffset |= static_cast<std::uint64_t>(bytes[bbcl + 8 + i]) << (8 * i);
    }
    bytes[bbclOffset + 32 + 20] = 40;  // level 1 atlas height: 3 → 40
    reseal(bytes);
    EXPECT_EQ(decodeError(bytes),
              "tree.plod: billboard level 1: its 4 x 40 atlas at byte 64 runs past the section "
              "'BBCA' (112 bytes)");

    // Missing file.
    Result<PlantLod> missing = readPlodFile("/nonexistent/tree.plod");
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().message,
              "cannot open /nonexistent/tree.plod: No such file or directory");
}

// The writer and the reader run one field list per record, so a round trip cannot see a
// field moved or dropped on both sides: this pins every field to its offset in the
// tables of docs/formats.md, reading the encoded bytes independently.
class EncodedFile {
public:
    explicit EncodedFile(const PlantLod& lod) : bytes_(encodePlod(lod)) {
        Result<PlantLod> decoded = decodePlod(bytes_, "layout.plod", &info_);
        EXPECT_TRUE(decoded.ok());
    }
    std::uint32_t u32(std::size_t at) const {
        std::uint32_t value = 0;
        for (int i = 0; i < 4; ++i) {
            value |= static_cast<std::uint32_t>(bytes_.at(at + i)) << (8 * i);
        }
        return value;
    }
    std::uint64_t u64(std::size_t at) const { return u32(at) | std::uint64_t{u32(at + 4)} << 32; }
    float f32(std::size_t at) const {
        const std::uint32_t bits = u32(at);
        float value;
        std::memcpy(&value, &bits, 4);
        return value;
    }
    // Byte offset of element `index` of the section `tag`, and its stride.
    std::size_t element(const std::string& tag, std::size_t index, std::uint32_t stride) const {
        for (const PlodSectionInfo& s : info_.sections) {
            if (s.tag == tag) {
                EXPECT_EQ(s.stride, stride) << tag;
                return static_cast<std::size_t>(s.offset) + index * stride;
            }
        }
        ADD_FAILURE() << "no section " << tag;
        return 0;
    }

private:
    std::vector<std::uint8_t> bytes_;
    PlodFileInfo info_;
};

TEST(PlodFile, RecordLayoutsFollowTheFormatDocument) {
    PlantLod lod = sampleLodWithBillboards();
    LodEllipsoid& e = lod.ellipsoids[1];
    e.center = {1.5f, 2.5f, 3.5f};
    e.weight = 4.5f;
    e.axes[0] = {0.0f, 1.0f, 0.0f};
    e.axes[1] = {0.0f, 0.0f, 1.0f};
    e.axes[2] = {1.0f, 0.0f, 0.0f};
    e.radii = {5.5f, 6.5f, 7.5f};
    e.color = {0.125f, 0.25f, 0.375f};
    e.ambientOcclusion = 0.625f;
    e.noiseLevel = 8.5f;
    e.alphaThreshold = 0.875f;
    LodLine& l = lod.lines[2];
    l.start = {1.25f, 2.25f, 3.25f};
    l.startRadius = 0.0625f;
    l.end = {4.25f, 5.25f, 6.25f};
    l.endRadius = 0.03125f;
    l.color = {0.5f, 0.75f, 1.0f};
    l.ambientOcclusion = 0.375f;
    l.weight = 9.5f;
    const EncodedFile file(lod);

    // Header.
    EXPECT_EQ(file.u32(8), 1u);
    EXPECT_EQ(file.u32(12), 64u);
    EXPECT_EQ(file.u32(16), 7u);
    EXPECT_EQ(file.u32(20), 0u);
    EXPECT_EQ(file.f32(32), -1.5f);
    EXPECT_EQ(file.f32(36), -2.0f);
    EXPECT_EQ(file.f32(48), 2.0f);
    EXPECT_EQ(file.f32(52), 7.25f);
    // Section table: tag, version, offset, size, count, stride.
    EXPECT_EQ(file.u32(64 + 32 + 4), 1u);
    const std::size_t levl = file.element("LEVL", 0, 32);
    EXPECT_EQ(file.u64(64 + 32 + 8), levl);
    EXPECT_EQ(file.u64(64 + 32 + 16), 3u * 32u);
    EXPECT_EQ(file.u32(64 + 32 + 24), 3u);
    EXPECT_EQ(file.u32(64 + 32 + 28), 32u);

    // LEVL (level 1 of sampleLod).
    const std::size_t level = file.element("LEVL", 1, 32);
    EXPECT_EQ(file.f32(level + 0), lod.levels[1].errorMinimum);
    EXPECT_EQ(file.f32(level + 4), lod.levels[1].errorMaximum);
    EXPECT_EQ(file.u32(level + 8), 2u);
    EXPECT_EQ(file.u32(level + 12), 4u);
    EXPECT_EQ(file.f32(level + 16), lod.levels[1].imageError);
    EXPECT_EQ(file.f32(level + 20), lod.levels[1].alphaThreshold);
    EXPECT_EQ(file.f32(level + 24), lod.levels[1].primitiveScale);
    EXPECT_EQ(file.u32(level + 28), 0u);

    // ELLI.
    const std::size_t ellipsoid = file.element("ELLI", 1, 112);
    const float expected[] = {1.5f,   2.5f,  3.5f,   4.5f,   0.0f, 1.0f,  0.0f, 5.5f,
                              0.0f,   0.0f,  1.0f,   6.5f,   1.0f, 0.0f,  0.0f, 7.5f,
                              0.125f, 0.25f, 0.375f, 0.625f, 8.5f, 0.875f};
    for (std::size_t i = 0; i < std::size(expected); ++i) {
        EXPECT_EQ(file.f32(ellipsoid + 4 * i), expected[i]) << "ELLI offset " << 4 * i;
    }
    EXPECT_EQ(file.f32(ellipsoid + 88), e.errorMinimum);
    EXPECT_EQ(file.f32(ellipsoid + 92), e.errorMaximum);
    EXPECT_EQ(file.u32(ellipsoid + 96), e.level);
    for (std::size_t at : {100u, 104u, 108u}) {
        EXPECT_EQ(file.u32(ellipsoid + at), 0u);
    }

    // LINE.
    const std::size_t line = file.element("LINE", 2, 64);
    const float lineExpected[] = {1.25f,    2.25f, 3.25f, 0.0625f, 4.25f,  5.25f, 6.25f,
                                  0.03125f, 0.5f,  0.75f, 1.0f,    0.375f, 9.5f};
    for (std::size_t i = 0; i < std::size(lineExpected); ++i) {
        EXPECT_EQ(file.f32(line + 4 * i), lineExpected[i]) << "LINE offset " << 4 * i;
    }
    EXPECT_EQ(file.f32(line + 52), l.errorMinimum);
    EXPECT_EQ(file.f32(line + 56), l.errorMaximum);
    EXPECT_EQ(file.u32(line + 60), 0u);

    // BBCL (level 1: quads 3 … 4, a 4 x 3 atlas after level 0's 60 bytes, aligned).
    const std::size_t bbcl = file.element("BBCL", 1, 32);
    EXPECT_EQ(file.f32(bbcl + 0), lod.billboards.levels[1].epsilon);
    EXPECT_EQ(file.f32(bbcl + 4), lod.billboards.levels[1].imageError);
    EXPECT_EQ(file.u32(bbcl + 8), 3u);
    EXPECT_EQ(file.u32(bbcl + 12), 2u);
    EXPECT_EQ(file.u32(bbcl + 16), 4u);
    EXPECT_EQ(file.u32(bbcl + 20), 3u);
    EXPECT_EQ(file.u64(bbcl + 24), 64u);

    // BBCQ (quad 1 of level 0: a branch, not cardboard; quad 2: cardboard leaves).
    const std::size_t quad = file.element("BBCQ", 1, 96);
    const BillboardQuad& q = lod.billboards.levels[0].quads[1];
    for (int c = 0; c < 4; ++c) {
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(file.f32(quad + 12 * c + 4 * k), q.corners[c][k]);
        }
        EXPECT_EQ(file.f32(quad + 48 + 8 * c), q.atlasUvs[c].x);
        EXPECT_EQ(file.f32(quad + 48 + 8 * c + 4), q.atlasUvs[c].y);
    }
    EXPECT_EQ(file.f32(quad + 80), 0.0f);
    EXPECT_EQ(file.f32(quad + 84), 1.0f);
    EXPECT_EQ(file.f32(quad + 88), 0.0f);
    EXPECT_EQ(file.u32(quad + 92), 1u);
    EXPECT_EQ(file.u32(file.element("BBCQ", 2, 96) + 92), 2u);
}

}  // namespace
}  // namespace sylva
