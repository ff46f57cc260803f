// VideoEncoder: encodes the numbered PNG frames of a path series into an MP4 with the
// `ffmpeg` program (H.264 through libx264, yuv420p, the path's frame rate; odd sizes
// padded by one pixel, which yuv420p needs). ffmpeg runs as a child process without a
// shell; its messages go to a log beside the frames and into the error when it fails.
// The video is written to a temporary file in the target folder and renamed into place,
// so no partial video ever carries the final name.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"

namespace sylva::render {

class VideoEncoder {
public:
    // `ffmpeg`: the program to run (a path, or a name looked up on PATH by execvp).
    explicit VideoEncoder(std::string ffmpeg) : ffmpeg_(std::move(ffmpeg)) {}

    // The full path of `program` in the folders of $PATH (executable regular files only),
    // or empty when there is none.
    static std::string findOnPath(const std::string& program);

    // Encodes `frames`/00000.png, 00001.png, ... at `framesPerSecond` into `output`
    // (ffmpeg's log: `frames`/ffmpeg.log). Errors name the output and carry ffmpeg's exit
    // status and messages; the temporary file is removed then.
    Status encode(const std::filesystem::path& frames, const std::filesystem::path& output,
                  double framesPerSecond) const;

private:
    // Runs `arguments` (no shell) with stdout and stderr into `log`; the exit status, or
    // -1 when the program could not be started or did not exit normally.
    static int run(const std::vector<std::string>& arguments, const std::filesystem::path& log);

    std::string ffmpeg_;
};

}  // namespace sylva::render
