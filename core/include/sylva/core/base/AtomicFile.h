// Atomic file writes: the bytes go to a temporary file (".sylva-<pid>-<n>-<name>") in
// the target's folder, which is renamed over the target only when complete, so an
// interrupted or failed write never leaves a partial file under the final name and
// never destroys the previous one. The folder must exist.
#pragma once

#include <filesystem>
#include <string_view>

#include "sylva/core/base/Result.h"

namespace sylva {

// On failure the temporary file is removed and the error holds the reason only
// (callers name the file in their own words).
Status writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace sylva
