// Plant instances carried in an ImageTile (InstanceTileCodec): bit-exact round trip,
// empty tiles, and a clear error for a tile of another layout.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

#include "sylva/core/sources/plants/InstanceTileCodec.h"

namespace sylva {
namespace {

TEST(InstanceTileCodec, RoundTripIsBitExact) {
    std::vector<PlantInstance> instances;
    for (int i = 0; i < 1000; ++i) {
        PlantInstance p;
        p.longitude = -0.6 + i * 1.234567890123e-7 + std::nextafter(0.0, 1.0);
        p.latitude = 0.139626340159546 + i * 3.3e-9;
        p.height = 12.345678901234 * i;
        p.species = std::uint32_t(i % 7);
        p.scale = 0.8f + float(i) * 1e-4f;
        p.rotation = float(i) * 0.01f;
        p.tint = glm::vec3(0.9f, 1.0f, 1.1f) * (1.0f + float(i) * 1e-5f);
        instances.push_back(p);
    }
    // Words that are NaN patterns as floats must survive too.
    instances[3].longitude = std::bit_cast<double>(std::uint64_t(0x3FF7FFFFFFFFFFFFull));
    const TileKey key{14, 0, 100, 200};
    const ImageTile tile = InstanceTileCodec::encode(key, instances);
    Result<std::vector<PlantInstance>> decoded = InstanceTileCodec::decode(tile);
    ASSERT_TRUE(decoded) << decoded.error().message;
    ASSERT_EQ(decoded.value().size(), instances.size());
    for (std::size_t i = 0; i < instances.size(); ++i) {
        const PlantInstance& a = instances[i];
        const PlantInstance& b = decoded.value()[i];
        EXPECT_EQ(std::bit_cast<std::uint64_t>(a.longitude),
                  std::bit_cast<std::uint64_t>(b.longitude));
        EXPECT_EQ(std::bit_cast<std::uint64_t>(a.latitude),
                  std::bit_cast<std::uint64_t>(b.latitude));
        EXPECT_EQ(std::bit_cast<std::uint64_t>(a.height), std::bit_cast<std::uint64_t>(b.height));
        EXPECT_EQ(a.species, b.species);
        EXPECT_EQ(a.scale, b.scale);
        EXPECT_EQ(a.rotation, b.rotation);
        EXPECT_EQ(a.tint, b.tint);
    }
    // The cache budget sees the bytes: one texel per instance plus the count.
    EXPECT_GE(tile.bytes(),
              (instances.size() * InstanceTileCodec::kFloatsPerInstance + 4) * sizeof(float));
}

TEST(InstanceTileCodec, EmptyTileAndForeignLayout) {
    const TileKey key{12, 0, 5, 6};
    Result<std::vector<PlantInstance>> empty =
        InstanceTileCodec::decode(InstanceTileCodec::encode(key, {}));
    ASSERT_TRUE(empty);
    EXPECT_TRUE(empty.value().empty());
    const ImageTile colour(key, 8, 2, 3);
    Result<std::vector<PlantInstance>> foreign = InstanceTileCodec::decode(colour);
    ASSERT_FALSE(foreign);
    EXPECT_EQ(foreign.error().message, "tile L12/k0/x5/y6 does not hold plant instances");
    ImageTile corrupt = InstanceTileCodec::encode(key, {});
    corrupt.texels()[0] = 1e9f;
    Result<std::vector<PlantInstance>> bad = InstanceTileCodec::decode(corrupt);
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().message, "tile L12/k0/x5/y6 has a corrupt instance count");
}

}  // namespace
}  // namespace sylva
