// ViewerScript: the line-based input language of `sylva view --script FILE` (docs/viewer.md),
// used by tests, demos and the viewer benchmark to replay a session: go to a camera, fly,
// change scenario and time, wait for tiles, take screenshots, save cameras, edit files.
//
// One command per line: a command word, then arguments separated by spaces; an argument
// with spaces is written in double quotes (\" and \\ escape inside). `#` starts a comment.
// Every command's arity and argument types are checked when the script is parsed, so a
// bad script fails before the viewer opens, with a located error "file:line:col: ...".
// Relative paths (screenshot, edit, touch) are made absolute against the script's folder.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/base/SourceLocation.h"

namespace sylva {

enum class ScriptCommandKind {
    Camera,      // camera NAME: go to a camera block of the project
    Scenario,    // scenario NAME
    Time,        // time 2024-06-21T16:00-03:00 (date, time and zone): the sun of that instant
    Mode,        // mode orbit|fly|walk
    Fly,         // fly FORWARD RIGHT UP: metres along the camera's axes (walk: along the ground)
    Turn,        // turn YAW PITCH: degrees, yaw to the right, pitch up
    Orbit,       // orbit NORTH EAST: degrees of latitude and longitude over the globe
    WaitTiles,   // wait-tiles: render until no wanted tile is pending
    Frames,      // frames N: render N frames
    Screenshot,  // screenshot PATH: render with every tile waited for, write a PNG
    SaveCamera,  // save-camera NAME [VIEWS]: write a camera block (and list it in VIEWS)
    Edit,        // edit FILE SEARCH REPLACE: replace the first occurrence in FILE
    Touch,       // touch FILE: set FILE's modification time to now
    Compare,     // compare off | compare swipe|blend|side_by_side|difference SCENARIO [AMOUNT]
    Layer,       // layer colour|vegetation|atmosphere on|off
    Quit,        // quit
};

struct ScriptCommand {
    ScriptCommandKind kind = ScriptCommandKind::Quit;
    SourceLocation location;                   // the command word
    std::vector<std::string> words;            // arguments as written (quotes removed)
    std::vector<double> numbers;               // Fly, Turn, Orbit: the numbers; Frames: N;
                                               // Compare: the amount (0.5 when not written)
    std::vector<std::filesystem::path> paths;  // Screenshot, Edit, Touch: absolute path
    double unixSeconds = 0;                    // Time: the instant
};

class ViewerScript {
public:
    // Parses `text` (named `file` in messages; relative paths resolve against `folder`).
    // The first error ends parsing: "file:line:col: unknown script command 'jump'
    // (expected camera, scenario, ...)" or "...: 'fly' expects 3 numbers".
    static Result<std::vector<ScriptCommand>> parse(std::string_view text, const std::string& file,
                                                    const std::filesystem::path& folder);
    // Reads and parses a script file; an unreadable file is an error naming it.
    static Result<std::vector<ScriptCommand>> load(const std::filesystem::path& file);

    // The command word of a kind ("save-camera").
    static const char* name(ScriptCommandKind kind);
};

}  // namespace sylva
