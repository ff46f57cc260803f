// ScriptPlayer: runs the commands of a ViewerScript on a ViewerSession (docs/viewer.md,
// "Scripts"): navigation and scenario/time changes act as the keys do, `frames` and
// `wait-tiles` render interactive frames (polling the hot-reload watch before each),
// `screenshot` renders with every tile waited for. Private to render/viewer.
#pragma once

#include <functional>
#include <vector>

#include "ViewerSession.h"
#include "sylva/core/scene/ViewerScript.h"

namespace sylva::render {

class ScriptPlayer {
public:
    // `showFrame` puts each rendered frame on the screen (a no-op without a window).
    ScriptPlayer(ViewerSession& session, std::function<void()> showFrame);

    // Runs the commands in order. Fails with the first failing command's error, prefixed
    // with its location ("run.script:4:1: screenshot: ..."); sets quit() on `quit`.
    Status run(const std::vector<ScriptCommand>& commands);
    bool quit() const { return quit_; }

private:
    Status execute(const ScriptCommand& command);
    Status renderFrames(int count);
    Status waitTiles(double timeoutSeconds);
    static Status editFile(const std::filesystem::path& file, const std::string& search,
                           const std::string& replace);
    static Status touchFile(const std::filesystem::path& file);

    ViewerSession& session_;
    std::function<void()> showFrame_;
    bool quit_ = false;
};

}  // namespace sylva::render
