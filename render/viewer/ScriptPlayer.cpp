#include "ScriptPlayer.h"

#include <chrono>
#include <fstream>
#include <sstream>

#include "sylva/core/base/AtomicFile.h"

namespace sylva::render {
namespace {

constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

ComparisonMode comparisonMode(const std::string& word) {
    return word == "swipe"          ? ComparisonMode::Swipe
           : word == "blend"        ? ComparisonMode::Blend
           : word == "side_by_side" ? ComparisonMode::SideBySide
           : word == "difference"   ? ComparisonMode::Difference
                                    : ComparisonMode::None;
}

}  // namespace

ScriptPlayer::ScriptPlayer(ViewerSession& session, std::function<void()> showFrame)
    : session_(session), showFrame_(std::move(showFrame)) {}

Status ScriptPlayer::run(const std::vector<ScriptCommand>& commands) {
    for (const ScriptCommand& command : commands) {
        std::fprintf(session_.log(), "script %s: %s", command.location.toString().c_str(),
                     ViewerScript::name(command.kind));
        for (const std::string& word : command.words) {
            std::fprintf(session_.log(), " %s", word.c_str());
        }
        std::fprintf(session_.log(), "\n");
        std::fflush(session_.log());
        if (Status done = execute(command); !done) {
            return Error{command.location.toString() + ": " + ViewerScript::name(command.kind) +
                         ": " + done.error().message};
        }
        if (quit_) {
            break;
        }
    }
    return {};
}

Status ScriptPlayer::execute(const ScriptCommand& command) {
    const std::vector<double>& n = command.numbers;
    switch (command.kind) {
        case ScriptCommandKind::Camera:
            return session_.goToCamera(command.words[0]);
        case ScriptCommandKind::Scenario:
            return session_.setScenario(command.words[0]);
        case ScriptCommandKind::Time:
            session_.setTime(command.unixSeconds);
            return {};
        case ScriptCommandKind::Mode:
            session_.setMode(command.words[0] == "orbit" ? NavigationMode::Orbit
                             : command.words[0] == "fly" ? NavigationMode::Fly
                                                         : NavigationMode::Walk);
            return {};
        case ScriptCommandKind::Fly:
            session_.move(n[0], n[1], n[2]);
            return {};
        case ScriptCommandKind::Turn:
            session_.turn(n[0] * kRadiansPerDegree, n[1] * kRadiansPerDegree);
            return {};
        case ScriptCommandKind::Orbit:
            session_.orbit(n[0] * kRadiansPerDegree, n[1] * kRadiansPerDegree);
            return {};
        case ScriptCommandKind::WaitTiles:
            return waitTiles(600.0);
        case ScriptCommandKind::Frames:
            return renderFrames(static_cast<int>(n[0]));
        case ScriptCommandKind::Screenshot:
            return session_.screenshot(command.paths[0]);
        case ScriptCommandKind::SaveCamera:
            return session_.saveCamera(command.words[0],
                                       command.words.size() > 1 ? command.words[1] : "");
        case ScriptCommandKind::Edit:
            return editFile(command.paths[0], command.words[1], command.words[2]);
        case ScriptCommandKind::Touch:
            return touchFile(command.paths[0]);
        case ScriptCommandKind::Compare:
            return session_.setComparison(comparisonMode(command.words[0]),
                                          command.words.size() > 1 ? command.words[1] : "",
                                          command.numbers.empty() ? 0.5 : command.numbers[0]);
        case ScriptCommandKind::Layer:
            return session_.setLayer(command.words[0], command.words[1] == "on");
        case ScriptCommandKind::Quit:
            quit_ = true;
            return {};
    }
    return {};
}

Status ScriptPlayer::renderFrames(int count) {
    for (int i = 0; i < count; ++i) {
        session_.pollFiles();
        // A failed frame is shown and printed by the session; the script goes on.
        (void)session_.renderFrame(false);
        showFrame_();
    }
    return {};
}

Status ScriptPlayer::waitTiles(double timeoutSeconds) {
    const auto start = std::chrono::steady_clock::now();
    do {
        session_.pollFiles();
        if (Status rendered = session_.renderFrame(false); !rendered) {
            return rendered;
        }
        showFrame_();
        if (!session_.report().pending) {
            return {};
        }
        (void)session_.waitForTiles(1.0);  // a tile arrived, or half a second passed
    } while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() <
             timeoutSeconds);
    return Error{"tiles still pending after " + std::to_string(static_cast<int>(timeoutSeconds)) +
                 " s"};
}

Status ScriptPlayer::editFile(const std::filesystem::path& file, const std::string& search,
                              const std::string& replace) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        return Error{file.string() + ": cannot read the file"};
    }
    std::ostringstream text;
    text << in.rdbuf();
    std::string content = text.str();
    const std::size_t at = content.find(search);
    if (search.empty() || at == std::string::npos) {
        return Error{file.string() + ": '" + search + "' does not occur in the file"};
    }
    content.replace(at, search.size(), replace);
    if (Status written = writeFileAtomically(file, content); !written) {
        return Error{file.string() + ": " + written.error().message};
    }
    return {};
}

Status ScriptPlayer::touchFile(const std::filesystem::path& file) {
    std::error_code error;
    std::filesystem::last_write_time(file, std::filesystem::file_time_type::clock::now(), error);
    if (error) {
        return Error{file.string() + ": cannot touch the file: " + error.message()};
    }
    return {};
}

}  // namespace sylva::render
