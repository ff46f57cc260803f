#include "sylva/render/batch/VideoEncoder.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

namespace sylva::render {

std::string VideoEncoder::findOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::stringstream folders(path ? path : "");
    std::string folder;
    while (std::getline(folders, folder, ':')) {
        const std::filesystem::path candidate =
            std::filesystem::path(folder.empty() ? "." : folder) / program;
        if (::access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate)) {
            return candidate.string();
        }
    }
    return {};
}

int VideoEncoder::run(const std::vector<std::string>& arguments, const std::filesystem::path& log) {
    const pid_t child = ::fork();
    if (child < 0) {
        return -1;
    }
    if (child == 0) {
        if (FILE* out = std::fopen(log.c_str(), "w")) {
            ::dup2(::fileno(out), STDOUT_FILENO);
            ::dup2(::fileno(out), STDERR_FILENO);
        }
        std::vector<char*> argv;
        for (const std::string& argument : arguments) {
            argv.push_back(const_cast<char*>(argument.c_str()));
        }
        argv.push_back(nullptr);
        ::execvp(argv[0], argv.data());
        ::_exit(127);
    }
    int status = 0;
    while (::waitpid(child, &status, 0) < 0) {
        if (errno != EINTR) {
            return -1;
        }
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

Status VideoEncoder::encode(const std::filesystem::path& frames,
                            const std::filesystem::path& output, double framesPerSecond) const {
    const std::filesystem::path folder = output.has_parent_path() ? output.parent_path() : ".";
    const std::filesystem::path temporary =
        folder / (".sylva-" + std::to_string(::getpid()) + "-" + output.filename().string());
    const std::filesystem::path log = frames / "ffmpeg.log";
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.6g", framesPerSecond);
    const int status = run({ffmpeg_,
                            "-nostdin",
                            "-y",
                            "-loglevel",
                            "error",
                            "-framerate",
                            rate,
                            "-start_number",
                            "0",
                            "-i",
                            (frames / "%05d.png").string(),
                            "-c:v",
                            "libx264",
                            "-pix_fmt",
                            "yuv420p",
                            "-vf",
                            "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                            "-movflags",
                            "+faststart",
                            "-f",
                            "mp4",
                            temporary.string()},
                           log);
    std::error_code error;
    if (status != 0) {
        std::ifstream stream(log);
        std::string text((std::istreambuf_iterator<char>(stream)), {});
        while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) {
            text.pop_back();
        }
        std::filesystem::remove(temporary, error);
        return Error{output.string() + ": ffmpeg failed (exit " + std::to_string(status) + ")" +
                     (text.empty() ? std::string() : ": " + text)};
    }
    std::filesystem::rename(temporary, output, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        return Error{output.string() + ": cannot move the finished video into place"};
    }
    return {};
}

}  // namespace sylva::render
