#include "GltfSkeleton.h"

#include <string>

#include "ImportedPlant.h"

namespace sylva::plantimport {

namespace {

using Json = nlohmann::json;

// [x, y, z] in the file frame → model frame.
bool readPoint(const Json& value, glm::vec3& out) {
    if (!value.is_array() || value.size() != 3) {
        return false;
    }
    for (std::size_t i = 0; i < 3; ++i) {
        if (!value[i].is_number()) {
            return false;
        }
        out[int(i)] = value[i].get<float>();
    }
    out = toModelFrame(out);
    return true;
}

Result<SkeletonSegment> readSegment(const std::filesystem::path& path, const Json& entry,
                                    const std::string& at, std::size_t index, std::size_t count) {
    SkeletonSegment segment;
    if (!entry.is_object() || !readPoint(entry.value("start", Json()), segment.start) ||
        !readPoint(entry.value("end", Json()), segment.end)) {
        return Error{path.string() + ": " + at + ": needs start and end as [x, y, z]"};
    }
    const Json startRadius = entry.value("startRadius", Json());
    const Json endRadius = entry.value("endRadius", Json());
    if (!startRadius.is_number() || !endRadius.is_number() || startRadius.get<double>() < 0.0 ||
        endRadius.get<double>() < 0.0) {
        return Error{path.string() + ": " + at +
                     ": startRadius and endRadius must be numbers >= 0"};
    }
    segment.startRadius = startRadius.get<float>();
    segment.endRadius = endRadius.get<float>();
    const Json parent = entry.value("parent", Json(-1));
    if (!parent.is_number_integer() || parent.get<long long>() < -1 ||
        parent.get<long long>() >= (long long)(count) ||
        parent.get<long long>() == (long long)(index)) {
        return Error{path.string() + ": " + at +
                     ".parent: must be -1 or the index of another segment"};
    }
    segment.parent = parent.get<int>();
    return segment;
}

Result<std::vector<SkeletonSegment>> readSegments(const std::filesystem::path& path,
                                                  const Json& list, const std::string& where) {
    if (!list.is_array()) {
        return Error{path.string() + ": " + where + ": must be an array of segments"};
    }
    std::vector<SkeletonSegment> skeleton;
    for (std::size_t i = 0; i < list.size(); ++i) {
        Result<SkeletonSegment> segment =
            readSegment(path, list[i], where + "[" + std::to_string(i) + "]", i, list.size());
        if (!segment) {
            return segment.error();
        }
        skeleton.push_back(*segment);
    }
    // Parents must form a forest: walking up from any segment ends at a root.
    for (std::size_t i = 0; i < skeleton.size(); ++i) {
        int current = int(i);
        for (std::size_t steps = 0; current >= 0; ++steps) {
            if (steps > skeleton.size()) {
                return Error{path.string() + ": " + where +
                             ": the parents form a cycle through segment " + std::to_string(i)};
            }
            current = skeleton[std::size_t(current)].parent;
        }
    }
    return skeleton;
}

}  // namespace

Result<std::vector<SkeletonSegment>> readGltfSkeleton(const std::filesystem::path& path,
                                                      const Json& json,
                                                      const std::vector<int>& roots) {
    const Json& asset = json["asset"];
    if (asset.contains("extras") && asset["extras"].is_object() &&
        asset["extras"].contains("sylva_skeleton")) {
        return readSegments(path, asset["extras"]["sylva_skeleton"], "asset.extras.sylva_skeleton");
    }
    if (!roots.empty() && json.contains("nodes") && json["nodes"].is_array() &&
        std::size_t(roots.front()) < json["nodes"].size()) {
        const Json& root = json["nodes"][std::size_t(roots.front())];
        if (root.is_object() && root.contains("extras") && root["extras"].is_object() &&
            root["extras"].contains("sylva_skeleton")) {
            return readSegments(
                path, root["extras"]["sylva_skeleton"],
                "nodes[" + std::to_string(roots.front()) + "].extras.sylva_skeleton");
        }
    }
    return std::vector<SkeletonSegment>{};
}

}  // namespace sylva::plantimport
