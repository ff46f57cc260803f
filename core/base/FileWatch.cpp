#include "sylva/core/base/FileWatch.h"

#include <sys/stat.h>

namespace sylva {

FileWatch::FileState FileWatch::stateOf(const std::filesystem::path& file) {
    struct stat info {};
    if (::stat(file.c_str(), &info) != 0) {
        return {};
    }
    FileState state;
    state.exists = true;
    state.size = static_cast<std::uintmax_t>(info.st_size);
    state.modifiedNanoseconds = static_cast<std::int64_t>(info.st_mtim.tv_sec) * 1000000000 +
                                static_cast<std::int64_t>(info.st_mtim.tv_nsec);
    state.inode = static_cast<std::uint64_t>(info.st_ino);
    state.device = static_cast<std::uint64_t>(info.st_dev);
    return state;
}

void FileWatch::watch(const std::filesystem::path& file) {
    files_[file] = stateOf(file);
}

std::vector<std::filesystem::path> FileWatch::poll() {
    std::vector<std::filesystem::path> changed;
    for (auto& [file, state] : files_) {
        const FileState now = stateOf(file);
        if (!(now == state)) {
            changed.push_back(file);
            state = now;
        }
    }
    return changed;
}

}  // namespace sylva
