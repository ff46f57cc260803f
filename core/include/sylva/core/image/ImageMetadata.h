// ImageMetadata: name/value text attributes stored in written images (PNG text chunks,
// EXR string attributes) so an image says where it came from: camera or path frame,
// scenario, time, project file and content hash, Sylva version. Names follow OIIO's
// "prefix:name" convention ("sylva:camera").
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace sylva {

struct ImageMetadata {
    std::vector<std::pair<std::string, std::string>> attributes;

    void set(std::string name, std::string value) {
        for (auto& [existing, text] : attributes) {
            if (existing == name) {
                text = std::move(value);
                return;
            }
        }
        attributes.emplace_back(std::move(name), std::move(value));
    }
    const std::string* find(const std::string& name) const {
        for (const auto& [existing, text] : attributes) {
            if (existing == name) {
                return &text;
            }
        }
        return nullptr;
    }
};

}  // namespace sylva
