#include "sylva/dsl/SourceFiles.h"

#include <utility>

namespace sylva::dsl {

std::shared_ptr<const std::string> SourceFiles::add(std::string displayName, std::string text) {
    auto file = std::make_unique<File>();
    file->name = std::make_shared<const std::string>(std::move(displayName));
    file->text = std::move(text);
    file->lineStarts.push_back(0);
    for (std::size_t i = 0; i < file->text.size(); ++i) {
        if (file->text[i] == '\n') {
            file->lineStarts.push_back(i + 1);
        }
    }
    files_.push_back(std::move(file));
    return files_.back()->name;
}

const SourceFiles::File* SourceFiles::find(const std::shared_ptr<const std::string>& file) const {
    for (const auto& candidate : files_) {
        if (candidate->name == file) {
            return candidate.get();
        }
    }
    return nullptr;
}

std::string_view SourceFiles::text(const std::shared_ptr<const std::string>& file) const {
    const File* found = find(file);
    return found ? std::string_view(found->text) : std::string_view();
}

std::string_view SourceFiles::line(const std::shared_ptr<const std::string>& file,
                                   std::uint32_t line) const {
    const File* found = find(file);
    if (!found || line == 0 || line > found->lineStarts.size()) {
        return {};
    }
    std::size_t begin = found->lineStarts[line - 1];
    std::size_t end =
        line < found->lineStarts.size() ? found->lineStarts[line] - 1 : found->text.size();
    std::string_view result(found->text.data() + begin, end - begin);
    if (!result.empty() && result.back() == '\r') {
        result.remove_suffix(1);
    }
    return result;
}

std::size_t SourceFiles::index(const std::shared_ptr<const std::string>& file) const {
    for (std::size_t i = 0; i < files_.size(); ++i) {
        if (files_[i]->name == file) {
            return i;
        }
    }
    return files_.size();
}

}  // namespace sylva::dsl
