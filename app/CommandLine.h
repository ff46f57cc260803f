// CommandLine: a small, strict parser for `sylva COMMAND [options] [arguments]`.
// Options are `--name value`, `--name=value` or flags; `-D name=value` is collected
// separately. Unknown options are usage errors (exit code 2), never ignored.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/render/gl/GlContext.h"

namespace sylva::app {

struct OptionSpec {
    std::string name;  // without dashes: "out"
    bool takesValue = true;
};

struct ParsedCommandLine {
    std::vector<std::string> positional;
    std::map<std::string, std::string> options;  // flags map to ""
    std::vector<std::pair<std::string, std::string>> defines;
    std::string error;  // non-empty: a usage error

    bool has(const std::string& name) const { return options.count(name) != 0; }
    std::optional<std::string> get(const std::string& name) const {
        auto it = options.find(name);
        return it == options.end() ? std::nullopt : std::optional<std::string>(it->second);
    }
};

// The `--cache-mb N` option (tile cache budget in MiB, 16..1048576): nullopt when absent,
// or an error "--cache-mb expects ..., got 'N'" when N is not such a whole number (a usage
// error, exit code 2).
Result<std::optional<std::size_t>> cacheMegabytesOption(const ParsedCommandLine& command);
// The disk tile cache options of `render`: --disk-cache DIR, --no-disk-cache and
// --disk-cache-mb N (64..1e9) into `options` (the CLI turns the cache on by default);
// an error is a usage error (exit code 2).
Status diskCacheOptions(const ParsedCommandLine& command, bool& disabled,
                        std::optional<std::filesystem::path>& folder,
                        std::optional<std::uint64_t>& megabytes);
// "WIDTHxHEIGHT" within 1..16384 each (--size); false for anything else.
bool parseSize(const std::string& text, int& width, int& height);

// The `--gl B` option of the commands that render: the backend, nullopt when absent, or
// an error "--gl: ..." when B names no backend (a usage error, exit code 2).
Result<std::optional<render::GlBackend>> glBackendOption(const ParsedCommandLine& command);

ParsedCommandLine parseCommandLine(const std::vector<std::string>& arguments,
                                   const std::vector<OptionSpec>& specs);

// A whole-number option `--NAME N` within minimum..maximum (decimal as strtol reads it, the
// whole text; the bounds within int): nullopt when absent, else N, or a usage error (exit
// code 2) saying "--NAME REQUIREMENT", followed by ", got 'N'" with EchoValue::Yes, e.g.
// "--threads needs a positive integer, got 'x'" or "--dem expects a sample count per side
// within 16..8192".
enum class EchoValue { No, Yes };
Result<std::optional<int>> wholeNumberOption(const ParsedCommandLine& command,
                                             const std::string& name, long minimum, long maximum,
                                             const std::string& requirement,
                                             EchoValue echo = EchoValue::Yes);
// `text` as such a whole number, nullopt otherwise (for the items of a list option).
std::optional<int> parseWholeNumber(const std::string& text, long minimum, long maximum);

}  // namespace sylva::app
