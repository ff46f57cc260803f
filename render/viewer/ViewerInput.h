// ViewerInput: the keyboard and mouse of the viewer's GLFW window, read once per frame
// (docs/viewer.md lists the conventions; ViewerHelp.h has the overlay text). Held keys
// and mouse drags become a continuous Motion scaled by the frame time; single presses
// (mode, camera 1..9, scenario, time, help, save, pick, quit) become Commands.
// Private to render/viewer. Installs GLFW callbacks on the window and owns them until
// destroyed (one ViewerInput per window); main thread only.
#pragma once

#include <functional>
#include <vector>

namespace sylva::render {

// One frame's continuous movement. Translations are fractions of the travel speed per
// second times the frame's seconds (the viewer multiplies by its speed); rotations are
// radians; `zoom` is the wheel's steps (positive: closer).
struct Motion {
    double forward = 0, right = 0, up = 0;
    double yaw = 0, pitch = 0;    // from the arrows and a left-button drag
    double dragX = 0, dragY = 0;  // pixels dragged with the left button this frame
    double zoom = 0;
    bool any() const {
        return forward != 0 || right != 0 || up != 0 || yaw != 0 || pitch != 0 || dragX != 0 ||
               dragY != 0 || zoom != 0;
    }
};

enum class ViewerCommand {
    CycleMode,     // Tab
    Camera,        // 1..9: `number` is the camera index (0-based)
    NextScenario,  // N
    TimeBack,      // T: one hour earlier
    TimeForward,   // Y: one hour later
    ToggleHelp,    // H or F1
    SaveCamera,    // P
    Pick,          // right click: `x`, `y` the pixel in the framebuffer
    Quality,       // [ and ]: `number` -1 or +1
    Quit,          // Escape
};

struct ViewerEvent {
    ViewerCommand command = ViewerCommand::Quit;
    int number = 0;
    double x = 0, y = 0;
};

class ViewerInput {
public:
    explicit ViewerInput(void* window);  // GLFWwindow*
    ~ViewerInput();
    ViewerInput(const ViewerInput&) = delete;
    ViewerInput& operator=(const ViewerInput&) = delete;

    // The movement since the last call, for a frame of `seconds`. Shift makes
    // translations 5× faster.
    Motion motion(double seconds);
    // The presses since the last call, in order.
    std::vector<ViewerEvent> takeEvents();
    // While these answer true (a UI panel has the pointer or a text field), mouse or
    // keyboard input is not navigation.
    void setCaptures(std::function<bool()> mouse, std::function<bool()> keyboard);

    // GLFW callbacks (public for the C trampolines in ViewerInput.cpp).
    void onKey(int key, int action, int mods);
    void onButton(int button, int action);
    void onCursor(double x, double y);
    void onScroll(double y);

private:
    void* window_;
    std::function<bool()> mouseCaptured_;
    std::function<bool()> keyboardCaptured_;
    std::vector<ViewerEvent> events_;
    bool dragging_ = false;
    double cursorX_ = 0, cursorY_ = 0;
    double dragX_ = 0, dragY_ = 0;
    double scroll_ = 0;
};

}  // namespace sylva::render
