#include "sylva/core/sources/plants/InstanceTileCodec.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "sylva/core/base/Check.h"

namespace sylva {

namespace {

void putDouble(float* texel, double value) {
    const auto bits = std::bit_cast<std::uint64_t>(value);
    const std::uint32_t words[2] = {std::uint32_t(bits), std::uint32_t(bits >> 32)};
    std::memcpy(texel, words, sizeof words);
}

double getDouble(const float* texel) {
    std::uint32_t words[2];
    std::memcpy(words, texel, sizeof words);
    return std::bit_cast<double>(std::uint64_t(words[0]) | (std::uint64_t(words[1]) << 32));
}

}  // namespace

ImageTile InstanceTileCodec::encode(const TileKey& key,
                                    const std::vector<PlantInstance>& instances) {
    SYLVA_CHECK(instances.size() < kMaximumInstances);
    const int size = std::max(1, int(std::ceil(std::sqrt(double(3 * instances.size() + 1)))));
    ImageTile tile(key, size, 0, kChannels);
    float* texels = tile.texels().data();
    texels[0] = float(instances.size());
    for (std::size_t i = 0; i < instances.size(); ++i) {
        const PlantInstance& instance = instances[i];
        float* texel = texels + kChannels + i * kFloatsPerInstance;
        putDouble(texel + 0, instance.longitude);
        putDouble(texel + 2, instance.latitude);
        putDouble(texel + 4, instance.height);
        std::memcpy(texel + 6, &instance.species, sizeof instance.species);
        texel[7] = instance.scale;
        texel[8] = instance.rotation;
        texel[9] = instance.tint.r;
        texel[10] = instance.tint.g;
        texel[11] = instance.tint.b;
    }
    return tile;
}

Result<std::vector<PlantInstance>> InstanceTileCodec::decode(const ImageTile& tile) {
    const std::size_t texelCount = std::size_t(tile.stride()) * tile.stride();
    if (tile.channels() != kChannels || tile.border() != 0 ||
        tile.texels().size() != texelCount * kChannels) {
        return Error{"tile " + tile.key().toString() + " does not hold plant instances"};
    }
    const float* texels = tile.texels().data();
    const float count = texels[0];
    if (!(count >= 0.0f) || !(count < float(kMaximumInstances)) ||
        3 * std::size_t(count) + 1 > texelCount || float(std::size_t(count)) != count) {
        return Error{"tile " + tile.key().toString() + " has a corrupt instance count"};
    }
    std::vector<PlantInstance> instances(static_cast<std::size_t>(count));
    for (std::size_t i = 0; i < instances.size(); ++i) {
        const float* texel = texels + kChannels + i * kFloatsPerInstance;
        PlantInstance& instance = instances[i];
        instance.longitude = getDouble(texel + 0);
        instance.latitude = getDouble(texel + 2);
        instance.height = getDouble(texel + 4);
        std::memcpy(&instance.species, texel + 6, sizeof instance.species);
        instance.scale = texel[7];
        instance.rotation = texel[8];
        instance.tint = glm::vec3(texel[9], texel[10], texel[11]);
    }
    return instances;
}

}  // namespace sylva
