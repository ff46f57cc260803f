// `sylva cache stats|prune|clear [--disk-cache DIR] [--budget-mb N] [--json]`: the disk
// tile cache's maintenance. The folder is --disk-cache, else DiskTileCache::defaultFolder()
// ($SYLVA_CACHE_DIR/tiles ...); a project's render { disk_cache } is not read here, so
// name that folder with --disk-cache. `prune` removes least recently used entries down to
// --budget-mb (default 16384, the render block's default), entries of other format
// versions and temporary files older than an hour; `clear` removes every entry. Other
// processes may read and write the folder meanwhile (entries are replaced atomically).
// Exit codes: 0 done, 1 the folder cannot be read or an entry not removed, 2 usage.
#include <cstdio>
#include <string>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/core/tiles/DiskTileCache.h"

namespace sylva::app {
namespace {

void printUsage() {
    std::puts(
        "usage: sylva cache stats|prune|clear [--disk-cache DIR] [--budget-mb N] [--json]\n"
        "The disk tile cache folder: --disk-cache, else $SYLVA_CACHE_DIR/tiles, else\n"
        "$XDG_CACHE_HOME/sylva/tiles, else ~/.cache/sylva/tiles.");
}

std::string jsonPath(const std::filesystem::path& path) {
    std::string out = "\"";
    for (char c : path.string()) {
        if (c == '"' || c == '\\') {
            out += '\\';
        }
        out += c;
    }
    return out + "\"";
}

int printStats(const std::filesystem::path& folder, bool json) {
    Result<DiskTileCacheUsage> usage = DiskTileCache::scan(folder);
    if (!usage) {
        reportError(usage.error().message);
        return 1;
    }
    const DiskTileCacheUsage& u = usage.value();
    if (json) {
        std::printf(
            "{\"folder\": %s, \"format_version\": %u, \"entries\": %llu, \"bytes\": %llu, "
            "\"sources\": %llu, \"other_version_entries\": %llu, \"other_version_bytes\": %llu, "
            "\"temporary_files\": %llu}\n",
            jsonPath(folder).c_str(), DiskTileCache::kFormatVersion,
            static_cast<unsigned long long>(u.entries), static_cast<unsigned long long>(u.bytes),
            static_cast<unsigned long long>(u.sources),
            static_cast<unsigned long long>(u.otherVersionEntries),
            static_cast<unsigned long long>(u.otherVersionBytes),
            static_cast<unsigned long long>(u.temporaryFiles));
    } else {
        std::printf("%s: %llu tiles of %llu sources, %.1f MiB (format version %u)\n",
                    folder.string().c_str(), static_cast<unsigned long long>(u.entries),
                    static_cast<unsigned long long>(u.sources),
                    static_cast<double>(u.bytes) / (1 << 20), DiskTileCache::kFormatVersion);
        if (u.otherVersionEntries > 0 || u.temporaryFiles > 0) {
            std::printf(
                "  also %llu entries of other format versions (%.1f MiB) and %llu "
                "temporary files; `sylva cache prune` removes them\n",
                static_cast<unsigned long long>(u.otherVersionEntries),
                static_cast<double>(u.otherVersionBytes) / (1 << 20),
                static_cast<unsigned long long>(u.temporaryFiles));
        }
    }
    return 0;
}

int printRemoval(const Result<DiskTileCachePruneReport>& report,
                 const std::filesystem::path& folder, bool json) {
    if (!report) {
        reportError(report.error().message);
        return 1;
    }
    const DiskTileCachePruneReport& r = report.value();
    if (json) {
        std::printf(
            "{\"folder\": %s, \"removed_entries\": %llu, \"removed_bytes\": %llu, "
            "\"kept_entries\": %llu, \"kept_bytes\": %llu}\n",
            jsonPath(folder).c_str(), static_cast<unsigned long long>(r.removedEntries),
            static_cast<unsigned long long>(r.removedBytes),
            static_cast<unsigned long long>(r.keptEntries),
            static_cast<unsigned long long>(r.keptBytes));
    } else {
        std::printf("%s: removed %llu files (%.1f MiB), kept %llu tiles (%.1f MiB)\n",
                    folder.string().c_str(), static_cast<unsigned long long>(r.removedEntries),
                    static_cast<double>(r.removedBytes) / (1 << 20),
                    static_cast<unsigned long long>(r.keptEntries),
                    static_cast<double>(r.keptBytes) / (1 << 20));
    }
    return 0;
}

}  // namespace

int runCache(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(
        arguments, {{"disk-cache"}, {"budget-mb"}, {"json", false}, {"help", false}});
    if (command.has("help")) {
        printUsage();
        return 0;
    }
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty()
                        ? "cache needs one of stats, prune, clear (see 'sylva cache --help')"
                        : command.error);
        return 2;
    }
    const std::string action = command.positional[0];
    bool disabled = false;
    std::optional<std::filesystem::path> folder;
    std::optional<std::uint64_t> budget;
    ParsedCommandLine diskOptions = command;
    if (std::optional<std::string> text = command.get("budget-mb")) {
        diskOptions.options["disk-cache-mb"] = *text;
    }
    if (Status parsed = diskCacheOptions(diskOptions, disabled, folder, budget); !parsed) {
        reportError(parsed.error().message);
        return 2;
    }
    const std::filesystem::path where = folder.value_or(DiskTileCache::defaultFolder());
    const bool json = command.has("json");
    if (action == "stats") {
        return printStats(where, json);
    }
    if (action == "prune") {
        return printRemoval(DiskTileCache::prune(where, budget.value_or(16384) << 20), where, json);
    }
    if (action == "clear") {
        return printRemoval(DiskTileCache::clear(where), where, json);
    }
    reportError("cache expects stats, prune or clear, got '" + action + "'");
    return 2;
}

}  // namespace sylva::app
