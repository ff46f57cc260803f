#include "sylva/core/sources/vector/FeatureSource.h"

#include <map>
#include <optional>

#include "sylva/core/base/Hash.h"

namespace sylva {

struct FeatureSource::LoadSlot {
    std::mutex mutex;
    std::optional<Result<std::shared_ptr<const FeatureCollection>>> loaded;
};

namespace {

std::shared_ptr<FeatureSource::LoadSlot> slotFor(std::uint64_t hash) {
    static std::mutex registryMutex;
    static std::map<std::uint64_t, std::weak_ptr<FeatureSource::LoadSlot>> registry;
    const std::lock_guard lock(registryMutex);
    std::weak_ptr<FeatureSource::LoadSlot>& entry = registry[hash];
    std::shared_ptr<FeatureSource::LoadSlot> slot = entry.lock();
    if (!slot) {
        slot = std::make_shared<FeatureSource::LoadSlot>();
        entry = slot;
    }
    return slot;
}

}  // namespace

FeatureSource::FeatureSource(std::string name, std::filesystem::path file,
                             FeatureLoadOptions options)
    : Source(std::move(name), "features", PortType::Features, 0),
      file_(std::move(file)),
      options_(std::move(options)) {
    ContentHash hash;
    hash.add(file_.string())
        .add(options_.layer)
        .add(options_.where)
        .add(static_cast<int>(options_.invalid));
    // The file's size and modification time, so an edited file is a new content.
    std::error_code ec;
    const auto size = std::filesystem::file_size(file_, ec);
    hash.add(static_cast<std::uint64_t>(ec ? 0 : size));
    const auto time = std::filesystem::last_write_time(file_, ec);
    hash.add(static_cast<std::int64_t>(ec ? 0 : time.time_since_epoch().count()));
    setParameterHash(hash.value());
    slot_ = slotFor(contentHash());
}

Result<TilePointer> FeatureSource::produce(const TileKey& key, TileProvider&) const {
    return Error{"source '" + name() + "' gives features, which have no raster tile (" +
                 key.toString() + "); use it through rasterize, elevation_edit or plants"};
}

Result<std::shared_ptr<const FeatureCollection>> FeatureSource::collection() const {
    const std::lock_guard lock(slot_->mutex);
    if (!slot_->loaded) {
        slot_->loaded = FeatureCollection::load(file_.string(), options_);
    }
    return *slot_->loaded;
}

const FeatureSource* FeatureSource::from(const Source* source) {
    if (source == nullptr || source->output() != PortType::Features) {
        return nullptr;
    }
    return dynamic_cast<const FeatureSource*>(source);
}

Result<std::unique_ptr<Source>> FeatureSource::create(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    const std::string file = reader.string("file");
    if (file.empty()) {
        return Error{reader.where("file") + "missing value for 'file'"};
    }
    std::filesystem::path path(file);
    if (path.is_relative()) {
        path = context.projectFolder / path;
    }
    FeatureLoadOptions options;
    options.layer = reader.string("layer");
    options.where = reader.string("where");
    std::string invalid = "error";
    if (const Value* v = reader.value("invalid")) {
        if (const Word* w = v->get<Word>()) {
            invalid = w->text;
        }
    }
    options.invalid = invalid == "skip"     ? FeatureLoadOptions::Invalid::Skip
                      : invalid == "repair" ? FeatureLoadOptions::Invalid::Repair
                                            : FeatureLoadOptions::Invalid::Error;
    return std::unique_ptr<Source>(std::make_unique<FeatureSource>(
        context.block.name, path.lexically_normal(), std::move(options)));
}

}  // namespace sylva
