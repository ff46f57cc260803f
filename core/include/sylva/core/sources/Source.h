// Source: a node of the source graph (seed 001 §4.4). A source has a kind, typed
// inputs, parameters and a content hash, and produces image tiles of the
// longitude/latitude pyramid as a pure function of (TileKey, input tiles).
//
// Sources never cache: a TileProvider (the TileEvaluator or the Scheduler)
// owns the caches and hands input tiles to produce(). Errors in data (an unreadable
// file, a failed input) come back as Result errors that name the source; they never
// abort the process.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/model/Schema.h"
#include "sylva/core/tiles/ImageTile.h"
#include "sylva/core/tiles/TileKey.h"
#include "sylva/core/tiles/TileProvider.h"

namespace sylva {

class Source {
public:
    Source(std::string name, std::string kind, PortType output, int channels);
    virtual ~Source();
    Source(const Source&) = delete;
    Source& operator=(const Source&) = delete;

    const std::string& name() const { return name_; }
    const std::string& kind() const { return kind_; }
    PortType output() const { return output_; }
    int channels() const { return channels_; }
    const std::vector<const Source*>& inputs() const { return inputs_; }

    // Hash of kind, parameters and the content hashes of all inputs: equal hashes
    // mean equal tiles, which is what caches and scenarios share on.
    std::uint64_t contentHash() const { return contentHash_; }

    // Produces the tile for `key` (interior and border). Called by TileProviders only.
    virtual Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const = 0;

    // The files this source itself reads (not its inputs'), for FileWatch: when one
    // changes on disk the owner rebuilds the graph (the source's hash then changes).
    virtual std::vector<std::filesystem::path> files() const { return {}; }

protected:
    // Subclasses call these from their constructor: inputs in a fixed order, then
    // the hash of their own parameters.
    void addInput(const Source* input);
    void setParameterHash(std::uint64_t parameterHash);

private:
    std::string name_;
    std::string kind_;
    PortType output_;
    int channels_;
    std::vector<const Source*> inputs_;
    std::uint64_t contentHash_ = 0;
};

}  // namespace sylva
