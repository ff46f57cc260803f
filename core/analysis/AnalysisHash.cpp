#include "sylva/core/analysis/AnalysisHash.h"

#include <filesystem>
#include <set>
#include <string>

#include "sylva/core/base/Hash.h"

namespace sylva {

namespace {

class FileStamps {
public:
    FileStamps(const ProjectModel& model, ContentHash& hash) : model_(model), hash_(hash) {}

    // Every source `value` references, and the files they read, into the hash.
    void visit(const Value& value) {
        if (const Reference* reference = value.get<Reference>()) {
            if (reference->kind == "source")
                visitSource(reference->name);
        } else if (const ValueList* list = value.get<ValueList>()) {
            for (const Value& item : *list)
                visit(item);
        } else if (const ValueObject* object = value.get<ValueObject>()) {
            for (const auto& [key, field] : *object)
                visit(field);
        }
    }

private:
    void visitSource(const std::string& name) {
        const Block* source = model_.findSource(name);
        if (source == nullptr || !visited_.insert(name).second)
            return;
        for (const Attribute& attribute : source->attributes) {
            const std::string* text = attribute.value.get<std::string>();
            if (text != nullptr &&
                (attribute.name == "file" || attribute.name == "model" || attribute.name == "lod"))
                stamp(*text);
            visit(attribute.value);
        }
    }

    void stamp(const std::string& file) {
        std::filesystem::path path(file);
        if (!path.is_absolute() && model_.file.has_parent_path())
            path = model_.file.parent_path() / path;
        std::error_code error;
        const auto size = std::filesystem::file_size(path, error);
        const auto time = std::filesystem::last_write_time(path, error);
        hash_.add(path.lexically_normal().string());
        hash_.add(std::uint64_t(error ? 0 : size));
        hash_.add(std::int64_t(error ? 0 : time.time_since_epoch().count()));
    }

    const ProjectModel& model_;
    ContentHash& hash_;
    std::set<std::string> visited_;
};

}  // namespace

std::uint64_t analysisHash(const ProjectModel& model, const Block& block) {
    ContentHash hash;
    hash.add(kAnalysisVersion);
    hash.add(block.keyword);
    hash.add(block.name);
    hash.add(block.contentHash);
    FileStamps stamps(model, hash);
    for (const Attribute& attribute : block.attributes)
        stamps.visit(attribute.value);
    return hash.value();
}

}  // namespace sylva
