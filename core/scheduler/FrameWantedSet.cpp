#include "sylva/core/scheduler/FrameWantedSet.h"

#include <algorithm>

namespace sylva {

TileLookup FrameWantedSet::tryGet(const Source& source, const TileKey& key, int priority) {
    TileLookup lookup = provider_.tryGet(source, key, priority);
    if (lookup.state == TileLookup::State::Pending) {
        add({&source, key, priority});
    }
    return lookup;
}

void FrameWantedSet::setWanted(const std::vector<TileRequest>& wanted) {
    for (const TileRequest& request : wanted) {
        add(request);
    }
}

void FrameWantedSet::add(const TileRequest& request) {
    SYLVA_CHECK(request.source != nullptr && request.key.valid());
    const auto id = std::make_pair(request.source->contentHash(), request.key);
    auto [it, inserted] = wanted_.try_emplace(id, request, wanted_.size());
    if (!inserted && request.priority < it->second.first.priority) {
        it->second.first.priority = request.priority;
    }
}

std::vector<TileRequest> FrameWantedSet::requests() const {
    std::vector<std::pair<TileRequest, std::size_t>> ordered;
    ordered.reserve(wanted_.size());
    for (const auto& [id, entry] : wanted_) {
        ordered.push_back(entry);
    }
    std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) {
        return a.first.priority != b.first.priority ? a.first.priority < b.first.priority
                                                    : a.second < b.second;
    });
    std::vector<TileRequest> out;
    out.reserve(ordered.size());
    for (const auto& entry : ordered) {
        out.push_back(entry.first);
    }
    return out;
}

void FrameWantedSet::flush() {
    provider_.setWanted(requests());
    wanted_.clear();
}

}  // namespace sylva
