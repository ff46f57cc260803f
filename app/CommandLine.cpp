#include "CommandLine.h"

#include <cstdlib>

namespace sylva::app {

ParsedCommandLine parseCommandLine(const std::vector<std::string>& arguments,
                                   const std::vector<OptionSpec>& specs) {
    ParsedCommandLine result;
    for (std::size_t i = 0; i < arguments.size(); ++i) {
        const std::string& argument = arguments[i];
        if (argument == "-D" ||
            (argument.rfind("-D", 0) == 0 && argument.size() > 2 && argument[2] != '-')) {
            std::string definition = argument.size() > 2 ? argument.substr(2) : "";
            if (definition.empty()) {
                if (i + 1 >= arguments.size()) {
                    result.error = "-D needs name=value";
                    return result;
                }
                definition = arguments[++i];
            }
            const std::size_t equals = definition.find('=');
            if (equals == std::string::npos || equals == 0) {
                result.error = "-D needs name=value, got '" + definition + "'";
                return result;
            }
            result.defines.emplace_back(definition.substr(0, equals),
                                        definition.substr(equals + 1));
            continue;
        }
        if (argument.rfind("--", 0) != 0 || argument == "--") {
            result.positional.push_back(argument);
            continue;
        }
        std::string name = argument.substr(2);
        std::optional<std::string> value;
        if (const std::size_t equals = name.find('='); equals != std::string::npos) {
            value = name.substr(equals + 1);
            name = name.substr(0, equals);
        }
        const OptionSpec* spec = nullptr;
        for (const OptionSpec& candidate : specs) {
            if (candidate.name == name) {
                spec = &candidate;
            }
        }
        if (spec == nullptr) {
            result.error = "unknown option '--" + name + "'";
            return result;
        }
        if (spec->takesValue && !value) {
            if (i + 1 >= arguments.size()) {
                result.error = "option '--" + name + "' needs a value";
                return result;
            }
            value = arguments[++i];
        }
        if (!spec->takesValue && value) {
            result.error = "option '--" + name + "' takes no value";
            return result;
        }
        result.options[name] = value.value_or("");
    }
    return result;
}

Result<std::optional<std::size_t>> cacheMegabytesOption(const ParsedCommandLine& command) {
    const std::optional<std::string> text = command.get("cache-mb");
    if (!text) {
        return std::optional<std::size_t>();
    }
    const Error error{"--cache-mb expects a tile cache budget in MiB within 16..1048576, got '" +
                      *text + "'"};
    if (text->empty() || text->size() > 7 ||
        text->find_first_not_of("0123456789") != std::string::npos) {
        return error;
    }
    const std::size_t value = std::stoul(*text);
    if (value < 16 || value > (1u << 20)) {
        return error;
    }
    return std::optional<std::size_t>(value);
}

Status diskCacheOptions(const ParsedCommandLine& command, bool& disabled,
                        std::optional<std::filesystem::path>& folder,
                        std::optional<std::uint64_t>& megabytes) {
    disabled = command.has("no-disk-cache");
    if (std::optional<std::string> text = command.get("disk-cache")) {
        if (disabled) {
            return Error{"--disk-cache and --no-disk-cache exclude each other"};
        }
        if (text->empty()) {
            return Error{"--disk-cache expects a folder"};
        }
        folder = std::filesystem::path(*text);
    }
    if (std::optional<std::string> text = command.get("disk-cache-mb")) {
        const Error error{
            "--disk-cache-mb expects a disk tile cache budget in MiB within 64..1000000000, "
            "got '" +
            *text + "'"};
        if (text->empty() || text->size() > 10 ||
            text->find_first_not_of("0123456789") != std::string::npos) {
            return error;
        }
        const std::uint64_t value = std::stoull(*text);
        if (value < 64 || value > 1000000000ull) {
            return error;
        }
        megabytes = value;
    }
    return {};
}

bool parseSize(const std::string& text, int& width, int& height) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') ||
        w < 1 || h < 1 || w > 16384 || h > 16384) {
        return false;
    }
    width = w;
    height = h;
    return true;
}

Result<std::optional<render::GlBackend>> glBackendOption(const ParsedCommandLine& command) {
    const std::optional<std::string> value = command.get("gl");
    if (!value) {
        return std::optional<render::GlBackend>();
    }
    Result<render::GlBackend> backend = render::parseBackend(*value);
    if (!backend) {
        return Error{"--gl: " + backend.error().message};
    }
    return std::optional<render::GlBackend>(backend.value());
}

std::optional<int> parseWholeNumber(const std::string& text, long minimum, long maximum) {
    SYLVA_CHECK(static_cast<int>(minimum) == minimum && static_cast<int>(maximum) == maximum);
    // Out of long's range strtol gives LONG_MIN or LONG_MAX, outside every int range.
    char* end = nullptr;
    const long value = std::strtol(text.c_str(), &end, 10);
    if (end == text.c_str() || *end != '\0' || value < minimum || value > maximum) {
        return std::nullopt;
    }
    return static_cast<int>(value);
}

Result<std::optional<int>> wholeNumberOption(const ParsedCommandLine& command,
                                             const std::string& name, long minimum, long maximum,
                                             const std::string& requirement, EchoValue echo) {
    const std::optional<std::string> text = command.get(name);
    if (!text) {
        return std::optional<int>();
    }
    const std::optional<int> value = parseWholeNumber(*text, minimum, maximum);
    if (!value) {
        std::string message = "--" + name + " " + requirement;
        if (echo == EchoValue::Yes) {
            message += ", got '" + *text + "'";
        }
        return Error{message};
    }
    return std::optional<int>(*value);
}

}  // namespace sylva::app
