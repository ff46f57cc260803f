// CameraBlockEditor: writes a viewer camera back into a project file as a `camera NAME
// { ... }` block (position with its height above the ellipsoid, heading, pitch, roll,
// fov), so `sylva render` renders exactly the view the viewer showed (docs/viewer.md).
// A camera block of that name is replaced (its own comments go with it), otherwise the
// block is appended; with a views block named, the camera is added to its `cameras`
// list (created when missing). The result goes through the Formatter, so every other
// comment survives and the layout is canonical; the file is replaced atomically.
//
// Errors (the text has syntax errors, no views block of that name, a name that is not an
// identifier, an unreadable or unwritable file) name the file and leave it untouched.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "sylva/core/base/Result.h"
#include "sylva/core/scene/Camera.h"

namespace sylva::dsl {

class CameraBlockEditor {
public:
    // The block text of `camera` (angles in degrees with 1e-8° steps, height in metres
    // with 0.1 mm steps: far below a pixel at any distance the viewer renders).
    static std::string blockText(const std::string& name, const Camera& camera);

    // `text` (named `displayName` in errors) with the camera block set and, when `views`
    // is not empty, listed in that views block; formatted.
    static Result<std::string> withCamera(std::string_view text, const std::string& displayName,
                                          const std::string& name, const Camera& camera,
                                          const std::string& views = {});

    // withCamera on a file, written back atomically.
    static Status save(const std::filesystem::path& file, const std::string& name,
                       const Camera& camera, const std::string& views = {});
};

}  // namespace sylva::dsl
