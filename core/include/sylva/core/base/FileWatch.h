// FileWatch: notices when files that sources read change on disk, by polling stat()
// (size, modification time in nanoseconds, inode; an editor that writes a new file and
// renames it over the old one changes the inode even when size and time agree).
// Polling keeps it portable and free of inotify's limits; a watch of a few files costs
// a few stat calls per poll.
//
// Typical use: after building a SourceGraph, watch every Source::files() entry; poll
// once per frame or second; on a change rebuild the graph (the raster source's content
// hash includes size and modification time, so changed nodes and their dependents get
// new hashes) and call Scheduler::retainOnly with the new graph's hashes.
// Not thread-safe; owned by one thread.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <vector>

namespace sylva {

class FileWatch {
public:
    // Starts watching `file` from its current state (a missing file is a state too:
    // its appearance is reported).
    void watch(const std::filesystem::path& file);
    void clear() { files_.clear(); }
    std::size_t size() const { return files_.size(); }

    // The watched files whose state changed since they were watched or last polled
    // (created, deleted, resized, touched, replaced), in path order.
    std::vector<std::filesystem::path> poll();

private:
    struct FileState {
        bool exists = false;
        std::uintmax_t size = 0;
        std::int64_t modifiedNanoseconds = 0;
        std::uint64_t inode = 0;
        std::uint64_t device = 0;
        friend bool operator==(const FileState&, const FileState&) = default;
    };
    static FileState stateOf(const std::filesystem::path& file);

    std::map<std::filesystem::path, FileState> files_;
};

}  // namespace sylva
