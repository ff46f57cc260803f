// ViewerPanels: the viewer's Dear ImGui panels (Debian libimgui-dev, its GLFW and
// OpenGL 3 back ends) drawn over the frame in the window: View (scenario chooser,
// navigation mode, project cameras), Compare (a second scenario as swipe, blend, side by
// side or CIEDE2000 difference through core/image ImageComparison, with the split or
// amount), Layers (terrain colour, vegetation, atmosphere), Time (day of year and UTC
// hour: the sun moves as the slider does), Vegetation quality, Stats (the status lines)
// and the last pick. Changes go to the ViewerSession, which redraws when needed.
// Private to render/viewer.
//
// Ownership: creates the ImGui context and installs its GLFW callbacks after (and
// chained to) ViewerInput's, so it must be created after and destroyed before the
// ViewerInput of the same window; needs the window's context current.
#pragma once

#include <string>

#include "ViewerSession.h"

namespace sylva::render {

class ViewerPanels {
public:
    explicit ViewerPanels(void* window);  // GLFWwindow*
    ~ViewerPanels();
    ViewerPanels(const ViewerPanels&) = delete;
    ViewerPanels& operator=(const ViewerPanels&) = delete;

    // Whether the panels take the mouse or keyboard now (the navigation then ignores it).
    bool wantsMouse() const;
    bool wantsKeyboard() const;

    // Builds and draws the panels into the default framebuffer, applying the user's
    // changes to `session`; `message` is the last pick or save (shown in Stats).
    void draw(ViewerSession& session, const std::string& message);

private:
    void viewPanel(ViewerSession& session);
    void comparePanel(ViewerSession& session);
    void layersAndTimePanel(ViewerSession& session);
    void statsPanel(const ViewerSession& session, const std::string& message);

    int comparisonMode_ = 0;  // index into the mode names
    int otherScenario_ = 0;
    float amount_ = 0.5f;
    bool timeOn_ = false;
    int dayOfYear_ = 172;  // 21 June 2024
    float hourUtc_ = 12.0f;
    float quality_ = 1.0f;
};

}  // namespace sylva::render
