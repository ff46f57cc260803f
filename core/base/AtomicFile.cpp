#include "sylva/core/base/AtomicFile.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

namespace sylva {

Status writeFileAtomically(const std::filesystem::path& path, std::string_view bytes) {
    static std::atomic<unsigned> counter{0};
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
    const std::filesystem::path temporary =
        folder / (".sylva-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
                  path.filename().string());
    std::error_code ignored;
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) {
            return Error{"cannot create " + temporary.string() + ": " + std::strerror(errno)};
        }
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        out.flush();
        if (!out) {
            std::filesystem::remove(temporary, ignored);
            return Error{"write failed (disk full?)"};
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, ignored);
        return Error{"cannot move the finished file into place: " + error.message()};
    }
    return {};
}

}  // namespace sylva
