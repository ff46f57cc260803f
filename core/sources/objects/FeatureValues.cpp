#include "FeatureValues.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace sylva {

FeatureValues::FeatureValues(const FeatureCollection& collection, std::string file)
    : collection_(collection), file_(std::move(file)) {}

Result<std::optional<std::size_t>> FeatureValues::field(const std::string& attribute) const {
    if (attribute.empty()) {
        return std::optional<std::size_t>();
    }
    if (std::optional<std::size_t> index = collection_.field(attribute)) {
        return index;
    }
    std::string names;
    for (const std::string& name : collection_.fields()) {
        names += (names.empty() ? "" : ", ") + name;
    }
    return Error{file_ + ": no attribute '" + attribute +
                 "' (attributes: " + (names.empty() ? "none" : names) + ")"};
}

std::string FeatureValues::where(const Feature& feature) const {
    return file_ + ": feature " + std::to_string(feature.id) + ": ";
}

Result<std::string> FeatureValues::text(const Feature& feature, std::size_t field) const {
    if (field >= feature.attributes.size() ||
        (field < feature.attributeSet.size() && !feature.attributeSet[field])) {
        return Error{where(feature) + "attribute '" + collection_.fields()[field] + "' is missing"};
    }
    return feature.attributes[field];
}

Result<double> FeatureValues::number(const Feature& feature, std::size_t field) const {
    Result<std::string> value = text(feature, field);
    if (!value) {
        return value.error();
    }
    const std::string& s = value.value();
    char* end = nullptr;
    const double number = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(number)) {
        return Error{where(feature) + "attribute '" + collection_.fields()[field] +
                     "' is not a number: '" + s + "'"};
    }
    return number;
}

std::uint32_t FeatureValues::packColor(float r, float g, float b) {
    const auto byte = [](float v) {
        return static_cast<std::uint32_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    };
    return byte(r) | (byte(g) << 8) | (byte(b) << 16) | (255u << 24);
}

std::optional<std::uint32_t> FeatureValues::parseHexColor(const std::string& text) {
    std::string digits = !text.empty() && text[0] == '#' ? text.substr(1) : text;
    if (digits.size() != 6 ||
        digits.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos) {
        return std::nullopt;
    }
    const unsigned long value = std::strtoul(digits.c_str(), nullptr, 16);
    return static_cast<std::uint32_t>(((value >> 16) & 0xff) | (value & 0xff00) |
                                      ((value & 0xff) << 16) | 0xff000000u);
}

}  // namespace sylva
