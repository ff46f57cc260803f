#include "sylva/core/scene/ViewerScript.h"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>

#include "sylva/core/scene/DateTime.h"

namespace sylva {
namespace {

// What a command takes: the argument count range and how the arguments are read.
enum class Arguments { Words, Numbers, Paths, Edit };

struct CommandSpec {
    ScriptCommandKind kind;
    const char* name;
    int minimum;
    int maximum;
    Arguments arguments;
};

constexpr std::array<CommandSpec, 16> kCommands{{
    {ScriptCommandKind::Camera, "camera", 1, 1, Arguments::Words},
    {ScriptCommandKind::Scenario, "scenario", 1, 1, Arguments::Words},
    {ScriptCommandKind::Time, "time", 1, 1, Arguments::Words},
    {ScriptCommandKind::Mode, "mode", 1, 1, Arguments::Words},
    {ScriptCommandKind::Fly, "fly", 3, 3, Arguments::Numbers},
    {ScriptCommandKind::Turn, "turn", 2, 2, Arguments::Numbers},
    {ScriptCommandKind::Orbit, "orbit", 2, 2, Arguments::Numbers},
    {ScriptCommandKind::WaitTiles, "wait-tiles", 0, 0, Arguments::Words},
    {ScriptCommandKind::Frames, "frames", 1, 1, Arguments::Numbers},
    {ScriptCommandKind::Screenshot, "screenshot", 1, 1, Arguments::Paths},
    {ScriptCommandKind::SaveCamera, "save-camera", 1, 2, Arguments::Words},
    {ScriptCommandKind::Edit, "edit", 3, 3, Arguments::Edit},
    {ScriptCommandKind::Touch, "touch", 1, 1, Arguments::Paths},
    {ScriptCommandKind::Compare, "compare", 1, 3, Arguments::Words},
    {ScriptCommandKind::Layer, "layer", 2, 2, Arguments::Words},
    {ScriptCommandKind::Quit, "quit", 0, 0, Arguments::Words},
}};

struct Word {
    std::string text;
    std::uint32_t column = 0;  // 1-based
};

// Splits one line into words (quotes and escapes resolved); stops at an unquoted '#'.
// Fails with the column of an unterminated quote.
Result<std::vector<Word>> splitLine(std::string_view line, std::uint32_t& errorColumn) {
    std::vector<Word> words;
    std::size_t i = 0;
    while (i < line.size()) {
        const char c = line[i];
        if (c == ' ' || c == '\t' || c == '\r') {
            ++i;
            continue;
        }
        if (c == '#') {
            break;
        }
        Word word;
        word.column = static_cast<std::uint32_t>(i + 1);
        if (c == '"') {
            ++i;
            bool closed = false;
            while (i < line.size()) {
                if (line[i] == '\\' && i + 1 < line.size()) {
                    word.text += line[i + 1];
                    i += 2;
                } else if (line[i] == '"') {
                    closed = true;
                    ++i;
                    break;
                } else {
                    word.text += line[i++];
                }
            }
            if (!closed) {
                errorColumn = word.column;
                return Error{"unterminated quoted argument"};
            }
        } else {
            while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') {
                word.text += line[i++];
            }
        }
        words.push_back(std::move(word));
    }
    return words;
}

// "'name'" built by appends (GCC 12 warns falsely on "'" + std::string + ... chains).
std::string singleQuoted(std::string_view name) {
    std::string text;
    text.reserve(name.size() + 2);
    text += '\'';
    text.append(name);
    text += '\'';
    return text;
}

std::string expectedList() {
    std::string list;
    for (const CommandSpec& spec : kCommands) {
        list += (list.empty() ? "" : ", ") + std::string(spec.name);
    }
    return list;
}

std::optional<double> parseNumber(const std::string& text) {
    double value = 0;
    const char* end = text.data() + text.size();
    const auto [rest, error] = std::from_chars(text.data(), end, value);
    if (error != std::errc() || rest != end || !std::isfinite(value)) {
        return std::nullopt;
    }
    return value;
}

class LineParser {
public:
    LineParser(std::shared_ptr<const std::string> file, const std::filesystem::path& folder)
        : file_(std::move(file)), folder_(folder) {}

    // The command of one non-empty line, or an error message already located.
    Result<ScriptCommand> parse(const std::vector<Word>& words, std::uint32_t line) {
        line_ = line;
        const CommandSpec* spec = nullptr;
        for (const CommandSpec& candidate : kCommands) {
            if (words[0].text == candidate.name) {
                spec = &candidate;
            }
        }
        if (spec == nullptr) {
            return located(words[0], "unknown script command " + singleQuoted(words[0].text) +
                                         " (expected " + expectedList() + ")");
        }
        ScriptCommand command;
        command.kind = spec->kind;
        command.location = locationOf(words[0]);
        const int count = static_cast<int>(words.size()) - 1;
        if (count < spec->minimum || count > spec->maximum) {
            return located(words[0], singleQuoted(spec->name) + " expects " + arityText(*spec));
        }
        for (std::size_t i = 1; i < words.size(); ++i) {
            command.words.push_back(words[i].text);
        }
        return readArguments(*spec, words, std::move(command));
    }

private:
    static std::string arityText(const CommandSpec& spec) {
        const char* what = spec.arguments == Arguments::Numbers ? "number" : "argument";
        std::string text = std::to_string(spec.minimum);
        if (spec.maximum != spec.minimum) {
            text += " or " + std::to_string(spec.maximum);
        }
        return text + " " + what + (spec.maximum == 1 ? "" : "s");
    }

    Result<ScriptCommand> readArguments(const CommandSpec& spec, const std::vector<Word>& words,
                                        ScriptCommand command) {
        if (spec.arguments == Arguments::Numbers) {
            for (std::size_t i = 1; i < words.size(); ++i) {
                std::optional<double> number = parseNumber(words[i].text);
                if (!number) {
                    return located(words[i], singleQuoted(spec.name) + " expects a number, got " +
                                                 singleQuoted(words[i].text));
                }
                command.numbers.push_back(*number);
            }
            if (spec.kind == ScriptCommandKind::Frames &&
                (command.numbers[0] < 1 || command.numbers[0] > 1e6 ||
                 command.numbers[0] != std::floor(command.numbers[0]))) {
                return located(words[1], "'frames' expects a whole number in 1..1000000");
            }
        } else if (spec.arguments == Arguments::Paths || spec.arguments == Arguments::Edit) {
            command.paths.push_back(absolute(words[1].text));
        }
        if (spec.kind == ScriptCommandKind::Mode && words[1].text != "orbit" &&
            words[1].text != "fly" && words[1].text != "walk") {
            return located(words[1],
                           "'mode' expects orbit, fly or walk, got " + singleQuoted(words[1].text));
        }
        if (spec.kind == ScriptCommandKind::Compare) {
            return readCompare(words, std::move(command));
        }
        if (spec.kind == ScriptCommandKind::Layer) {
            if (words[1].text != "colour" && words[1].text != "vegetation" &&
                words[1].text != "atmosphere") {
                return located(words[1], "'layer' expects colour, vegetation or atmosphere, got " +
                                             singleQuoted(words[1].text));
            }
            if (words[2].text != "on" && words[2].text != "off") {
                return located(words[2],
                               "'layer' expects on or off, got " + singleQuoted(words[2].text));
            }
        }
        if (spec.kind == ScriptCommandKind::Time) {
            Result<DateTime> time = DateTime::parse(words[1].text);
            Result<double> seconds = time ? time->unixSeconds() : Result<double>(time.error());
            if (!seconds) {
                return located(words[1], seconds.error().message);
            }
            command.unixSeconds = seconds.value();
        }
        return command;
    }

    Result<ScriptCommand> readCompare(const std::vector<Word>& words, ScriptCommand command) {
        const std::string& mode = words[1].text;
        if (mode == "off") {
            if (words.size() != 2) {
                return located(words[2], "'compare off' takes no more arguments");
            }
            return command;
        }
        if (mode != "swipe" && mode != "blend" && mode != "side_by_side" && mode != "difference") {
            return located(words[1],
                           "'compare' expects off, swipe, blend, side_by_side or difference, got " +
                               singleQuoted(mode));
        }
        if (words.size() < 3) {
            return located(words[1], "'compare " + mode + "' needs the scenario to compare with");
        }
        command.numbers.push_back(0.5);
        if (words.size() == 4) {
            std::optional<double> amount = parseNumber(words[3].text);
            if (!amount || *amount < 0 || *amount > 1) {
                return located(words[3], "'compare' expects an amount in 0..1, got " +
                                             singleQuoted(words[3].text));
            }
            command.numbers[0] = *amount;
        }
        return command;
    }

    std::filesystem::path absolute(const std::string& text) const {
        const std::filesystem::path path(text);
        return path.is_absolute() ? path : folder_ / path;
    }

    SourceLocation locationOf(const Word& word) const {
        SourceLocation location;
        location.file = file_;
        location.line = line_;
        location.column = word.column;
        location.length = static_cast<std::uint32_t>(word.text.size());
        return location;
    }

    Error located(const Word& word, const std::string& message) const {
        return Error{locationOf(word).toString() + ": " + message};
    }

    std::shared_ptr<const std::string> file_;
    std::filesystem::path folder_;
    std::uint32_t line_ = 0;
};

}  // namespace

Result<std::vector<ScriptCommand>> ViewerScript::parse(std::string_view text,
                                                       const std::string& file,
                                                       const std::filesystem::path& folder) {
    LineParser parser(std::make_shared<const std::string>(file), folder);
    std::vector<ScriptCommand> commands;
    std::uint32_t lineNumber = 0;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        const std::string_view line = text.substr(start, end - start);
        ++lineNumber;
        std::uint32_t errorColumn = 0;
        Result<std::vector<Word>> words = splitLine(line, errorColumn);
        if (!words) {
            return Error{file + ":" + std::to_string(lineNumber) + ":" +
                         std::to_string(errorColumn) + ": " + words.error().message};
        }
        if (!words->empty()) {
            Result<ScriptCommand> command = parser.parse(words.value(), lineNumber);
            if (!command) {
                return command.error();
            }
            commands.push_back(std::move(command.value()));
        }
        start = end + 1;
    }
    return commands;
}

Result<std::vector<ScriptCommand>> ViewerScript::load(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        return Error{file.string() + ": cannot read the script file"};
    }
    std::ostringstream text;
    text << in.rdbuf();
    std::error_code error;
    std::filesystem::path folder = std::filesystem::absolute(file, error).parent_path();
    return parse(text.str(), file.string(), folder);
}

const char* ViewerScript::name(ScriptCommandKind kind) {
    for (const CommandSpec& spec : kCommands) {
        if (spec.kind == kind) {
            return spec.name;
        }
    }
    return "?";
}

}  // namespace sylva
