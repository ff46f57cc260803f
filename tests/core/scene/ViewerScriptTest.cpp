// ViewerScript: every command parsed with its arguments, quoting, comments, relative
// paths against the script's folder, and located errors (exact messages) for unknown
// commands, wrong arity, bad numbers, modes and times.
#include "sylva/core/scene/ViewerScript.h"

#include <gtest/gtest.h>

namespace sylva {
namespace {

Result<std::vector<ScriptCommand>> parse(const std::string& text) {
    return ViewerScript::parse(text, "run.script", "/scripts");
}

std::string errorOf(const std::string& text) {
    Result<std::vector<ScriptCommand>> result = parse(text);
    EXPECT_FALSE(result);
    return result ? std::string() : result.error().message;
}

TEST(ViewerScript, ParsesEveryCommandWithItsArguments) {
    Result<std::vector<ScriptCommand>> script = parse(
        "# a session\n"
        "camera aircraft\n"
        "scenario dry   # comment after a command\n"
        "time 2024-06-21T16:00-03:00\n"
        "mode walk\n"
        "fly 10 -2.5 3e2\n"
        "turn 25 -5\n"
        "orbit 1 2\n"
        "\n"
        "wait-tiles\n"
        "frames 12\n"
        "screenshot \"shots/a b.png\"\n"
        "save-camera flown check\n"
        "edit /abs/p.sylva \"x = \\\"1\\\"\" y\n"
        "touch data.tif\n"
        "compare swipe dry 0.25\n"
        "compare off\n"
        "layer vegetation off\n"
        "quit\n");
    ASSERT_TRUE(script) << script.error().message;
    const std::vector<ScriptCommand>& c = script.value();
    ASSERT_EQ(c.size(), 17u);
    EXPECT_EQ(c[0].kind, ScriptCommandKind::Camera);
    EXPECT_EQ(c[0].words, std::vector<std::string>{"aircraft"});
    EXPECT_EQ(c[0].location.toString(), "run.script:2:1");
    EXPECT_EQ(c[1].words, std::vector<std::string>{"dry"});
    // 2024-06-21T19:00:00Z.
    EXPECT_DOUBLE_EQ(c[2].unixSeconds, 1718996400.0);
    EXPECT_EQ(c[3].words[0], "walk");
    EXPECT_EQ(c[4].numbers, (std::vector<double>{10, -2.5, 300}));
    EXPECT_EQ(c[5].numbers, (std::vector<double>{25, -5}));
    EXPECT_EQ(c[6].kind, ScriptCommandKind::Orbit);
    EXPECT_EQ(c[7].kind, ScriptCommandKind::WaitTiles);
    EXPECT_EQ(c[8].numbers, std::vector<double>{12});
    EXPECT_EQ(c[9].paths[0], std::filesystem::path("/scripts/shots/a b.png"));
    EXPECT_EQ(c[10].words, (std::vector<std::string>{"flown", "check"}));
    EXPECT_EQ(c[11].paths[0], std::filesystem::path("/abs/p.sylva"));
    EXPECT_EQ(c[11].words[1], "x = \"1\"");
    EXPECT_EQ(c[11].words[2], "y");
    EXPECT_EQ(c[12].paths[0], std::filesystem::path("/scripts/data.tif"));
    EXPECT_EQ(c[13].kind, ScriptCommandKind::Compare);
    EXPECT_EQ(c[13].numbers, std::vector<double>{0.25});
    EXPECT_EQ(c[14].words, std::vector<std::string>{"off"});
    EXPECT_EQ(c[15].words, (std::vector<std::string>{"vegetation", "off"}));
    EXPECT_EQ(c[16].kind, ScriptCommandKind::Quit);
    EXPECT_STREQ(ViewerScript::name(ScriptCommandKind::SaveCamera), "save-camera");
}

TEST(ViewerScript, UnknownCommandsAreLocated) {
    EXPECT_EQ(errorOf("camera a\n  jump 3\n"),
              "run.script:2:3: unknown script command 'jump' (expected camera, scenario, time, "
              "mode, fly, turn, orbit, wait-tiles, frames, screenshot, save-camera, edit, touch, "
              "compare, layer, quit)");
}

TEST(ViewerScript, ArgumentErrorsAreLocated) {
    EXPECT_EQ(errorOf("fly 1 2\n"), "run.script:1:1: 'fly' expects 3 numbers");
    EXPECT_EQ(errorOf("\nturn 1 north\n"), "run.script:2:8: 'turn' expects a number, got 'north'");
    EXPECT_EQ(errorOf("frames 2.5\n"),
              "run.script:1:8: 'frames' expects a whole number in 1..1000000");
    EXPECT_EQ(errorOf("frames 0\n"),
              "run.script:1:8: 'frames' expects a whole number in 1..1000000");
    EXPECT_EQ(errorOf("mode swim\n"),
              "run.script:1:6: 'mode' expects orbit, fly or walk, got 'swim'");
    EXPECT_EQ(errorOf("save-camera\n"), "run.script:1:1: 'save-camera' expects 1 or 2 arguments");
    EXPECT_EQ(errorOf("quit now\n"), "run.script:1:1: 'quit' expects 0 arguments");
    EXPECT_EQ(errorOf("compare wipe dry\n"),
              "run.script:1:9: 'compare' expects off, swipe, blend, side_by_side or difference, "
              "got 'wipe'");
    EXPECT_EQ(errorOf("compare blend\n"),
              "run.script:1:9: 'compare blend' needs the scenario to compare with");
    EXPECT_EQ(errorOf("compare blend dry 1.5\n"),
              "run.script:1:19: 'compare' expects an amount in 0..1, got '1.5'");
    EXPECT_EQ(errorOf("layer trees off\n"),
              "run.script:1:7: 'layer' expects colour, vegetation or atmosphere, got 'trees'");
    EXPECT_EQ(errorOf("screenshot \"a.png\n"), "run.script:1:12: unterminated quoted argument");
    // A time without a zone cannot place the sun.
    const std::string time = errorOf("time 2024-06-21T16:00\n");
    EXPECT_EQ(time.rfind("run.script:1:6: ", 0), 0u) << time;
    EXPECT_NE(time.find("zone"), std::string::npos) << time;
}

TEST(ViewerScript, AMissingFileIsNamed) {
    Result<std::vector<ScriptCommand>> script = ViewerScript::load("/nonexistent/run.script");
    ASSERT_FALSE(script);
    EXPECT_EQ(script.error().message, "/nonexistent/run.script: cannot read the script file");
}

}  // namespace
}  // namespace sylva
