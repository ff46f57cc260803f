// FeatureValues: reading per-feature numbers, words and colours from the attributes a
// buildings or objects source names, with the located messages of MeshSource:
// "<file>: no attribute 'h' (attributes: a, b)", "<file>: feature 7: attribute 'h' is
// missing", "... is not a number: 'tall'".
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/core/sources/vector/FeatureCollection.h"

namespace sylva {

class FeatureValues {
public:
    FeatureValues(const FeatureCollection& collection, std::string file);

    // The field index of `attribute`; nullopt when `attribute` is empty; an error when the
    // collection has no such field.
    Result<std::optional<std::size_t>> field(const std::string& attribute) const;

    // "<file>: feature <id>: " for messages about one feature.
    std::string where(const Feature& feature) const;

    // The attribute as a finite number; errors when unset or not a number.
    Result<double> number(const Feature& feature, std::size_t field) const;
    // The attribute as text; an error when unset.
    Result<std::string> text(const Feature& feature, std::size_t field) const;

    // Packs sRGB components in [0, 1] as RGBA8 (r in the low byte, alpha 255).
    static std::uint32_t packColor(float r, float g, float b);
    // "#rrggbb" or "rrggbb" as packed sRGB8; nullopt when malformed.
    static std::optional<std::uint32_t> parseHexColor(const std::string& text);

private:
    const FeatureCollection& collection_;
    std::string file_;
};

}  // namespace sylva
